#include "subdiv/level.h"

#include "subdiv/sdc_masks.h"

#include <opensubdiv/sdc/catmarkScheme.h>

#include <algorithm>

namespace limn {

namespace {

using OpenSubdiv::Sdc::Crease;

VertexRule ruleFrom(const Crease& crease, float vertexSharpness, int sharpEdges) {
    return static_cast<VertexRule>(crease.DetermineVertexVertexRule(vertexSharpness, sharpEdges));
}

Crease::Rule sdcRule(uint8_t r) { return static_cast<Crease::Rule>(r); }

// Sharpness of the child edge of `e` at its end vertex `v` (Vtr's subdivideEdgeSharpness).
float childEdgeSharpness(const Level& L, const Crease& crease, uint32_t e, uint32_t v,
                         std::vector<float>& scratch) {
    float s = L.edgeSharpness[e];
    if (s <= 0) return 0;
    if (Crease::IsInfinite(s)) return Crease::SHARPNESS_INFINITE;
    if (crease.IsUniform()) return crease.SubdivideUniformSharpness(s);
    scratch.clear();
    for (uint32_t h : L.topo.vertexOutgoing(v)) {
        scratch.push_back(L.edgeSharpness[L.topo.edge(h)]);
        uint32_t p = L.topo.prev(h);
        if (L.topo.twin(p) == kNone) scratch.push_back(L.edgeSharpness[L.topo.edge(p)]);
    }
    return crease.SubdivideEdgeSharpnessAtVertex(s, static_cast<int>(scratch.size()), scratch.data());
}

} // namespace

std::vector<uint8_t> oneRing(const Topology& T, const std::vector<uint8_t>& marked) {
    std::vector<uint8_t> vertexMarked(T.vertexCount(), 0), out(T.faceCount(), 0);
    for (uint32_t f = 0; f < T.faceCount(); ++f)
        if (marked[f])
            for (uint32_t v : T.faceVertices(f)) vertexMarked[v] = 1;
    for (uint32_t v = 0; v < T.vertexCount(); ++v)
        if (vertexMarked[v])
            for (uint32_t h : T.vertexOutgoing(v)) out[T.face(h)] = 1;
    return out;
}

void assignVertexRules(Level& L) {
    Crease crease;
    L.vertexRule.assign(L.topo.vertexCount(), static_cast<uint8_t>(VertexRule::Smooth));
    for (uint32_t v = 0; v < L.topo.vertexCount(); ++v) {
        int sharp = 0;
        for (uint32_t h : L.topo.vertexOutgoing(v)) {
            if (L.edgeSharpness[L.topo.edge(h)] > 0) ++sharp;
            uint32_t p = L.topo.prev(h);
            if (L.topo.twin(p) == kNone && L.edgeSharpness[L.topo.edge(p)] > 0) ++sharp;
        }
        L.vertexRule[v] = static_cast<uint8_t>(ruleFrom(crease, L.vertexSharpness[v], sharp));
    }
}

Level makeBaseLevel(Topology topo, Sharpness sharpness) {
    Level L;
    L.depth = 0;
    L.topo = std::move(topo);
    L.edgeSharpness = std::move(sharpness.edge);
    L.vertexSharpness = std::move(sharpness.vertex);
    L.noLimit = std::move(sharpness.faceNoLimit);
    assignVertexRules(L);
    const Topology& T = L.topo;
    L.frames.resize(T.faceCount());
    uint32_t ptex = 0;
    for (uint32_t f = 0; f < T.faceCount(); ++f) {
        L.frames[f].ptex = ptex;
        ptex += T.faceSize(f) == 4 ? 1 : T.faceSize(f);
    }
    L.complete.assign(T.faceCount(), 1);
    L.vertexOrigin.assign(T.vertexCount(), VertexOrigin::Base);
    return L;
}

namespace {

// refineLevel, and without the stencils (refineLevelTopology), each with childCorners or without
// (kCorners): one function for all, each instantiation compiled on its own (the checks for
// childCorners cost the whole mesh's refinement a percent where they are not compiled out).
template <bool kStencils, bool kCorners>
Level refine(const Level& P, const std::vector<uint8_t>& selected, const SchemeOptions& options,
             const std::vector<uint32_t>& ptexBase, LevelStencils& st, const std::vector<uint8_t>* childCorners) {
    const Topology& T = P.topo;
    const uint32_t F = T.faceCount(), E = T.edgeCount(), V = T.vertexCount();
    Crease crease(toSdcOptions(options));

    // Which parent components get a child vertex.
    std::vector<uint8_t> edgeUsed(E, 0), vertexUsed(V, 0), faceCenter(F, 0);
    // The children's twins follow from the parent's (below) where every parent edge is manifold
    // and no selected face runs along an edge twice or along a loop (faces like (a, b, c, b)):
    // then each child edge is half of one parent edge or joins an edge point to a face point
    // inside one face, with exactly the half-edges named there.
    bool twinsFromParent = T.nonManifoldEdgeCount() == 0;
    std::vector<uint32_t> firstChild(F, kNone), edgeSeenIn(twinsFromParent ? E : 0, kNone);
    // childCorners: the child of each parent half-edge's corner, kNone where it is not made.
    std::vector<uint32_t> childAt(kCorners ? T.halfedgeCount() : 0, kNone);
    auto made = [&](uint32_t h) { return !kCorners || (*childCorners)[T.vertex(h)]; };
    uint32_t childFaces = 0; // counted first so that every per-face array is allocated once
    for (uint32_t f = 0; f < F; ++f) {
        if (!selected[f]) continue;
        firstChild[f] = childFaces;
        if constexpr (!kCorners) childFaces += T.faceSize(f);
        for (uint32_t h = T.faceHalfedge(f); h < T.faceHalfedge(f) + T.faceSize(f); ++h) {
            if (kCorners && made(h)) childAt[h] = childFaces++;
            edgeUsed[T.edge(h)] = 1;
            vertexUsed[T.vertex(h)] = 1;
            if (!twinsFromParent) continue;
            if (edgeSeenIn[T.edge(h)] == f || T.vertex(h) == T.destination(h)) twinsFromParent = false;
            else edgeSeenIn[T.edge(h)] = f;
        }
    }
    for (uint32_t v = 0; v < V; ++v)
        if (vertexUsed[v])
            for (uint32_t h : T.vertexOutgoing(v)) faceCenter[T.face(h)] = 1;
    // childCorners: points only for the children made (their corners) and the face points their
    // edge and vertex points read; the others are in no face and nothing reads them. Numbered
    // in the same order as without childCorners (a subset of the same sequence).
    std::vector<uint8_t> keepFace(kCorners ? F : 0, 0), keepEdge(kCorners ? E : 0, 0), keepVertex(kCorners ? V : 0, 0);
    if constexpr (kCorners) {
        for (uint32_t f = 0; f < F; ++f)
            if (selected[f])
                for (uint32_t h = T.faceHalfedge(f); h < T.faceHalfedge(f) + T.faceSize(f); ++h)
                    if (made(h)) keepFace[f] = keepEdge[T.edge(h)] = keepEdge[T.edge(T.prev(h))] = keepVertex[T.vertex(h)] = 1;
        for (uint32_t v = 0; v < V; ++v)
            if (keepVertex[v])
                for (uint32_t h : T.vertexOutgoing(v)) keepFace[T.face(h)] = 1;
        for (uint32_t e = 0; e < E; ++e)
            if (keepEdge[e]) {
                const uint32_t h = T.edgeHalfedge(e);
                keepFace[T.face(h)] = 1;
                if (T.twin(h) != kNone) keepFace[T.face(T.twin(h))] = 1;
            }
    }
    auto hasFacePoint = [&](uint32_t f) { return faceCenter[f] && (!kCorners || keepFace[f]); };
    auto hasEdgePoint = [&](uint32_t e) { return edgeUsed[e] && (!kCorners || keepEdge[e]); };
    auto hasVertexPoint = [&](uint32_t v) { return vertexUsed[v] && (!kCorners || keepVertex[v]); };

    Level C;
    C.depth = P.depth + 1;
    std::vector<uint32_t> faceChild(F, kNone), edgeChild(E, kNone), vertexChild(V, kNone);
    const size_t childVertices = size_t(std::count(faceCenter.begin(), faceCenter.end(), 1)) +
                                 size_t(std::count(edgeUsed.begin(), edgeUsed.end(), 1)) +
                                 size_t(std::count(vertexUsed.begin(), vertexUsed.end(), 1));
    C.vertexOrigin.reserve(childVertices);
    C.vertexParent.reserve(childVertices);
    uint32_t next = 0;
    for (uint32_t f = 0; f < F; ++f)
        if (hasFacePoint(f)) {
            faceChild[f] = next++;
            C.vertexOrigin.push_back(VertexOrigin::Face);
            C.vertexParent.push_back(f);
        }
    C.facePointCount = next;
    for (uint32_t e = 0; e < E; ++e)
        if (hasEdgePoint(e)) {
            edgeChild[e] = next++;
            C.vertexOrigin.push_back(VertexOrigin::Edge);
            C.vertexParent.push_back(e);
        }
    C.edgePointCount = next - C.facePointCount;
    for (uint32_t v = 0; v < V; ++v)
        if (hasVertexPoint(v)) {
            vertexChild[v] = next++;
            C.vertexOrigin.push_back(VertexOrigin::Vertex);
            C.vertexParent.push_back(v);
        }
    C.vertexPointCount = next - C.facePointCount - C.edgePointCount;
    const uint32_t childV = next;

    // Child faces: corner k of a parent face gives the quad (v_k, e_k, f, e_{k-1}) with child
    // corner 0 at the parent's corner k (OpenSubdiv's child and ptex sub-face convention).
    std::vector<uint32_t> offsets{0}, corners, twins;
    offsets.reserve(size_t(childFaces) + 1);
    corners.reserve(4 * size_t(childFaces));
    if (twinsFromParent) twins.reserve(4 * size_t(childFaces));
    // The child half-edge of a parent half-edge's end `at`, in the face across it: the quad at
    // that face's corner `at` (slot 0 leaves the corner, slot 3 returns to it); none across a
    // boundary or into a face that is not refined.
    auto childOf = [&](uint32_t f, uint32_t k) {
        return kCorners ? childAt[T.faceHalfedge(f) + k] : firstChild[f] + k;
    };
    auto across = [&](uint32_t t, uint32_t corner, uint32_t slot) {
        if (t == kNone || firstChild[T.face(t)] == kNone) return kNone;
        if constexpr (!kCorners) return 4 * (firstChild[T.face(t)] + T.cornerIndex(corner)) + slot;
        const uint32_t c = childOf(T.face(t), T.cornerIndex(corner));
        return c == kNone ? kNone : 4 * c + slot;
    };
    C.frames.reserve(childFaces);
    C.noLimit.reserve(childFaces);
    C.faceParent.reserve(childFaces);
    for (uint32_t f = 0; f < F; ++f) {
        if (!selected[f]) continue;
        const uint32_t n = T.faceSize(f), h0 = T.faceHalfedge(f);
        const FaceFrame& pf = P.frames[f];
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t h = h0 + k;
            if (!made(h)) continue;
            for (uint32_t c : {vertexChild[T.vertex(h)], edgeChild[T.edge(h)], faceChild[f],
                               edgeChild[T.edge(T.prev(h))]})
                corners.push_back(c);
            offsets.push_back(static_cast<uint32_t>(corners.size()));
            if (twinsFromParent) {
                // Slot 0 is the first half of h, slot 3 the second half of prev(h); slots 1 and
                // 2 join the edge points to the face point, shared with the next and previous
                // corners' quads.
                const uint32_t t = T.twin(h), tp = T.twin(T.prev(h));
                twins.push_back(t == kNone ? kNone : across(t, T.next(t), 3));
                if constexpr (kCorners) {
                    const uint32_t cn = childOf(f, k + 1 == n ? 0 : k + 1), cp = childOf(f, k == 0 ? n - 1 : k - 1);
                    twins.push_back(cn == kNone ? kNone : 4 * cn + 2);
                    twins.push_back(cp == kNone ? kNone : 4 * cp + 1);
                } else {
                    const uint32_t q = firstChild[f];
                    twins.push_back(4 * (q + (k + 1 == n ? 0 : k + 1)) + 2);
                    twins.push_back(4 * (q + (k == 0 ? n - 1 : k - 1)) + 1);
                }
                twins.push_back(tp == kNone ? kNone : across(tp, tp, 0));
            }
            FaceFrame cf;
            if (P.depth == 0 && n != 4) { // a non-quad's sub-faces are ptex faces of their own
                cf.ptex = ptexBase[f] + k;
                cf.rotation = 0;
                cf.u0 = cf.v0 = 0;
                cf.size = 1;
            } else {
                static const double offU[4] = {0, 1, 1, 0}, offV[4] = {0, 0, 1, 1};
                uint32_t j = (k + 4 - pf.rotation) % 4; // which ptex corner parent corner k is
                cf.ptex = pf.ptex;
                cf.size = pf.size / 2;
                cf.u0 = pf.u0 + offU[j] * cf.size;
                cf.v0 = pf.v0 + offV[j] * cf.size;
                cf.rotation = static_cast<uint8_t>((4 - j) % 4);
            }
            C.frames.push_back(cf);
            C.noLimit.push_back(P.noLimit[f]);
            C.faceParent.push_back(f);
        }
    }
    C.topo = twinsFromParent ? Topology::withTwins(childV, std::move(offsets), std::move(corners), std::move(twins))
                             : Topology(childV, offsets, corners);
    C.complete.assign(C.topo.faceCount(), 0); // the caller marks the children of refined faces

