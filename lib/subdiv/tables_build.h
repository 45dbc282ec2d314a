// The phases of buildTables (tables.h), internal to lib/subdiv: the input checks and the
// feature-adaptive refinement, level by level, with the sets each level's faces fall into
// (tables_refine.cpp); then the tables assembled from those levels (tables_assemble.cpp).
// buildIrregularBasis (irregular_basis.cpp) refines its generated mesh by the same rules and
// reads the sub-patches from such levels, without the tables.
#pragma once

#include "subdiv/crease_basis.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/level.h"
#include "subdiv/tables.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace limn {

// Whether cv[i] of a patch with boundary mask `boundary` lies beyond a boundary (a phantom).
// Inline: called 16 times per patch, twice, by both halves of the builder.
inline bool isPhantom(uint8_t boundary, int i) {
    const int u = i % 4, v = i / 4;
    return ((boundary & kBoundaryU0) && u == 0) || ((boundary & kBoundaryU1) && u == 3) ||
           ((boundary & kBoundaryV0) && v == 0) || ((boundary & kBoundaryV1) && v == 3);
}

// The regular patch of face f of level L: its 16 control points as levelBase + remap[vertex].
// creaseEdge: the edge of a single-crease patch (kNone: none).
Patch gatherPatch(const Level& L, uint32_t f, uint32_t levelBase, const std::vector<uint32_t>& remap,
                  uint32_t creaseEdge);

// Throw Error for what tables cannot be built from, before any work: a depth out of range,
// uniform tables over opts.maxMemoryBytes; then a non-manifold or misoriented mesh, faces or
// vertices past the stencil row limit, non-quads at depth 0.
void checkTablesOptions(const Mesh& mesh, const TablesOptions& opts);
void checkTablesTopology(const Topology& baseTopo, const TablesOptions& opts);

// A face of T_N, or a descendant of one at level N + j (j < K) once its semi-sharp features
// have decayed, around one smooth interior extraordinary vertex or one boundary or crease vertex:
// drawn from its basis's weights of its support (irregular_basis.h; bands 1..levels - j), not
// refined further.
struct SmoothIrregularFace {
    uint32_t face, basis, corner;
    std::vector<uint32_t> support; // vertices of `level`
    uint32_t level = 0;
};

// Levels 0..D = N + K of the refinement, where N is the depth and K the irregular faces' extra
// levels (docs/irregular.md), each with the stencils that made it from the one before.
struct AdaptiveLevels {
    uint32_t N = 0, K = 0, D = 0;
    std::vector<Level> levels;
    std::vector<LevelStencils> stencils;             // [l]: level l from l - 1 (none at 0)
    std::vector<std::vector<uint8_t>> irregularSets; // T_l
    std::vector<std::vector<uint8_t>> patchSets;     // D_l \ T_l with a limit surface
    std::vector<std::vector<uint32_t>> creaseEdges;  // per face: a single-crease patch's edge
    std::vector<uint32_t> ptexBase;                  // per base face: its first ptex id
    std::vector<SmoothIrregularFace> smooth;         // by level: roots (T_N) first, then deeper
    std::vector<IrregularBasis> bases;               // their bases, one per valence or configuration met
    uint64_t basisWeightCount = 0;                   // their weights (IrregularBasis::weightCount)
    std::vector<int> basisOfValence;                 // into bases; -1: not tried, -2: failed
    std::unordered_map<uint64_t, int> basisOfConfiguration; // boundary ones, by key (the same)
    // TablesOptions::creaseChainsPrototype: the faces of T_N taken with a chain (basis: the
    // chain's index, corner: its feature corner) and one chain per configuration.
    std::vector<SmoothIrregularFace> creaseFaces;
    std::vector<CreaseChain> creaseChains;
};

// Adds b to a.bases where all their weights stay within kMaxBasisWeightBytes, returning its
// index; -2 where it would pass it (its faces are refined instead, and the tables stay readable).
int addBasis(AdaptiveLevels& a, IrregularBasis b);

// TablesOptions::creaseChainsPrototype (crease_basis.cpp): takes the faces of T (level N) that
// have a decaying-crease chain out of T, building one chain per configuration.
void takeCreaseFaces(const Level& L, const SchemeOptions& options, const TablesOptions& opts, uint32_t basisLevels,
                     std::vector<uint8_t>& T,
                     AdaptiveLevels& a);

// Refines `baseTopo` (checked by checkTablesTopology) to depth opts.depth and K more levels under
// the irregular faces; throws Error(BadInput) where that would pass opts.maxMemoryBytes or
// kMaxLevelVertices.
AdaptiveLevels refineAdaptive(const Mesh& mesh, Topology baseTopo, const SchemeOptions& options,
                              const TablesOptions& opts, Warnings& warnings);

// The tables of the refined levels: the corners' limit points, the vertices something reads
// (the rest pruned) in their global numbering, the stencils, patches and sub-patches, the
// irregular faces and their quadtrees.
Tables assembleTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                      AdaptiveLevels levels);

} // namespace limn
