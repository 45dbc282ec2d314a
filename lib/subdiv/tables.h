// Feature-adaptive subdivision tables (paper 000, 4.1; Nießner et al. 2012): everything the GPU
// needs to compute the surface every frame, built from topology alone.
//
// Isolation: at level l, T_l are the faces that are not regular B-spline patches (among the
// children of T_{l-1}; all faces at level 0). Refining T_l needs the full one-ring of its
// vertices, so the faces sharing a vertex with T_l (S_l) are refined; the children of T_l have
// complete neighbourhoods at level l+1. Regular children of T_l become patches at level l+1;
// T_N is drawn at its limit positions. Every base face's ptex domain is covered exactly once.
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"
#include "subdiv/irregular_basis.h"
#include "topology/features.h"

#include <array>
#include <cstdint>
#include <vector>

namespace limn {

// A flattened stencil table (CSR): row r is sum(weights[i] * V[indices[i]]) for
// i in [start[r], start[r+1]). Indices are global vertex indices (all levels concatenated).
struct StencilTable {
    std::vector<uint32_t> start{0};
    std::vector<uint32_t> indices;
    std::vector<float> weights; // empty for face points: they are plain averages
    size_t rows() const { return start.size() - 1; }
    void addRow() { start.push_back(static_cast<uint32_t>(indices.size())); }
};

// The vertices of level l are [first, first+count): face points, then edge points, then vertex
// points. Level 0 is the control mesh (count = its vertex count, no stencils).
struct LevelInfo {
    uint32_t first = 0;
    uint32_t facePoints = 0, edgePoints = 0, vertexPoints = 0;
    uint32_t count() const { return facePoints + edgePoints + vertexPoints; }
    uint32_t regularPatches = 0;  // patches drawn at this level
    uint32_t irregularFaces = 0;  // |T_l|: faces refined further (or, at level N, drawn at limit)
};

// Boundary mask bits of a regular patch: the patch edge lies on the mesh boundary or on an
// infinitely sharp crease, and the row beyond it is a phantom row P_-1 = 2 P_0 - P_1 (math.md C.4).
enum PatchBoundary : uint8_t { kBoundaryV0 = 1, kBoundaryU1 = 2, kBoundaryV1 = 4, kBoundaryU0 = 8 };

// A bicubic B-spline patch (paper 000, eq. 1). cv[4*j + i] is P_{i,j}: i runs along ptex u,
// j along ptex v; the patch covers the face whose corners are P11, P21, P22, P12, which is
// [u0, u0+size] x [v0, v0+size] of ptex face `ptex`. Missing points (beyond a boundary) hold
// index 0 and are replaced by phantoms as `boundary` says.
//
// A single-crease patch (Nießner, Loop and Greiner 2012) has a semi-sharp crease of sharpness
// `sharpness` (> 0) along the one patch edge whose bit (as in PatchBoundary) `crease` holds, and
// continuing straight on beyond the patch: the basis across the crease is that of a cubic
// B-spline curve with a semi-sharp vertex (creaseBasis in evaluate.h). crease = 0: none.
struct Patch {
    uint32_t cv[16];
    uint32_t ptex;
    float u0, v0, size;
    uint8_t level;
    uint8_t boundary;
    uint8_t crease = 0;
    float sharpness = 0;
};

// A face left irregular at level N, drawn at the limit positions of its corners. corner[i] is a
// limit point; corner 0 is at (u0, v0), then counter-clockwise like the ptex axes.
struct IrregularFace {
    uint32_t corner[4];
    uint32_t ptex;
    float u0, v0, size;
};

// The largest face size or vertex valence whose stencil rows (2 k + 1 entries) fit the TBLS
// format's limit of 65,536 entries per row.
inline constexpr uint32_t kMaxStencilValence = 32767;
// Ptex coordinates stay exact in float down to 2^-16; deeper levels would not tile exactly.
inline constexpr int kMaxDepth = 16;
// Irregular faces get their surface (per-valence bases, irregular_basis.h, or K more levels)
// only where no corner has more faces than this; the others stay bilinear, and are counted.
inline constexpr uint32_t kMaxBasisValence = 64;
// The irregular bases' weights are drawn from one GPU storage buffer (WebGPU's limit): readers
// refuse tables whose bases expand to more (formats/tbls.md), so the builder takes no basis past it.
inline constexpr uint64_t kMaxBasisWeightBytes = uint64_t(128) << 20;
// A level with more vertices than this is refused (about 10 GB of tables).
inline constexpr uint64_t kMaxLevelVertices = 1ull << 28;

struct TablesOptions {
    int depth = 3;
    bool uniform = false;
    // Regular faces along infinitely sharp creases and corners are B-spline patches with
    // boundary bits (OpenSubdiv's useInfSharpPatch) instead of being isolated to depth N.
    bool infSharpPatches = true;
    // Faces along a straight semi-sharp crease are single-crease patches (OpenSubdiv's
    // useSingleCreasePatch) instead of being isolated until the crease has decayed.
    bool singleCreasePatches = true;
    // Levels refined beyond `depth` under the faces left irregular at `depth`, so that those
    // faces are evaluated on the limit surface: their sub-patches at levels depth+1..depth+K
    // (docs/irregular.md). Every (s, t) of an irregular face on the grid of 2^-K is on a
    // sub-patch or is a limit point; K = 6 covers the view-adaptive default of 64 segments.
    // Capped so that depth + K <= kMaxDepth; none for uniform tables.
    int irregularLevels = 6;
    // Descendants of irregular faces (levels depth+1..depth+K-1) around one smooth interior
    // extraordinary vertex, once their semi-sharp creases have decayed, use the per-valence
    // basis there instead of being refined on (TBLS version 5). Off: the quadtree refines them
    // to depth+K, which versions 3 and 4 can hold (tests compare the two).
    bool smoothFacesBelowDepth = true;
    // Faces around one boundary vertex (smooth or a corner) with regular neighbours also take a
    // basis, one per configuration (irregular_basis.h, buildBoundaryBasis, under the mesh's
    // boundary rule), instead of being refined (FVSF version 3, TBLS version 7). Off: refined
    // (TBLS version 6 can hold such tables; tests compare the two).
    bool boundaryBases = true;
    // Faces around one interior extraordinary vertex keep their basis where boundaries, creases
    // or sharp vertices lie on their support's rim only (smoothSupport's featuresBeyondCorners:
    // the stencils of one level read features at the face's corners only).
    bool basisRimFeatures = true;
    // Faces of T_N whose feature corner is on a semi-sharp crease that has not decayed take the
    // surface of their configuration's chain (crease_basis.h) as a basis of their own support,
    // instead of K more levels (leaf and smooth ends, and regular ends whose patch is a
    // B-spline). TBLS version 8 holds them; limn-render, the web runtime and evaluateIrregular
    // draw them (docs/irregular-tables.md, "Chains in the tables"): the car's tables within 5% of those
    // without the irregular surface, and close-ups beside such creases no longer lose their
    // normals to the float coordinates of levels below N. The face-varying surface never takes
    // them (FVSF has no chains).
    bool creaseChains = true;
    // The bases' weights expanded (IrregularBasis::weights), as a renderer and the CPU evaluator
    // read them. Off: their programs and kinds only, for tables that are only written (TBLS
    // version 9 stores the programs, and readers expand them): limn-tables. Such tables cannot
    // be evaluated or drawn (IrregularBasis::hasWeights).
    bool basisWeights = true;
    // Measurement only (bench_crease_bases; no tool sets it): faces of T_N with a decaying-crease
    // chain (crease_basis.h) are not refined below N and their roots get no codes, so the tables
    // lack those faces' surface; what the tables would hold without their extra levels.
    bool creaseChainsPrototype = false;
    // Refuse (Error(BadInput), with the estimate and a remedy) tables whose building would need
    // more memory than this, estimated from the counts before each level is refined; 0: no limit.
    uint64_t maxMemoryBytes = 0;
};

// Peak memory of building tables, per table vertex (measured: limn-tables --uniform on a
// 1,280-triangle sphere peaks at 710 bytes per vertex at depths 5-7).
inline constexpr uint64_t kTableBytesPerVertex = 768;
// The vertices of `depth` levels of uniform refinement, all levels together (V + E + F per level;
// after the first, every face is a quad): the upper bound of adaptive tables too.
uint64_t uniformTableVertices(const Mesh& mesh, int depth);

// A node of an irregular face's quadtree: per child quadrant c = (s >= 1/2) | (t >= 1/2) << 1 of
// its face, a code: the kind in the top two bits, an index below.
inline constexpr uint32_t kNodeSubPatch = 0u << 30; // into Tables::subPatches
inline constexpr uint32_t kNodeChild = 1u << 30;    // into Tables::irregularNodes
inline constexpr uint32_t kNodeLeaf = 2u << 30;     // into Tables::irregularLeaves
inline constexpr uint32_t kNodeBasis = 3u << 30;    // into Tables::smoothIrregular (see smoothRoot)
inline constexpr uint32_t kNodeNone = 0xFFFFFFFFu;  // no surface there (never in a built table)
inline constexpr uint32_t kNodeIndexMask = (1u << 30) - 1;
// A root whose four codes are the same basis code is itself a smooth face (at level N); any
// other basis code names the smooth face of its quadrant, one level below the node (a face
// whose semi-sharp creases have decayed there; TBLS version 5). Two quadrants are different
// faces, so they never share a smooth face.
inline bool smoothRoot(const std::array<uint32_t, 4>& node) {
    return (node[0] & ~kNodeIndexMask) == kNodeBasis && node[0] == node[1] && node[0] == node[2] &&
           node[0] == node[3];
}

struct Tables {
    uint32_t depth = 0;
    bool uniform = false;
    SchemeOptions options;
    uint64_t topologyHash = 0; // of the faces and tags the tables were built from
    std::vector<LevelInfo> levels; // 0..depth + irregularLevels
    uint32_t totalVertices = 0;
    // Per level 1..depth + irregularLevels (index l-1): the three passes of paper 000, 4.2.
    std::vector<StencilTable> facePoints, edgePoints, vertexPoints;
    std::vector<Patch> patches; // sorted by level
    std::vector<IrregularFace> irregular;
    // The surface of the irregular faces (docs/irregular.md): levels depth+1..depth+K refine only
    // under them. irregularNodes[i] for i < irregular.size() is the root of irregular[i]; the
    // quadtree's leaves are regular sub-patches and, at level depth+K, irregular leaves drawn
    // from their corners' limit points (only their corners are exact).
    uint32_t irregularLevels = 0; // K
    std::vector<Patch> subPatches;
    std::vector<std::array<uint32_t, 4>> irregularNodes;
    std::vector<IrregularFace> irregularLeaves;
    // Irregular faces around one smooth interior extraordinary vertex are not refined further:
    // their sub-patches come from per-valence weights of their 2n + 8 surrounding level-N
    // points (irregular_basis.h); since version 7 also those around one boundary vertex or in a
    // sector between infinitely sharp creases, from a basis per configuration over its own
    // support size. A root node of kNodeBasis codes names one of these. So do
    // the basis codes of deeper nodes (version 5): descendants at level N + j whose creases
    // have decayed, their support at that level, the basis's first levels - j bands.
    struct SmoothIrregular {
        uint32_t basis;  // into irregularBases
        uint32_t corner; // the extraordinary corner (ptex order)
        uint32_t first;  // its basis's supportSize() points: smoothPoints[first ...]
    };
    std::vector<IrregularBasis> irregularBases;
    std::vector<SmoothIrregular> smoothIrregular;
    std::vector<uint32_t> smoothPoints; // global vertex indices (level N, or the face's level)
    // Limit points (paper 000, 4.4; math.md C): position and two tangents per point.
    StencilTable limitPosition, limitTangent1, limitTangent2;
    std::vector<uint32_t> limitVertex; // the level-N vertex (global index) of each limit point
    std::vector<uint8_t> limitExact;     // per limit point: 0 where the masks only approximate
    uint32_t approximateLimitPoints = 0; // count of those (see docs)
};

// How the irregular faces' surface is drawn (docs/irregular.md): from a per-valence basis, on
// sub-patches of a quadtree, or bilinear between their corners' limit points (tables without
// their surface). Every point at least 2^-exactLevels of a face from its extraordinary corners
// is on the limit surface (for the bilinear ones only the corners are).
struct IrregularSurfaceCounts {
    size_t basis = 0, subPatches = 0, bilinear = 0;
    size_t basisBelow = 0; // smooth faces below level N in the sub-patch quadtrees (TBLS version 5)
    size_t boundaryBasis = 0; // of `basis`, those around a boundary vertex (TBLS version 7)
    size_t creaseChain = 0;   // of `basis`, those from a decaying-crease chain (TBLS version 8)
    uint32_t exactLevels = 0; // the smallest K among the faces that are not bilinear
};
IrregularSurfaceCounts irregularSurfaceCounts(const Tables& tables);

// Hash of what tables depend on: faces, tags and scheme options (never positions).
uint64_t topologyHash(const Mesh& mesh, const SchemeOptions& options);

// Throws Error(BadInput) for non-manifold meshes and depth out of range.
Tables buildTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                   Warnings& warnings);

} // namespace limn