    // Child sharpness (Vtr's subdivideEdgeSharpness / subdivideVertexSharpness) computed from
    // the parent, so it is right even for child vertices at the fringe of the sparse level.
    std::vector<float> scratch;
    std::vector<float> edgeChildSharp(2 * E, 0.0f); // child edge of e at its end 0 / end 1
    for (uint32_t e = 0; e < E; ++e) {
        if (!edgeUsed[e]) continue;
        auto ends = T.edgeVertices(e);
        edgeChildSharp[2 * e] = childEdgeSharpness(P, crease, e, ends[0], scratch);
        edgeChildSharp[2 * e + 1] = childEdgeSharpness(P, crease, e, ends[1], scratch);
    }
    C.vertexSharpness.assign(childV, 0.0f);
    C.vertexRule.assign(childV, static_cast<uint8_t>(VertexRule::Smooth));
    for (uint32_t e = 0; e < E; ++e)
        if (hasEdgePoint(e)) {
            int sharp = (edgeChildSharp[2 * e] > 0) + (edgeChildSharp[2 * e + 1] > 0);
            C.vertexRule[edgeChild[e]] = static_cast<uint8_t>(ruleFrom(crease, 0.0f, sharp));
        }
    for (uint32_t v = 0; v < V; ++v) {
        if (!hasVertexPoint(v)) continue;
        float s = crease.SubdivideVertexSharpness(P.vertexSharpness[v]);
        int sharp = 0;
        for (uint32_t h : T.vertexOutgoing(v)) {
            auto ends = T.edgeVertices(T.edge(h));
            if (edgeChildSharp[2 * T.edge(h) + (ends[0] == v ? 0 : 1)] > 0) ++sharp;
            uint32_t p = T.prev(h);
            if (T.twin(p) == kNone) {
                auto pe = T.edgeVertices(T.edge(p));
                if (edgeChildSharp[2 * T.edge(p) + (pe[0] == v ? 0 : 1)] > 0) ++sharp;
            }
        }
        C.vertexSharpness[vertexChild[v]] = s;
        C.vertexRule[vertexChild[v]] = static_cast<uint8_t>(ruleFrom(crease, s, sharp));
    }
    C.edgeSharpness.assign(C.topo.edgeCount(), 0.0f);
    for (uint32_t ce = 0; ce < C.topo.edgeCount(); ++ce) {
        auto [a, b] = C.topo.edgeVertices(ce);
        if (C.vertexOrigin[a] == VertexOrigin::Vertex) std::swap(a, b);
        if (C.vertexOrigin[a] != VertexOrigin::Edge || C.vertexOrigin[b] != VertexOrigin::Vertex) continue;
        uint32_t e = C.vertexParent[a], v = C.vertexParent[b];
        auto ends = T.edgeVertices(e);
        C.edgeSharpness[ce] = edgeChildSharp[2 * e + (ends[0] == v ? 0 : 1)];
    }

