#include "subdiv/tables_build.h"

#include "subdiv/exact_limits.h"

#include <algorithm>
#include <array>

namespace limn {

namespace {

// Limit points of the corners of T_N, one per (vertex, sector) (paper 000, 4.4), numbered in
// the order the corners are first met; a vertex's sectors' limit points are consecutive.
// Their masks are exact (exact_limits.h): undecayed semi-sharp vertices are refined locally
// beyond level N and their stencils composed back onto level-N vertices, darts and valence-2
// vertices get the eigenvectors of their local subdivision matrix. The same for the corners
// of T_D, the irregular leaves.
struct CornerLimits {
    StencilTable position, tangent1, tangent2; // over the level's local vertices
    std::vector<uint8_t> exact;
    std::vector<uint32_t> vertex;
    std::vector<std::array<uint32_t, 4>> corners; // per face of T, its corners' limit points
    std::vector<uint32_t> faces;                  // those faces
};

// Masks are computed in double and stored as the float the GPU reads.
void appendMask(StencilTable& t, const std::vector<WeightedPoint>& list) {
    for (const auto& wp : list) {
        t.indices.push_back(wp.vertex);
        t.weights.push_back(static_cast<float>(wp.weight));
    }
    t.addRow();
}

CornerLimits cornerLimits(const AdaptiveLevels& a, uint32_t lv, const SchemeOptions& options) {
    CornerLimits out;
    const Level& LN = a.levels[lv];
    const auto& TN = a.irregularSets[lv];
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
        exactVertexLimits(LN, cornerVertices, TN, options, a.ptexBase);
    std::vector<uint32_t> limitBase;
    for (size_t i = 0; i < cornerVertices.size(); ++i) {
        limitBase.push_back(static_cast<uint32_t>(out.vertex.size()));
        for (const LimitMasks& m : vertexLimits[i].sectors) {
            appendMask(out.position, m.position);
            appendMask(out.tangent1, m.tangent1);
            appendMask(out.tangent2, m.tangent2);
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
}

// Prune to the vertices something reads, from the last level down (paper 000 keeps all; the
// tables then grow with the support region only).
std::vector<std::vector<uint8_t>> neededVertices(const AdaptiveLevels& a, const CornerLimits& limN,
                                                 const CornerLimits& limD) {
    const auto& levels = a.levels;
    const auto& patchSets = a.patchSets;
    const auto& stencils = a.stencils;
    const uint32_t N = a.N, D = a.D;
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
    for (const SmoothIrregularFace& sm : a.smooth) {
        std::vector<uint8_t>& at = needed[sm.level];
        for (uint32_t v : sm.support) at[v] = 1;
    }
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

    return needed;
}

// Global numbering: level by level, keeping face, edge, vertex point order. Fills t.levels and
// t.totalVertices; returns each level's local-to-level-numbering map (kNone: pruned).
std::vector<std::vector<uint32_t>> numberVertices(const AdaptiveLevels& a,
                                                  const std::vector<std::vector<uint8_t>>& needed,
                                                  Tables& t) {
    const auto& levels = a.levels;
    const auto& irregularSets = a.irregularSets;
    const auto& patchSets = a.patchSets;
    const uint32_t D = a.D;
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

    return remap;
}

// Each level's face, edge and vertex point rows, over the global numbering.
void emitLevelStencils(const AdaptiveLevels& a, const std::vector<std::vector<uint8_t>>& needed,
                       const std::vector<std::vector<uint32_t>>& remap, Tables& t) {
    const auto& levels = a.levels;
    const auto& stencils = a.stencils;
    const uint32_t D = a.D;
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

}

// Patches to level N are drawn; deeper ones are sub-patches of the irregular faces. Returns the
// sub-patch index of each face of the deeper levels (kNone: none).
std::vector<std::vector<uint32_t>> emitPatches(const AdaptiveLevels& a,
                                               const std::vector<std::vector<uint32_t>>& remap,
                                               Tables& t) {
    const auto& levels = a.levels;
    const auto& patchSets = a.patchSets;
    const auto& creaseEdges = a.creaseEdges;
    const uint32_t N = a.N, D = a.D;
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

    return subIndex;
}

// Limit points: those of T_N's corners, then those of the leaves' (T_D's) corners; the irregular
// faces and leaves that read them.
void emitLimitPoints(const AdaptiveLevels& a, const CornerLimits& limN, const CornerLimits& limD,
                     const std::vector<std::vector<uint32_t>>& remap, Tables& t) {
    const auto& levels = a.levels;
    const uint32_t N = a.N, D = a.D;
    const uint32_t baseN = t.levels[N].first, baseD = t.levels[D].first;
    auto globalize = [&](StencilTable& out, const StencilTable& atN, const StencilTable& atD) {
        out = atN;
        for (auto& v : out.indices) v = baseN + remap[N][v];
        for (size_t r = 0; r < atD.rows(); ++r) {
            for (uint32_t k = atD.start[r]; k < atD.start[r + 1]; ++k) {
                out.indices.push_back(baseD + remap[D][atD.indices[k]]);
                out.weights.push_back(atD.weights[k]);
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
}

// The quadtree of each irregular face: a node per face of T_l (N <= l < D), the roots (T_N)
// first in the order of t.irregular; a child's quadrant comes from its ptex frame. A smooth
// face at level N is a root of four equal basis codes; one below N is its parent's basis code.
void emitIrregularQuadtrees(AdaptiveLevels& a, const CornerLimits& limD,
                            const std::vector<std::vector<uint32_t>>& remap,
                            const std::vector<std::vector<uint32_t>>& subIndex, Tables& t) {
    const auto& levels = a.levels;
    const auto& irregularSets = a.irregularSets;
    const auto& patchSets = a.patchSets;
    const auto& smooth = a.smooth;
    const uint32_t N = a.N, D = a.D;
    t.irregularBases = std::move(a.bases);
    std::vector<std::vector<uint32_t>> smoothOf(D + 1); // per level and face: its smooth index
    for (size_t i = 0; i < smooth.size(); ++i) {
        const uint32_t l = smooth[i].level;
        if (smoothOf[l].empty()) smoothOf[l].assign(levels[l].topo.faceCount(), kNone);
        smoothOf[l][smooth[i].face] = static_cast<uint32_t>(i);
        t.smoothIrregular.push_back({smooth[i].basis, smooth[i].corner, uint32_t(t.smoothPoints.size())});
        const uint32_t base = t.levels[l].first;
        const std::vector<uint32_t>& local = remap[l];
        for (uint32_t v : smooth[i].support) t.smoothPoints.push_back(base + local[v]);
    }
    auto smoothAt = [&](uint32_t l, uint32_t f) { return smoothOf[l].empty() ? kNone : smoothOf[l][f]; };
    const std::vector<uint32_t>& smoothN = smoothOf[N];
    if (D > N || !smooth.empty()) {
        std::vector<std::vector<uint32_t>> nodeIndex(D + 1);
        for (uint32_t l = N; l < std::max(D, N + 1); ++l) {
            nodeIndex[l].assign(irregularSets[l].size(), kNone);
            for (uint32_t f = 0; f < irregularSets[l].size(); ++f)
                if (irregularSets[l][f]) {
                    nodeIndex[l][f] = static_cast<uint32_t>(t.irregularNodes.size());
                    const uint32_t b = l == N && !smoothN.empty() && smoothN[f] != kNone ? kNodeBasis | smoothN[f] : kNodeNone;
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
                else if (smoothAt(l, cf) != kNone)
                    code = kNodeBasis | smoothAt(l, cf);
                t.irregularNodes[nodeIndex[l - 1][pf]][q] = code;
            }
        }
    }
}

} // namespace

Tables assembleTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                      AdaptiveLevels a) {
    const CornerLimits limN = cornerLimits(a, a.N, options);
    const CornerLimits limD = a.D > a.N ? cornerLimits(a, a.D, options) : CornerLimits{};
    const std::vector<std::vector<uint8_t>> needed = neededVertices(a, limN, limD);
    Tables t;
    t.depth = a.N;
    t.irregularLevels = a.K;
    t.uniform = opts.uniform;
    t.options = options;
    t.topologyHash = topologyHash(mesh, options);
    const std::vector<std::vector<uint32_t>> remap = numberVertices(a, needed, t);
    emitLevelStencils(a, needed, remap, t);
    const std::vector<std::vector<uint32_t>> subIndex = emitPatches(a, remap, t);
    emitLimitPoints(a, limN, limD, remap, t);
    emitIrregularQuadtrees(a, limD, remap, subIndex, t);
    return t;
}

} // namespace limn
