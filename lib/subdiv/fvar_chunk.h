// Codec of the FVSF chunk (formats/limn.md, "Smooth face-varying UV surface"): the surface of a
// mesh's UV channel under a face-varying rule other than "all" (fvar_surface.h), in the form the
// GPU reads it (FaceVaryingSurface::Gpu, shaders/fvar_eval.glsl), so that a runtime without
// limn's C++ (the WebGPU one in web/) can draw smooth UVs without building their tables.
// limn-tables writes it beside TBLS; it depends on the UV values as well as the topology, and
// says which (two hashes), so a stale one is refused.
#pragma once

#include "container/container.h"
#include "mesh/mesh.h"
#include "subdiv/fvar_surface.h"

#include <cstdint>

namespace limn {

inline constexpr FourCC kFvarSurfaceChunk{"FVSF"};
inline constexpr uint32_t kFvarSurfaceChunkVersion = 3;

struct FvarSurfaceChunk {
    uint32_t depth = 0;         // of the geometry's tables (TBLS): the same lattice of drawn points
    uint64_t topologyHash = 0;  // topologyHash(mesh, options), as TBLS's
    uint64_t uvHash = 0;        // fvarUVHash(mesh): the UV values and their indices
    uint32_t ptexCount = 0;     // nodes[0, ptexCount) are the roots, one per ptex face
    uint32_t elementCount = 0;  // records.size() / 9
    // Compact (FaceVaryingSurface::compactGpu): faces with a per-valence basis are smooth faces;
    // expandSmoothFaces(surface) gives the records the GPU draws. Version 1 has none.
    FaceVaryingSurface::Gpu surface;
};

// The hash of a mesh's UVs (values, then per-corner indices) that FVSF records.
uint64_t fvarUVHash(const Mesh& mesh);

// For `mesh` with UVs and `options.fvar` other than All: its UV surface at the tables' depth
// and irregular levels K (their irregular faces' surface, docs/irregular.md).
FvarSurfaceChunk makeFvarSurfaceChunk(const Mesh& mesh, const SchemeOptions& options, uint32_t depth,
                                      uint32_t irregularLevels, Warnings& warnings);

Chunk encodeFvarSurfaceChunk(const FvarSurfaceChunk& fvar);

// Checks every count, node and record (a node is a hole, a leaf naming an element, or the first
// of four children after itself; records finite, their domains in [0, 1]). With `mesh`, also that
// it was made from this mesh's topology, options and UVs, and has a root per ptex face. Throws
// Error(BadInput) naming chunk FVSF.
FvarSurfaceChunk decodeFvarSurfaceChunk(const Chunk& chunk, const Mesh* mesh, const SchemeOptions* options);

// Checks that every point `tables` (the geometry's, the ones the chunk was made with) draws finds
// a UV element: no walk toward a patch or irregular face's domain meets a hole. Throws
// Error(BadInput) naming chunk FVSF.
void checkFvarSurfaceCoverage(const FvarSurfaceChunk& fvar, const Tables& tables);

} // namespace limn