    // Stencils, with Sdc's masks and the parent/child rules as PrimvarRefiner passes them.
    OpenSubdiv::Sdc::Scheme<OpenSubdiv::Sdc::SCHEME_CATMARK> scheme(toSdcOptions(options));
    // Rows are appended in child vertex order (face, edge, vertex points by parent index).
    st = LevelStencils{};
    if constexpr (!kStencils) return C;
    st.faceStart.reserve(C.facePointCount + 1);
    st.faceVertices.reserve(4 * size_t(C.facePointCount)); // quads after the first level
    for (uint32_t f = 0; f < F; ++f)
        if (hasFacePoint(f)) {
            auto fv = T.faceVertices(f);
            st.faceVertices.insert(st.faceVertices.end(), fv.begin(), fv.end());
            st.faceStart.push_back(static_cast<uint32_t>(st.faceVertices.size()));
        }
    uint32_t maxValence = 2;
    for (uint32_t v = 0; v < V; ++v) maxValence = std::max(maxValence, T.vertexEdgeCount(v));
    SdcMask mask(static_cast<int>(maxValence));
    st.edgeEntries.reserve(4 * C.edgePointCount);
    st.edgeStart.reserve(C.edgePointCount + 1);
    st.vertexStart.reserve(C.vertexPointCount + 1);
    size_t vertexEntries = 0; // at most the vertex, its ring and its faces
    for (uint32_t v = 0; v < V; ++v)
        if (vertexUsed[v]) vertexEntries += 1 + 2 * size_t(T.vertexEdgeCount(v));
    st.vertexEntries.reserve(vertexEntries);
    for (uint32_t e = 0; e < E; ++e) {
        if (!hasEdgePoint(e)) continue;
        uint32_t cv = edgeChild[e];
        SdcEdge hood(T, e, P.edgeSharpness[e]);
        auto pRule = P.edgeSharpness[e] > 0 ? Crease::RULE_CREASE : Crease::RULE_SMOOTH;
        scheme.ComputeEdgeVertexMask(hood, mask, pRule, sdcRule(C.vertexRule[cv]));
        auto ends = T.edgeVertices(e);
        st.edgeEntries.push_back({ends[0], mask.VertexWeight(0), false});
        st.edgeEntries.push_back({ends[1], mask.VertexWeight(1), false});
        uint32_t h = T.edgeHalfedge(e);
        uint32_t faces[2] = {T.face(h), T.twin(h) == kNone ? kNone : T.face(T.twin(h))};
        for (int i = 0; i < mask.GetNumFaceWeights(); ++i)
            if (mask.FaceWeight(i) != 0)
                st.edgeEntries.push_back({faceChild[faces[i]], mask.FaceWeight(i), true});
        st.edgeStart.push_back(static_cast<uint32_t>(st.edgeEntries.size()));
    }
    VertexNeighborhood hood; // room for the largest ring at once
    for (auto* x : {&hood.edges, &hood.ringVertex, &hood.faces, &hood.diagonal}) x->reserve(maxValence + 1);
    std::vector<float> ringSharpness;
    for (uint32_t v = 0; v < V; ++v) {
        if (!hasVertexPoint(v)) continue;
        uint32_t cv = vertexChild[v];
        gatherNeighborhood(T, v, hood);
        SdcVertex sv(hood, P.edgeSharpness, P.vertexSharpness[v], C.vertexSharpness[cv], ringSharpness);
        scheme.ComputeVertexVertexMask(sv, mask, sdcRule(P.vertexRule[v]), sdcRule(C.vertexRule[cv]));
        st.vertexEntries.push_back({v, mask.VertexWeight(0), false});
        for (int i = 0; i < mask.GetNumEdgeWeights(); ++i)
            if (mask.EdgeWeight(i) != 0)
                st.vertexEntries.push_back({hood.ringVertex[i], mask.EdgeWeight(i), false});
        for (int i = 0; i < mask.GetNumFaceWeights(); ++i)
            if (mask.FaceWeight(i) != 0)
                st.vertexEntries.push_back({faceChild[hood.faces[i]], mask.FaceWeight(i), true});
        st.vertexStart.push_back(static_cast<uint32_t>(st.vertexEntries.size()));
    }
    return C;
}

} // namespace

Level refineLevel(const Level& P, const std::vector<uint8_t>& selected, const SchemeOptions& options,
                  const std::vector<uint32_t>& ptexBase, LevelStencils& st,
                  const std::vector<uint8_t>* childCorners) {
    return childCorners ? refine<true, true>(P, selected, options, ptexBase, st, childCorners)
                        : refine<true, false>(P, selected, options, ptexBase, st, nullptr);
}

Level refineLevelTopology(const Level& P, const std::vector<uint8_t>& selected, const SchemeOptions& options,
                          const std::vector<uint32_t>& ptexBase, const std::vector<uint8_t>* childCorners) {
    LevelStencils none;
    return childCorners ? refine<false, true>(P, selected, options, ptexBase, none, childCorners)
                        : refine<false, false>(P, selected, options, ptexBase, none, nullptr);
}

} // namespace limn
