// The subdivision surface as the GPU draws it, prepared on the CPU once from the tables (topology
// only; control points are uploaded per frame): the stencil tables of every level concatenated
// for the face/edge/vertex passes (paper 000, 4.2), the limit stencils (4.4), the patches and
// irregular faces, and the watertight tessellation (lib/tess) that the vertex stage evaluates
// (4.3). Layouts mirror the GLSL structs in shaders/surface_eval.glsl.
#pragma once

#include "mesh/mesh.h"
#include "render/camera.h"
#include "seams/seams.h"
#include "subdiv/tables.h"
#include "tess/edge_pieces.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace limn::render {

struct GpuPatch { // mirrors Patch in surface_eval.glsl
    uint32_t cv[16];
    uint32_t ptex;
    float u0, v0, size;
    uint32_t levelBoundary; // level | boundary << 8 | crease << 16
    float sharpness;        // of a single-crease patch's crease
    uint32_t pad[2];
};
static_assert(sizeof(GpuPatch) == 96);

struct GpuIrregularFace { // mirrors IrregularFace in surface_eval.glsl
    uint32_t corner[4];
    uint32_t ptex;
    float u0, v0, size;
};
static_assert(sizeof(GpuIrregularFace) == 32);

struct GpuTessVertex {   // mirrors the uvec4 in surface.vert
    uint32_t element;    // patch index, or patch count + irregular face index
    uint32_t st;         // s | t << 16, in 1/32768
    float u, v;          // texture coordinates in the element's own face chart (0 without UVs)
};
static_assert(sizeof(GpuTessVertex) == 16);

// One level's three passes: rows [firstRow, firstRow + count) of their tables write vertices
// [firstOut, firstOut + count).
struct LevelPasses {
    uint32_t level;
    uint32_t faceFirstOut, faceFirstRow, faceCount;
    uint32_t edgeFirstOut, edgeFirstRow, edgeCount;
    uint32_t vertexFirstOut, vertexFirstRow, vertexCount;
};

struct SubdivisionDraw {
    uint32_t baseVertices = 0, totalVertices = 0;
    std::vector<uint32_t> faceStarts, faceIndices;  // face-point rows of every level
    std::vector<uint32_t> stencilStarts, stencilIndices; // edge- and vertex-point rows
    std::vector<float> stencilWeights;
    std::vector<LevelPasses> levels;
    // Limit points: three tables (position, tangent 1, tangent 2) of limitCount rows each. The
    // pass uploads them in chunks of consecutive rows under this many bytes of indices (uniform
    // tables of catmark_car at depth 5 need 154 MiB: over WebGPU's binding limit in one piece).
    uint32_t limitCount = 0;
    uint64_t limitChunkBytes = uint64_t(128) << 20;
    std::vector<uint32_t> limitStarts, limitIndices;
    std::vector<float> limitWeights;
    std::vector<GpuPatch> patches;
    std::vector<GpuIrregularFace> irregular;
    // The irregular faces' quadtrees (docs/irregular.md): after the patches in the patches
    // buffer, a root node per irregular face (in order), the other nodes, then the sub-patches;
    // after the irregular faces in theirs, the leaves. patchBuffer() and irregularBuffer() are
    // what is uploaded.
    std::vector<GpuPatch> irregularNodes;
    std::vector<GpuIrregularFace> irregularLeaves;
    std::vector<GpuPatch> patchBuffer() const;
    std::vector<GpuIrregularFace> irregularBuffer() const;
    std::vector<GpuTessVertex> tessVertices;
    std::vector<uint32_t> triangles;      // 3 per triangle, into tessVertices
    std::vector<uint32_t> triangleLevels; // per triangle: its element's level, 255 if irregular
    std::vector<uint32_t> wireLines;      // 2 per segment: the element edges, each once
    // Displacement (paper 000, 4.5): per drawn vertex the range of UVs its samples are taken at
    // (sideUVs), and the range of the triangles around its point (for the displaced normals).
    std::vector<glm::uvec2> sideRanges, incidentRanges;
    std::vector<glm::vec2> sideUVs;
    std::vector<uint32_t> incidentTriangles;
    uint32_t stitchedEdges = 0;
    bool hasUVs = false;
    // View-adaptive: no fixed tessellation above, the edge pieces instead.
    bool adaptive = false;
    EdgePieces pieces;
    const Seams* seams = nullptr; // view-adaptive displacement: the seam records (not owned)
    // View-adaptive displacement with smooth UVs: the seam records of seams.h built
    // from the smooth UVs (used instead of *seams when it has elements).
    Seams smoothSeams;
    // View-adaptive smooth UVs: as AdaptiveOptions (empty under rule "all").
    std::vector<glm::vec4> elementDomains, fvarRecords;
    std::vector<uint32_t> fvarNodes;
    float fvarCell = 0;
    bool seamFix = true;
    bool closed = false;    // every edge piece has two sides (no boundary, no holes)
    float orientation = 0;  // sign of the control mesh's signed volume (0: too flat to tell)
    Bounds bounds; // of the control points
};

struct DisplacementPlan {
    const Seams* seams = nullptr; // the SEAM data of these tables
    bool seamFix = true;          // average every face's sample (false: each side its own)
};

// Whether the surface point of `element` at st (GpuTessVertex) is approximate: in an irregular
// face drawn bilinear there (within 2^-K of an extraordinary corner, a leaf of its quadtree, or
// a face without a surface: surface_eval_impl.glsl's irregularPoint), and not one of the
// corners, which are limit points. The same walk as the shader, on the buffers it reads.
bool drawnPointIsApproximate(const SubdivisionDraw& draw, uint32_t element, uint32_t st);

// `tessCap` caps the segments per side of any patch (--tess; rounded down to a power of two).
// Before building it, the fixed tessellation's size is estimated, and one whose index or vertex
// buffer would pass 128 MiB is refused with the estimate and what to do. With `adaptive`, no
// fixed tessellation is built: the edge pieces of the view-adaptive one instead. Vertices on UV seams are split per
// side when the mesh has UVs (texture lookups stay in their chart; positions are shared). With a
// displacement plan, also the sample UVs and the normal neighbourhoods of every vertex.
SubdivisionDraw prepareSubdivision(const Mesh& mesh, const Tables& tables, uint32_t tessCap,
                                   const DisplacementPlan* displacement = nullptr, bool adaptive = false);

// The limit tables cut into chunks of consecutive rows [firstRow, firstRow + rows), each with its
// three tables of `rows` rows back to back (starts rebased to the chunk) and at most
// `maxBytes` / 4 indices (one row more if a single row is larger). Chunks in row order.
struct LimitChunk {
    uint32_t firstRow = 0, rows = 0;
    std::vector<uint32_t> starts, indices;
    std::vector<float> weights;
};
std::vector<LimitChunk> limitChunks(const SubdivisionDraw& draw, uint64_t maxBytes);

// The sign of the mesh's signed volume with these positions (faces fanned from their first
// corner, about the box centre): +1 when Du x Dv points outward, -1 inward, 0 too flat to tell.
float surfaceOrientation(const Mesh& mesh, const std::vector<glm::dvec3>& positions);

} // namespace limn::render
