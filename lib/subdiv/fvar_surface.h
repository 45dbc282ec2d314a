// Smooth face-varying UVs: the UV channel refined with its own value topology, as
// OpenSubdiv does for Sdc::Options::FVarLinearInterpolation modes other than FVAR_LINEAR_ALL.
//
// The channel is treated as a mesh of its own (faceVaryingMesh): one vertex per UV value and
// span of faces around a base vertex, the same faces with UV corners, so UV seams are its
// boundaries; the base mesh's creases, corners and holes carried over; and the UV boundary
// values sharpened into corners exactly where OpenSubdiv's Vtr::FVarLevel sharpens them for the
// mode (completeTopologyFromFaceValues, v3_6_0). limn's own feature-adaptive tables of that mesh,
// with the geometry's depth and irregular levels K, then give its limit surface: a B-spline
// where it is regular, and on its level-N irregular faces the surface the geometry's evaluator
// gives (evaluateIrregular: sub-patches of a quadtree or of a per-valence basis; bilinear only
// within 2^-K of an extraordinary corner, docs/irregular.md). The mesh has the same faces in the
// same order as the base mesh, so the ptex parameterization is shared and the UV at (ptex, u, v)
// is the UV surface's point there.
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables.h"
#include "topology/features.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace limn {

// The UV channel of `mesh` as a mesh whose vertices are UV values (positions (u, v, 0)), for a
// mode other than All. Throws Error(BadInput) without UVs or for non-manifold meshes.
Mesh faceVaryingMesh(const Mesh& mesh, const SchemeOptions& options);

class FaceVaryingSurface {
  public:
    static constexpr size_t kMaxGpuRecordBytes = size_t(64) << 20; // half a WebGPU storage buffer

    // `depth`: that of the geometry's tables, so their lattice of drawn points is this one's;
    // `irregularLevels`: their K, the levels of the irregular faces' surface (docs/irregular.md).
    // `maxGpuRecordBytes`: see gpuLevels().
    // `boundaryBases`: faces around one UV boundary vertex take a basis per configuration (FVSF
    // version 3); off, they are refined K levels as in version 2 (tests compare the two).
    FaceVaryingSurface(const Mesh& mesh, const SchemeOptions& options, uint32_t depth, uint32_t irregularLevels,
                       Warnings& warnings, size_t maxGpuRecordBytes = kMaxGpuRecordBytes, bool boundaryBases = true);

    // The UV at (u, v) of ptex face `ptex`, from the element that contains the point just inside
    // toward (towardU, towardV) (any element containing it gives the same limit; this picks one).
    glm::dvec2 uvAt(uint32_t ptex, double u, double v, double towardU, double towardV) const;

    // Whether ptex face `ptex` has UV elements: not for a hole or a face without a limit
    // surface (boundary rule none), which the geometry's tables do not draw either.
    bool hasElements(uint32_t ptex) const { return ptex < hasElements_.size() && hasElements_[ptex]; }

    const Tables& tables() const { return tables_; }

    // The surface as the GPU reads it (shaders/fvar_eval.glsl): `nodes` is a quadtree per ptex
    // face, nodes[p] the root of ptex face p; a node is a leaf 0x80000000 | element, 0xFFFFFFFF
    // (no element: a hole), or the index of its four children (i, j) = (0,0), (1,0), (0,1), (1,1).
    // `records` holds 9 per element: (u0, v0, size, 0 for a patch / 1 for a bilinear face), then
    // the patch's 16 UV control points P_ij at 4j + i, phantoms applied, as 8 (P, P) pairs, or
    // the bilinear face's 4 corner limit UVs in the first two. The elements are the patches, then
    // each irregular face's surface as pieces: its sub-patches (quadtree or per-valence basis,
    // control points summed once) and its leaves within 2^-K of an extraordinary corner, which
    // are bilinear (docs/irregular.md); a face without a surface (K = 0) is one bilinear record.
    //
    // Compact (FVSF version 2, compactGpu()): a face with a per-valence basis is not pieces but
    // a smooth face, named by a leaf 0x80000000 | (elements + s): its extraordinary corner, its
    // 2n + 8 support UVs (float, in `points`) and that corner's limit UV; each valence's basis
    // (its weights, and the program FVSF stores them as) once in `bases`. Version 3: so is a
    // face around one UV boundary vertex (a seam), with its configuration's basis
    // (irregular_basis.h, buildBoundaryBasis) over its support. expandSmoothFaces()
    // turns that into the pieces above, the same bits wherever it runs (web/src/fvar_chunk.mjs
    // mirrors it).
    struct SmoothFace {
        uint32_t corner = 0;     // ptex order, 0..3
        uint32_t basis = 0;      // into `bases`
        uint32_t firstPoint = 0; // its support UVs (bases[basis].supportSize()): points[firstPoint ...]
        glm::vec2 limit{0.0f};   // the limit UV at the extraordinary corner
        uint32_t node = 0;       // not stored: the node naming it
        float u0 = 0, v0 = 0, size = 0; // not stored: that node's square of its ptex face
    };
    // A per-valence basis of `levels` bands (the tables' K, or fewer: gpuLevels()), with the
    // program its weights expand from (FVSF stores the program, as TBLS version 5 does).
    using Basis = IrregularBasis;
    struct Gpu {
        std::vector<uint32_t> nodes;
        std::vector<glm::vec4> records;
        std::vector<SmoothFace> smoothFaces;
        std::vector<glm::vec2> points;
        std::vector<Basis> bases;
    };
    Gpu gpu() const; // expandSmoothFaces(compactGpu())
    Gpu compactGpu() const;
    // The levels of the irregular faces' pieces in gpu(): the tables' K, fewer where that would
    // take more than maxGpuRecordBytes (then the constructor warned; the deepest squares are
    // bilinear in their exact corners).
    uint32_t gpuLevels() const { return gpuLevels_; }

  private:
    Tables tables_;
    std::vector<glm::dvec3> vertices_;
    std::vector<LimitPoint> limits_;
    // (ptex, size exponent, cell i, cell j) -> element (patch index, or patches + irregular face).
    std::unordered_map<uint64_t, uint32_t> cells_;
    uint32_t depth_;
    uint32_t ptexCount_ = 0;
    std::vector<uint8_t> hasElements_; // per ptex face
    uint32_t gpuLevels_ = 0;
    size_t gpuElementCount(uint32_t levels) const;
};

// The surface of `compact` with its smooth faces as pieces: per smooth face, in order, its band
// sub-patches k = 1..K (quadrants 1, 2, 3), control point j = sum over the support i, in order,
// of double(weight) * double(point), and its leaf within 2^-K of the corner (bilinear: the
// limit UV and the three band-K sub-patches' corner points), appended as elements and as
// children of the smooth face's node. Every smooth face must be named by its node.
FaceVaryingSurface::Gpu expandSmoothFaces(FaceVaryingSurface::Gpu compact);

// The GPU quadtree's cell (i, j) `levels` below `node` (FaceVaryingSurface::Gpu::nodes: a node
// holds the index of its four children, 0xFFFFFFFF none yet), its nodes made on the way down:
// where the records' builder and the readers' expansion of smooth faces put an element.
uint32_t fvarQuadtreeCell(std::vector<uint32_t>& nodes, uint32_t node, uint32_t levels, uint32_t i, uint32_t j);

} // namespace limn
