#include "subdiv/tables_build.h"

#include "base/cli.h"
#include "base/error.h"
#include "subdiv/irregular_basis.h"
#include "topology/orientation.h"

#include <algorithm>
#include <string>

namespace limn {

namespace {

// Patch corner k's three outer control points (a, d, b) and the corner itself, as indices into
// cv[16] = P_{i,j} at 4*j + i (see Patch): a lies beyond the corner away from corner k+1, b away
// from corner k-1, d diagonally.
constexpr int kCornerCV[4] = {5, 6, 10, 9};
constexpr int kOuterCV[4][3] = {{4, 0, 1}, {2, 3, 7}, {11, 15, 14}, {13, 12, 8}};

void requireManifold(const Topology& T) {
    // Two faces that run their edge the same way: a fixable inconsistency, or (a Möbius strip)
    // a surface without an orientation; the message says which.
    if (const Orientation o = checkOrientation(T); o.misorientedEdges)
        throwBadInput(describeMisorientation(T, o));
    for (uint32_t e = 0; e < T.edgeCount(); ++e)
        if (T.edgeIsNonManifold(e)) {
            auto [a, b] = T.edgeVertices(e);
            throwBadInput("edge (" + std::to_string(a) + "," + std::to_string(b) +
                          ") is non-manifold (" + std::to_string(T.edgeFaceCount(e)) +
                          " faces, or faces of opposite orientation); subdivision tables need a "
                          "manifold, consistently oriented mesh");
        }
    for (uint32_t v = 0; v < T.vertexCount(); ++v)
        if (T.vertexIsNonManifold(v))
            throwBadInput("vertex " + std::to_string(v) +
                          " is non-manifold (separate fans of faces meet there); subdivision "
                          "tables need a manifold mesh");
}


// The faces of T_l around one smooth interior extraordinary vertex, or (opts.boundaryBases) one
// boundary or crease vertex: drawn from the weights of their support (irregular_basis.h, built
// once per valence or boundary configuration met, under the mesh's boundary rule `rule`), so
// taken out of T (not refined further) and recorded in a.smooth; and the faces too crowded for
// either surface.
// At l = N these are irregular faces (quadtree roots); below N (l < D) they are descendants of
// irregular faces whose semi-sharp creases have decayed by level l: the rest of their surface
// is smooth Catmull-Clark, which the same basis gives (its first levels - (l - N) bands)
// instead of refining on to level D.
void takeSmoothFaces(const Level& L, uint32_t basisLevels, const TablesOptions& opts, BoundaryRule rule,
                     std::vector<uint8_t>& T, AdaptiveLevels& a) {
    int corner = 0;
    uint32_t valence = 0;
    std::vector<uint32_t> support, signature;
    BasisConfiguration configuration;
    const uint32_t F = L.topo.faceCount();
    // Below N no face is crowded: those of level N were not refined, and refinement keeps
    // valences.
    const bool roots = L.depth == a.N;
    std::vector<uint32_t> facesAt(roots ? L.topo.vertexCount() : 0, 0);
    std::vector<int>& basisOfValence = a.basisOfValence;
    for (uint32_t f = 0; roots && f < F; ++f)
        for (uint32_t v : L.topo.faceVertices(f)) ++facesAt[v];
    for (uint32_t f = 0; f < F; ++f) {
        if (!T[f]) continue;
        // Around a vertex of more than kMaxBasisValence faces (a huge n-gon's centre,
        // a hostile fan) either way costs K levels of thousands of faces: a 32,767-gon
        // at depth 2 took minutes. Such a face stays bilinear between its limit points,
        // counted as such (irregularSurfaceCounts; limn-render and limn-info say so).
        bool crowded = false;
        for (uint32_t v : L.topo.faceVertices(f)) crowded |= roots && facesAt[v] > kMaxBasisValence;
        if (crowded) {
            T[f] = 0;
            continue;
        }
        if (opts.boundaryBases && boundarySupport(L, f, corner, configuration, support, signature)) {
            // A face around one boundary vertex (a mesh boundary or a UV seam): its
            // configuration's basis, built once under the mesh's boundary rule, if the
            // configuration is self-similar and its topology the generated one's.
            auto [it, added] = a.basisOfConfiguration.try_emplace(configuration.key(), -1);
            if (added) {
                try {
                    it->second = addBasis(a, buildBoundaryBasis(configuration, basisLevels, rule, opts.basisWeights));
                } catch (const std::exception&) {
                    it->second = -2; // refined like any other
                }
            }
            if (it->second < 0 || a.bases[size_t(it->second)].signature != signature) continue;
            a.smooth.push_back({f, uint32_t(it->second), uint32_t(corner), support, L.depth});
            T[f] = 0;
            continue;
        }
        if (!smoothSupport(L, f, corner, valence, support, opts.basisRimFeatures)) continue;
        if (basisOfValence.size() <= valence) basisOfValence.resize(valence + 1, -1);
        if (basisOfValence[valence] == -1) {
            try {
                basisOfValence[valence] = addBasis(a, buildIrregularBasis(valence, basisLevels, opts.basisWeights));
            } catch (const std::exception&) {
                basisOfValence[valence] = -2; // refined like any other (never seen)
            }
        }
        if (basisOfValence[valence] < 0) continue;
        a.smooth.push_back({f, uint32_t(basisOfValence[valence]), uint32_t(corner), support, L.depth});
        T[f] = 0; // not refined further
    }
}

} // namespace

Patch gatherPatch(const Level& L, uint32_t f, uint32_t levelBase, const std::vector<uint32_t>& remap,
                  uint32_t creaseEdge) {
    const Topology& T = L.topo;
    const FaceFrame& fr = L.frames[f];
    Patch p{};
    auto global = [&](uint32_t v) { return levelBase + remap[v]; };
    for (int k = 0; k < 4; ++k) {
        uint32_t e0 = T.faceHalfedge(f) + (fr.rotation + k) % 4;
        p.cv[kCornerCV[k]] = global(T.vertex(e0));
        // A boundary edge, or an infinitely sharp one (only regular patches along inf-sharp
        // creases have those: the surface on this side ignores the points across it).
        if (T.twin(e0) == kNone || L.edgeSharpness[T.edge(e0)] >= kInfiniteSharpness)
            p.boundary |= static_cast<uint8_t>(1u << k);
        if (T.edge(e0) == creaseEdge) {
            p.crease = static_cast<uint8_t>(1u << k);
            p.sharpness = L.edgeSharpness[creaseEdge];
        }
        uint32_t a = kNone, d = kNone, b = kNone;
        uint32_t e1 = T.rotateCCW(e0);
        if (e1 != kNone) {
            a = T.vertex(T.prev(e1));
            uint32_t e2 = T.rotateCCW(e1);
            if (e2 != kNone) {
                d = T.vertex(T.next(T.next(e2)));
                b = T.vertex(T.prev(e2));
            }
        }
        if (b == kNone) {
            uint32_t e3 = T.rotateCW(e0);
            if (e3 != kNone) b = T.destination(e3);
        }
        const uint32_t outer[3] = {a, d, b};
        for (int i = 0; i < 3; ++i)
            p.cv[kOuterCV[k][i]] = outer[i] == kNone ? 0 : global(outer[i]);
    }
    // Points replaced by phantoms are read with weight zero: store 0 as for a mesh boundary.
    for (int i = 0; i < 16; ++i)
        if (isPhantom(p.boundary, i)) p.cv[i] = 0;
    p.ptex = fr.ptex;
    p.u0 = static_cast<float>(fr.u0);
    p.v0 = static_cast<float>(fr.v0);
    p.size = static_cast<float>(fr.size);
    p.level = static_cast<uint8_t>(L.depth);
    return p;
}

void checkTablesOptions(const Mesh& mesh, const TablesOptions& opts) {
    if (opts.depth < 0 || opts.depth > kMaxDepth)
        throw Error(ErrorKind::Usage, "depth " + std::to_string(opts.depth) + " is outside 0.." +
                                          std::to_string(kMaxDepth));
    const uint32_t N = static_cast<uint32_t>(opts.depth);
    if (opts.uniform && opts.maxMemoryBytes) {
        const uint64_t need = uniformTableVertices(mesh, opts.depth) * kTableBytesPerVertex;
        if (need > opts.maxMemoryBytes)
            throwBadInput("uniform tables of depth " + std::to_string(N) + " need about " +
                          cli::formatBytes(need) + " of memory (" +
                          std::to_string(uniformTableVertices(mesh, opts.depth)) +
                          " vertices), more than --max-memory " +
                          cli::formatBytes(opts.maxMemoryBytes) +
                          "; use a lower --depth, adaptive tables, or raise --max-memory");
    }
}

void checkTablesTopology(const Topology& baseTopo, const TablesOptions& opts) {
    requireManifold(baseTopo);
    // A stencil row holds up to 2 k + 1 entries for a face of k sides or a vertex of k edges, and
    // the TBLS format caps rows at 65,536 entries (formats/limn.md): refuse before the work what
    // limn-info and limn-render would refuse after it.
    for (uint32_t f = 0; f < baseTopo.faceCount(); ++f)
        if (baseTopo.faceSize(f) > kMaxStencilValence)
            throwBadInput("face " + std::to_string(f) + " has " +
                          std::to_string(baseTopo.faceSize(f)) + " sides; subdivision tables " +
                          "support up to " + std::to_string(kMaxStencilValence) +
                          " (split the face first)");
    for (uint32_t v = 0; v < baseTopo.vertexCount(); ++v)
        if (baseTopo.vertexOutgoing(v).size() > kMaxStencilValence)
            throwBadInput("vertex " + std::to_string(v) + " is shared by " +
                          std::to_string(baseTopo.vertexOutgoing(v).size()) + " faces; " +
                          "subdivision tables support up to " +
                          std::to_string(kMaxStencilValence));
    if (opts.depth == 0)
        for (uint32_t f = 0; f < baseTopo.faceCount(); ++f)
            if (baseTopo.faceSize(f) != 4)
                throwBadInput("face " + std::to_string(f) + " has " +
                              std::to_string(baseTopo.faceSize(f)) +
                              " sides; depth 0 draws faces at their limit corners and needs an "
                              "all-quad mesh (non-quads are split at the first level: use "
                              "--depth 1 or more)");
}

int addBasis(AdaptiveLevels& a, IrregularBasis b) {
    const uint64_t count = a.basisWeightCount + b.weightCount();
    if (count * sizeof(float) > kMaxBasisWeightBytes) return -2;
    a.basisWeightCount = count;
    a.bases.push_back(std::move(b));
    return static_cast<int>(a.bases.size() - 1);
}

AdaptiveLevels refineAdaptive(const Mesh& mesh, Topology baseTopo, const SchemeOptions& options,
                              const TablesOptions& opts, Warnings& warnings) {
    AdaptiveLevels a;
    const uint32_t N = static_cast<uint32_t>(opts.depth);
    // Levels beyond N under T_N only (docs/irregular.md); none for uniform tables.
    const uint32_t K = opts.uniform ? 0u
                                    : static_cast<uint32_t>(std::clamp(opts.irregularLevels, 0, kMaxDepth - opts.depth));
    const uint32_t D = N + K;
    Sharpness sharp = baseSharpness(baseTopo, mesh.tags, options.boundary, warnings);
    a.N = N;
    a.K = K;
    a.D = D;
    std::vector<Level>& levels = a.levels;
    levels.push_back(makeBaseLevel(std::move(baseTopo), std::move(sharp)));
    std::vector<uint32_t>& ptexBase = a.ptexBase;
    ptexBase.resize(levels[0].topo.faceCount());
    for (uint32_t f = 0; f < ptexBase.size(); ++f) ptexBase[f] = levels[0].frames[f].ptex;

    std::vector<LevelStencils>& stencils = a.stencils;
    stencils.resize(1);
    auto& irregularSets = a.irregularSets;
    auto& patchSets = a.patchSets;
    auto& creaseEdges = a.creaseEdges;
    const uint32_t basisLevels = opts.uniform ? 0u : static_cast<uint32_t>(std::clamp(opts.irregularLevels, 0, kMaxDepth));
    for (uint32_t l = 0;; ++l) {
        Level& L = levels[l];
        const uint32_t F = L.topo.faceCount();
        // The faces that can become patches or irregular faces (the children of T_{l-1} with a
        // limit surface): below the depth a quarter of the level, the rest being the refined
        // one-ring's outer children, whose regularity is not needed. Where most faces are such
        // (the first levels), analysing all is cheaper than visiting each vertex from its faces.
        std::vector<uint8_t> drawn(F, 0);
        uint32_t count = 0;
        for (uint32_t f = 0; f < F; ++f) count += drawn[f] = L.complete[f] && !L.noLimit[f];
        std::vector<uint8_t> regular(F, 0);
        if (!opts.uniform) {
            Regularity r = analyzeRegularity(L.topo, L.edgeSharpness, L.vertexSharpness, L.noLimit,
                                             opts.infSharpPatches, opts.singleCreasePatches,
                                             2 * count < F ? &drawn : nullptr);
            regular = std::move(r.faceRegular);
            creaseEdges.push_back(std::move(r.faceCreaseEdge));
        } else {
            creaseEdges.emplace_back(F, kNone);
        }
        std::vector<uint8_t> T(F, 0), P(F, 0);
        for (uint32_t f = 0; f < F; ++f)
            if (drawn[f]) (regular[f] ? P : T)[f] = 1;
        // Roots stay in T_N (each has a node); smooth faces below N are not in T_l: their
        // parent's node names them.
        if (opts.smoothFacesBelowDepth && l > N && l < D && basisLevels > 0) takeSmoothFaces(L, basisLevels, opts, options.boundary, T, a);
        irregularSets.push_back(T);
        patchSets.push_back(P);
        if (l == N && basisLevels > 0) takeSmoothFaces(L, basisLevels, opts, options.boundary, T, a);
        if (l == N && K > 0 && (opts.creaseChainsPrototype || opts.creaseChains)) takeCreaseFaces(L, options, opts, basisLevels, T, a);
        if (l == D) break;
        std::vector<uint8_t> S = opts.uniform ? std::vector<uint8_t>(F, 1) : oneRing(L.topo, T);
        if (std::find(S.begin(), S.end(), 1) == S.end()) {
            // Nothing left to refine: the remaining levels are empty.
            for (uint32_t m = l + 1; m <= D; ++m) {
                Level empty;
                empty.depth = m;
                levels.push_back(std::move(empty));
                stencils.emplace_back();
                irregularSets.emplace_back();
                patchSets.emplace_back();
                creaseEdges.emplace_back();
            }
            break;
        }
        // Guard memory before refining: a selected face of n sides makes n children (counted
        // as at least 4, a quad's, as before), a vertex and an edge point each about. Counting
        // 4 per face let 16 faces of 32,767 sides pass --max-memory 400M and use 1.2 GB.
        uint64_t children = 0;
        for (uint32_t f = 0; f < F; ++f)
            if (S[f]) children += std::max<uint64_t>(4, L.topo.faceSize(f));
        const uint64_t estimate = children * 2;
        if (opts.maxMemoryBytes) {
            // What is built, plus this level's estimate for it and every level still to come
            // (adaptive refinement does not grow faster than that once it is local).
            uint64_t built = 0;
            for (const auto& lv : levels) built += lv.topo.vertexCount();
            const uint64_t need = (built + estimate * (D - l)) * kTableBytesPerVertex;
            if (need > opts.maxMemoryBytes)
                throwBadInput("depth " + std::to_string(N) + " needs about " + cli::formatBytes(need) +
                              " of memory (level " + std::to_string(l + 1) + " alone about " +
                              std::to_string(estimate) + " vertices), more than --max-memory " +
                              cli::formatBytes(opts.maxMemoryBytes) + "; use a lower --depth" +
                              (opts.uniform ? " or adaptive tables" : "") +
                              ", or raise --max-memory");
        }
        if (estimate > kMaxLevelVertices)
            throwBadInput("level " + std::to_string(l + 1) + " would need about " +
                          std::to_string(estimate) + " vertices (more than " +
                          std::to_string(kMaxLevelVertices) + "); use a lower --depth" +
                          (opts.uniform ? " or adaptive tables" : ""));
        LevelStencils st;
        Level child = refineLevel(L, S, options, ptexBase, st);
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf)
            child.complete[cf] = T[child.faceParent[cf]];
        levels.push_back(std::move(child));
        stencils.push_back(std::move(st));
    }
    return a;
}

} // namespace limn
