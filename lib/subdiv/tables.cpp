#include "subdiv/tables.h"

#include "base/cli.h"
#include "base/error.h"
#include "container/container.h"
#include "subdiv/exact_limits.h"
#include "subdiv/level.h"
#include "subdiv/limit_masks.h"
#include "topology/orientation.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

namespace limn {

namespace {

// Patch corner k's three outer control points (a, d, b) and the corner itself, as indices into
// cv[16] = P_{i,j} at 4*j + i (see Patch): a lies beyond the corner away from corner k+1, b away
// from corner k-1, d diagonally.
constexpr int kCornerCV[4] = {5, 6, 10, 9};
constexpr int kOuterCV[4][3] = {{4, 0, 1}, {2, 3, 7}, {11, 15, 14}, {13, 12, 8}};

// Whether cv[i] of a patch with boundary mask `boundary` lies beyond a boundary (a phantom).
bool isPhantom(uint8_t boundary, int i) {
    const int u = i % 4, v = i / 4;
    return ((boundary & kBoundaryU0) && u == 0) || ((boundary & kBoundaryU1) && u == 3) ||
           ((boundary & kBoundaryV0) && v == 0) || ((boundary & kBoundaryV1) && v == 3);
}

Patch gatherPatch(const Level& L, uint32_t f, uint32_t levelBase,
                  const std::vector<uint32_t>& remap, uint32_t creaseEdge) {
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

} // namespace

uint64_t topologyHash(const Mesh& mesh, const SchemeOptions& options) {
    auto bytesOf = [](const auto& v) {
        return std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(v.data()),
                                        v.size() * sizeof(v[0]));
    };
    uint64_t h = hashBytes(bytesOf(mesh.faceOffsets));
    h = hashBytes(bytesOf(mesh.faceVertices), h);
    uint8_t opts[4] = {uint8_t(options.boundary), uint8_t(options.creaseMethod),
                       uint8_t(options.triangles), uint8_t(options.fvar)};
    h = hashBytes(opts, h);
    for (const auto& c : mesh.tags.creases) {
        uint32_t w[3] = {c.v0, c.v1, 0};
        std::memcpy(&w[2], &c.sharpness, 4);
        h = hashBytes({reinterpret_cast<const uint8_t*>(w), 12}, h);
    }
    for (const auto& c : mesh.tags.corners) {
        uint32_t w[2] = {c.vertex, 0};
        std::memcpy(&w[1], &c.sharpness, 4);
        h = hashBytes({reinterpret_cast<const uint8_t*>(w), 8}, h);
    }
    h = hashBytes(bytesOf(mesh.tags.holes), h);
    uint32_t vcount = static_cast<uint32_t>(mesh.vertexCount());
    return hashBytes({reinterpret_cast<const uint8_t*>(&vcount), 4}, h);
}

IrregularSurfaceCounts irregularSurfaceCounts(const Tables& t) {
    IrregularSurfaceCounts c;
    uint32_t most = kMaxDepth + 1;
    for (size_t i = 0; i < t.irregular.size(); ++i) {
        const uint32_t code = i < t.irregularNodes.size() ? t.irregularNodes[i][0] : kNodeNone;
        if (code == kNodeNone) {
            ++c.bilinear;
        } else if ((code & ~kNodeIndexMask) == kNodeBasis) {
            ++c.basis;
            const auto& f = t.smoothIrregular[code & kNodeIndexMask];
            most = std::min(most, t.irregularBases[f.basis].levels);
        } else {
            ++c.subPatches;
            most = std::min(most, t.irregularLevels);
        }
    }
    c.exactLevels = most > uint32_t(kMaxDepth) ? 0 : most;
    return c;
}

uint64_t uniformTableVertices(const Mesh& mesh, int depth) {
    const uint64_t corners = mesh.cornerCount();
    // Edges: each interior edge is shared by two corners; count the distinct ones exactly.
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    edges.reserve(corners);
    for (size_t f = 0; f < mesh.faceCount(); ++f) {
        auto face = mesh.face(f);
        for (size_t k = 0; k < face.size(); ++k) {
            uint32_t a = face[k], b = face[(k + 1) % face.size()];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    double E = double(std::unique(edges.begin(), edges.end()) - edges.begin());
    double V = double(mesh.vertexCount()), F = double(mesh.faceCount()), total = V;
    for (int l = 1; l <= depth; ++l) {
        const double faceCorners = l == 1 ? double(corners) : 4 * F;
        const double nextV = V + E + F, nextE = 2 * E + faceCorners, nextF = faceCorners;
        V = nextV, E = nextE, F = nextF;
        total += V;
        if (total > 1e18) return uint64_t(1e18);
    }
    return static_cast<uint64_t>(total);
}

Tables buildTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                   Warnings& warnings) {
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
    Topology baseTopo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
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
    if (N == 0)
        for (uint32_t f = 0; f < baseTopo.faceCount(); ++f)
            if (baseTopo.faceSize(f) != 4)
                throwBadInput("face " + std::to_string(f) + " has " +
                              std::to_string(baseTopo.faceSize(f)) +
                              " sides; depth 0 draws faces at their limit corners and needs an "
                              "all-quad mesh (non-quads are split at the first level: use "
                              "--depth 1 or more)");

    // Levels beyond N under T_N only (docs/irregular.md); none for uniform tables.
    const uint32_t K = opts.uniform ? 0u
                                    : static_cast<uint32_t>(std::clamp(opts.irregularLevels, 0, kMaxDepth - opts.depth));
    const uint32_t D = N + K;
    Sharpness sharp = baseSharpness(baseTopo, mesh.tags, options.boundary, warnings);
    std::vector<Level> levels;
    levels.push_back(makeBaseLevel(std::move(baseTopo), std::move(sharp)));
    std::vector<uint32_t> ptexBase(levels[0].topo.faceCount());
    for (uint32_t f = 0; f < ptexBase.size(); ++f) ptexBase[f] = levels[0].frames[f].ptex;

    std::vector<LevelStencils> stencils(1);
    std::vector<std::vector<uint8_t>> irregularSets; // T_l
    std::vector<std::vector<uint8_t>> patchSets;     // D_l \ T_l with a limit surface
    std::vector<std::vector<uint32_t>> creaseEdges;  // per face: a single-crease patch's edge
    // Faces of T_N around one smooth interior extraordinary vertex: drawn from per-valence
    // weights of their support, not refined further (irregular_basis.h).
    struct Smooth {
        uint32_t face, basis, corner;
        std::vector<uint32_t> support; // level-N vertices
    };
    std::vector<Smooth> smooth;
    std::vector<IrregularBasis> bases;
    std::vector<int> basisOfValence; // -1: not tried, -2: failed
    const uint32_t basisLevels = opts.uniform ? 0u : static_cast<uint32_t>(std::clamp(opts.irregularLevels, 0, kMaxDepth));
    for (uint32_t l = 0;; ++l) {
        Level& L = levels[l];
        const uint32_t F = L.topo.faceCount();
        std::vector<uint8_t> regular(F, 0);
        if (!opts.uniform) {
            Regularity r = analyzeRegularity(L.topo, L.edgeSharpness, L.vertexSharpness, L.noLimit,
                                             opts.infSharpPatches, opts.singleCreasePatches);
            regular = std::move(r.faceRegular);
            creaseEdges.push_back(std::move(r.faceCreaseEdge));
        } else {
            creaseEdges.emplace_back(F, kNone);
        }
        std::vector<uint8_t> T(F, 0), P(F, 0);
        for (uint32_t f = 0; f < F; ++f) {
            if (!L.complete[f] || L.noLimit[f]) continue;
            (regular[f] ? P : T)[f] = 1;
        }
        irregularSets.push_back(T);
        patchSets.push_back(P);
        if (l == N && basisLevels > 0) {
            int corner = 0;
            uint32_t valence = 0;
            std::vector<uint32_t> support;
            std::vector<uint32_t> facesAt(L.topo.vertexCount(), 0);
            for (uint32_t f = 0; f < F; ++f)
                for (uint32_t v : L.topo.faceVertices(f)) ++facesAt[v];
            for (uint32_t f = 0; f < F; ++f) {
                if (!T[f]) continue;
                // Around a vertex of more than kMaxBasisValence faces (a huge n-gon's centre,
                // a hostile fan) either way costs K levels of thousands of faces: a 32,767-gon
                // at depth 2 took minutes. Such a face stays bilinear between its limit points,
                // counted as such (irregularSurfaceCounts; limn-render and limn-info say so).
                bool crowded = false;
                for (uint32_t v : L.topo.faceVertices(f)) crowded |= facesAt[v] > kMaxBasisValence;
                if (crowded) {
                    T[f] = 0;
                    continue;
                }
                if (!smoothSupport(L, f, corner, valence, support)) continue;
                if (basisOfValence.size() <= valence) basisOfValence.resize(valence + 1, -1);
                if (basisOfValence[valence] == -1) {
                    try {
                        bases.push_back(buildIrregularBasis(valence, basisLevels));
                        basisOfValence[valence] = static_cast<int>(bases.size() - 1);
                    } catch (const std::exception&) {
                        basisOfValence[valence] = -2; // refined like any other (never seen)
                    }
                }
                if (basisOfValence[valence] < 0) continue;
                smooth.push_back({f, uint32_t(basisOfValence[valence]), uint32_t(corner), support});
                T[f] = 0; // not refined further
            }
        }
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
        // Guard memory before refining: every selected face makes about 4 children per level.
        uint64_t selected = std::count(S.begin(), S.end(), 1);
        uint64_t estimate = selected * 4 * 2;
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

    // Limit points of the corners of T_N, one per (vertex, sector) (paper 000, 4.4), numbered in
    // the order the corners are first met; a vertex's sectors' limit points are consecutive.
    // Their masks are exact (exact_limits.h): undecayed semi-sharp vertices are refined locally
    // beyond level N and their stencils composed back onto level-N vertices, darts and valence-2
    // vertices get the eigenvectors of their local subdivision matrix. The same for the corners
    // of T_D, the irregular leaves.
    struct LocalLimits {
        StencilTable position, tangent1, tangent2; // over the level's local vertices
        std::vector<uint8_t> exact;
        std::vector<uint32_t> vertex;
        std::vector<std::array<uint32_t, 4>> corners; // per face of T, its corners' limit points
        std::vector<uint32_t> faces;                  // those faces
    };
    // Masks are computed in double and stored as the float the GPU reads.
    auto append = [](StencilTable& t, const std::vector<WeightedPoint>& list) {
        for (const auto& wp : list) {
            t.indices.push_back(wp.vertex);
            t.weights.push_back(static_cast<float>(wp.weight));
        }
        t.addRow();
    };
    auto limitsAt = [&](uint32_t lv) {
        LocalLimits out;
        const Level& LN = levels[lv];
        const auto& TN = irregularSets[lv];
        if (std::find(TN.begin(), TN.end(), 1) == TN.end()) return out;
        auto cornerVertex = [&](uint32_t f, int k) {
            return LN.topo.vertex(LN.topo.faceHalfedge(f) + (LN.frames[f].rotation + k) % 4);
        };
        std::vector<uint32_t> cornerIndex(LN.topo.vertexCount(), kNone);
        std::vector<uint32_t> cornerVertices; // in first-met order
        for (uint32_t f = 0; f < TN.size(); ++f)
            if (TN[f])
                for (int k = 0; k < 4; ++k) {
                    const uint32_t v = cornerVertex(f, k);
                    if (cornerIndex[v] != kNone) continue;
                    cornerIndex[v] = static_cast<uint32_t>(cornerVertices.size());
                    cornerVertices.push_back(v);
                }
        const std::vector<VertexLimits> vertexLimits =
            exactVertexLimits(LN, cornerVertices, TN, options, ptexBase);
        std::vector<uint32_t> limitBase;
        for (size_t i = 0; i < cornerVertices.size(); ++i) {
            limitBase.push_back(static_cast<uint32_t>(out.vertex.size()));
            for (const LimitMasks& m : vertexLimits[i].sectors) {
                append(out.position, m.position);
                append(out.tangent1, m.tangent1);
                append(out.tangent2, m.tangent2);
                out.exact.push_back(m.exact ? 1 : 0);
                out.vertex.push_back(cornerVertices[i]);
            }
        }
        for (uint32_t f = 0; f < TN.size(); ++f) {
            if (!TN[f]) continue;
            std::array<uint32_t, 4> corners{};
            for (int k = 0; k < 4; ++k) {
                const uint32_t i = cornerIndex[cornerVertex(f, k)];
                const VertexLimits& vl = vertexLimits[i];
                const size_t pos = size_t(std::find(vl.ringFaces.begin(), vl.ringFaces.end(), f) -
                                          vl.ringFaces.begin());
                corners[k] = limitBase[i] + vl.ringSector[pos];
            }
            out.corners.push_back(corners);
            out.faces.push_back(f);
        }
        return out;
    };
    LocalLimits limN = limitsAt(N), limD;
    if (D > N) limD = limitsAt(D);

    // Prune to the vertices something reads, from the last level down (paper 000 keeps all; the
    // tables then grow with the support region only).
    std::vector<std::vector<uint8_t>> needed(D + 1);
    for (uint32_t l = 0; l <= D; ++l) needed[l].assign(levels[l].topo.vertexCount(), 0);
    std::fill(needed[0].begin(), needed[0].end(), 1); // the control points are uploaded anyway
    // A patch reads its 16 points less the phantoms (across an inf-sharp crease those are real
    // vertices that it does not read).
    for (uint32_t l = 0; l <= D; ++l) {
        std::vector<uint32_t> identity(levels[l].topo.vertexCount());
        for (uint32_t v = 0; v < identity.size(); ++v) identity[v] = v;
        for (uint32_t f = 0; f < patchSets[l].size(); ++f) {
            if (!patchSets[l][f]) continue;
            const Patch p = gatherPatch(levels[l], f, 0, identity, kNone);
            for (int i = 0; i < 16; ++i)
                if (!isPhantom(p.boundary, i)) needed[l][p.cv[i]] = 1;
        }
    }
    for (const auto* table : {&limN.position, &limN.tangent1, &limN.tangent2})
        for (uint32_t v : table->indices) needed[N][v] = 1;
    for (const auto* table : {&limD.position, &limD.tangent1, &limD.tangent2})
        for (uint32_t v : table->indices) needed[D][v] = 1;
    for (const Smooth& sm : smooth)
        for (uint32_t v : sm.support) needed[N][v] = 1;
    for (uint32_t l = D; l >= 1; --l) {
        const Level& L = levels[l];
        const LevelStencils& st = stencils[l];
        const uint32_t fp = L.facePointCount, ep = L.edgePointCount;
        for (uint32_t i = 0; i < ep; ++i)
            if (needed[l][fp + i])
                for (uint32_t k = st.edgeStart[i]; k < st.edgeStart[i + 1]; ++k)
                    (st.edgeEntries[k].fromFacePoint ? needed[l] : needed[l - 1])[st.edgeEntries[k].index] = 1;
        for (uint32_t i = 0; i < L.vertexPointCount; ++i)
            if (needed[l][fp + ep + i])
                for (uint32_t k = st.vertexStart[i]; k < st.vertexStart[i + 1]; ++k)
                    (st.vertexEntries[k].fromFacePoint ? needed[l] : needed[l - 1])[st.vertexEntries[k].index] = 1;
        for (uint32_t i = 0; i < fp; ++i)
            if (needed[l][i])
                for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k)
                    needed[l - 1][st.faceVertices[k]] = 1;
    }

    // Global numbering: level by level, keeping face, edge, vertex point order.
    Tables t;
    t.depth = N;
    t.irregularLevels = K;
    t.uniform = opts.uniform;
    t.options = options;
    t.topologyHash = topologyHash(mesh, options);
    std::vector<std::vector<uint32_t>> remap(D + 1);
    uint32_t next = 0;
    for (uint32_t l = 0; l <= D; ++l) {
        const Level& L = levels[l];
        LevelInfo info;
        info.first = next;
        remap[l].assign(L.topo.vertexCount(), kNone);
        uint32_t local = 0;
        for (uint32_t v = 0; v < L.topo.vertexCount(); ++v) {
            if (!needed[l][v]) continue;
            remap[l][v] = local++;
            if (l == 0) continue;
            if (v < L.facePointCount)
                ++info.facePoints;
            else if (v < L.facePointCount + L.edgePointCount)
                ++info.edgePoints;
            else
                ++info.vertexPoints;
        }
        if (l == 0) info.vertexPoints = local; // level 0: the control points
        next += local;
        for (uint8_t p : patchSets[l]) info.regularPatches += p;
        for (uint8_t x : irregularSets[l]) info.irregularFaces += x;
        t.levels.push_back(info);
    }
    t.totalVertices = next;

    for (uint32_t l = 1; l <= D; ++l) {
        const Level& L = levels[l];
        const LevelStencils& st = stencils[l];
        const uint32_t base = t.levels[l].first, parentBase = t.levels[l - 1].first;
        auto src = [&](const StencilEntry& e) {
            return e.fromFacePoint ? base + remap[l][e.index] : parentBase + remap[l - 1][e.index];
        };
        StencilTable faces, edges, verts;
        for (uint32_t i = 0; i < L.facePointCount; ++i) {
            if (!needed[l][i]) continue;
            for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k)
                faces.indices.push_back(parentBase + remap[l - 1][st.faceVertices[k]]);
            faces.addRow();
        }
        auto emitRows = [&](StencilTable& out, uint32_t first, uint32_t count,
                            const std::vector<uint32_t>& start, const std::vector<StencilEntry>& entries) {
            for (uint32_t i = 0; i < count; ++i) {
                if (!needed[l][first + i]) continue;
                for (uint32_t k = start[i]; k < start[i + 1]; ++k) {
                    out.indices.push_back(src(entries[k]));
                    out.weights.push_back(static_cast<float>(entries[k].weight));
                }
                out.addRow();
            }
        };
        emitRows(edges, L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
        emitRows(verts, L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart,
                 st.vertexEntries);
        t.facePoints.push_back(std::move(faces));
        t.edgePoints.push_back(std::move(edges));
        t.vertexPoints.push_back(std::move(verts));
    }

    // Patches to level N are drawn; deeper ones are sub-patches of the irregular faces.
    std::vector<std::vector<uint32_t>> subIndex(D + 1);
    for (uint32_t l = 0; l <= D; ++l)
        for (uint32_t f = 0; f < patchSets[l].size(); ++f)
            if (patchSets[l][f]) {
                Patch p = gatherPatch(levels[l], f, t.levels[l].first, remap[l], creaseEdges[l][f]);
                if (l <= N) {
                    t.patches.push_back(p);
                    continue;
                }
                if (subIndex[l].empty()) subIndex[l].assign(patchSets[l].size(), kNone);
                subIndex[l][f] = static_cast<uint32_t>(t.subPatches.size());
                t.subPatches.push_back(p);
            }

    // Limit points: those of T_N's corners, then those of the leaves' (T_D's) corners.
    const uint32_t baseN = t.levels[N].first, baseD = t.levels[D].first;
    auto globalize = [&](StencilTable& out, const StencilTable& a, const StencilTable& b) {
        out = a;
        for (auto& v : out.indices) v = baseN + remap[N][v];
        for (size_t r = 0; r < b.rows(); ++r) {
            for (uint32_t k = b.start[r]; k < b.start[r + 1]; ++k) {
                out.indices.push_back(baseD + remap[D][b.indices[k]]);
                out.weights.push_back(b.weights[k]);
            }
            out.addRow();
        }
    };
    globalize(t.limitPosition, limN.position, limD.position);
    globalize(t.limitTangent1, limN.tangent1, limD.tangent1);
    globalize(t.limitTangent2, limN.tangent2, limD.tangent2);
    for (uint32_t v : limN.vertex) t.limitVertex.push_back(baseN + remap[N][v]);
    for (uint32_t v : limD.vertex) t.limitVertex.push_back(baseD + remap[D][v]);
    t.limitExact = limN.exact;
    t.limitExact.insert(t.limitExact.end(), limD.exact.begin(), limD.exact.end());
    // Counted once per surface point: a leaf's approximate corner is that of its face at level N.
    for (uint8_t e : limN.exact) t.approximateLimitPoints += e ? 0 : 1;
    auto faceOf = [&](const Level& L, uint32_t f, const std::array<uint32_t, 4>& corners, uint32_t offset) {
        const FaceFrame& fr = L.frames[f];
        IrregularFace face{};
        for (int k = 0; k < 4; ++k) face.corner[k] = offset + corners[k];
        face.ptex = fr.ptex;
        face.u0 = static_cast<float>(fr.u0);
        face.v0 = static_cast<float>(fr.v0);
        face.size = static_cast<float>(fr.size);
        return face;
    };
    for (size_t i = 0; i < limN.faces.size(); ++i)
        t.irregular.push_back(faceOf(levels[N], limN.faces[i], limN.corners[i], 0));
    const uint32_t leafOffset = static_cast<uint32_t>(limN.vertex.size());
    for (size_t i = 0; i < limD.faces.size(); ++i)
        t.irregularLeaves.push_back(faceOf(levels[D], limD.faces[i], limD.corners[i], leafOffset));

    // The quadtree of each irregular face: a node per face of T_l (N <= l < D), the roots (T_N)
    // first in the order of t.irregular; a child's quadrant comes from its ptex frame.
    t.irregularBases = std::move(bases);
    std::vector<uint32_t> smoothOf(irregularSets[N].size(), kNone);
    for (size_t i = 0; i < smooth.size(); ++i) {
        smoothOf[smooth[i].face] = static_cast<uint32_t>(i);
        t.smoothIrregular.push_back({smooth[i].basis, smooth[i].corner, uint32_t(t.smoothPoints.size())});
        for (uint32_t v : smooth[i].support) t.smoothPoints.push_back(baseN + remap[N][v]);
    }
    if (D > N || !smooth.empty()) {
        std::vector<std::vector<uint32_t>> nodeIndex(D + 1);
        for (uint32_t l = N; l < std::max(D, N + 1); ++l) {
            nodeIndex[l].assign(irregularSets[l].size(), kNone);
            for (uint32_t f = 0; f < irregularSets[l].size(); ++f)
                if (irregularSets[l][f]) {
                    nodeIndex[l][f] = static_cast<uint32_t>(t.irregularNodes.size());
                    const uint32_t b = l == N && smoothOf[f] != kNone ? kNodeBasis | smoothOf[f] : kNodeNone;
                    t.irregularNodes.push_back({b, b, b, b});
                }
        }
        std::vector<uint32_t> leafIndex(irregularSets[D].size(), kNone);
        for (size_t i = 0; i < limD.faces.size(); ++i) leafIndex[limD.faces[i]] = static_cast<uint32_t>(i);
        for (uint32_t l = N + 1; l <= D; ++l) {
            const Level& L = levels[l];
            for (uint32_t cf = 0; cf < L.topo.faceCount(); ++cf) {
                const uint32_t pf = L.faceParent[cf];
                if (!L.complete[cf] || nodeIndex[l - 1][pf] == kNone) continue;
                const FaceFrame &c = L.frames[cf], &p = levels[l - 1].frames[pf];
                const int q = (c.u0 > p.u0 ? 1 : 0) | (c.v0 > p.v0 ? 2 : 0);
                uint32_t code = kNodeNone;
                if (patchSets[l][cf])
                    code = kNodeSubPatch | subIndex[l][cf];
                else if (irregularSets[l][cf])
                    code = l < D ? kNodeChild | nodeIndex[l][cf] : kNodeLeaf | leafIndex[cf];
                t.irregularNodes[nodeIndex[l - 1][pf]][q] = code;
            }
        }
    }
    return t;
}

} // namespace limn
