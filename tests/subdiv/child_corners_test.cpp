// refineLevel's childCorners (lib/subdiv/level.h), which the crease chains refine with: the
// children it makes, their points, stencil rows, sharpness and rules must be those of the whole
// refinement, in the same order, and the edges between two faces made in the same order too,
// because a chain's program bytes follow that order (crease_basis.cpp, chainCorners).
#include "mesh/import.h"
#include "subdiv/level.h"
#include "test_support.h"
#include "topology/features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <filesystem>
#include <tuple>

using namespace limn;

namespace {

// Row `cv` of a level's stencils as (source, weight bits, from a face point), face points'
// sources mapped by `point` (the identity for the whole level's rows).
template <class Point>
std::vector<std::tuple<uint32_t, uint64_t, bool>> rowOf(const Level& L, const LevelStencils& st, uint32_t cv,
                                                        Point point) {
    std::vector<std::tuple<uint32_t, uint64_t, bool>> row;
    if (cv < L.facePointCount) {
        for (uint32_t k = st.faceStart[cv]; k < st.faceStart[cv + 1]; ++k) row.emplace_back(st.faceVertices[k], 0, false);
        return row;
    }
    const bool edge = cv < L.facePointCount + L.edgePointCount;
    const uint32_t i = edge ? cv - L.facePointCount : cv - L.facePointCount - L.edgePointCount;
    const auto& start = edge ? st.edgeStart : st.vertexStart;
    const auto& entries = edge ? st.edgeEntries : st.vertexEntries;
    for (uint32_t k = start[i]; k < start[i + 1]; ++k)
        row.emplace_back(entries[k].fromFacePoint ? point(entries[k].index) : entries[k].index,
                         std::bit_cast<uint64_t>(entries[k].weight), entries[k].fromFacePoint);
    return row;
}

} // namespace

// Every catmark shape without non-manifold edges or vertices, refined once whole; then, for a few of its
// faces, the faces around the face refined with and without childCorners at the face's corners.
TEST(ChildCorners, AreTheWholeRefinementsChildrenInItsOrder) {
    const std::vector<std::filesystem::path> models = test::objModelsIn("osd/catmark");
    uint32_t checked = 0;
    for (const auto& model : models) {
        SCOPED_TRACE(model.filename().string());
        Warnings w;
        Mesh m;
        try {
            m = importMeshFile(model.string(), w);
        } catch (const std::exception&) {
            continue;
        }
        const SchemeOptions options = resolveSchemeOptions(m.tags, {});
        Topology base(uint32_t(m.vertexCount()), m.faceOffsets, m.faceVertices);
        bool manifold = base.nonManifoldEdgeCount() == 0; // the stencils need a fan at every vertex
        for (uint32_t v = 0; v < base.vertexCount() && manifold; ++v) manifold = !base.vertexIsNonManifold(v);
        if (!manifold) continue;
        Sharpness sharpness = baseSharpness(base, m.tags, options.boundary, w);
        const Level level0 = makeBaseLevel(std::move(base), std::move(sharpness));
        std::vector<uint32_t> ptexBase(level0.topo.faceCount());
        for (uint32_t f = 0; f < ptexBase.size(); ++f) ptexBase[f] = level0.frames[f].ptex;
        LevelStencils st0;
        const Level L = refineLevel(level0, std::vector<uint8_t>(level0.topo.faceCount(), 1), options, ptexBase, st0);
        const Topology& T = L.topo;
        for (uint32_t f = 0; f < T.faceCount(); f += 1 + T.faceCount() / 6) {
            SCOPED_TRACE(f);
            std::vector<uint8_t> marked(T.faceCount(), 0), corners(T.vertexCount(), 0);
            marked[f] = 1;
            for (uint32_t v : T.faceVertices(f)) corners[v] = 1;
            const std::vector<uint8_t> selected = oneRing(T, marked);
            LevelStencils whole, part;
            const Level W = refineLevel(L, selected, options, ptexBase, whole);
            const Level P = refineLevel(L, selected, options, ptexBase, part, &corners);
            // Points: each of P's is W's of the same origin and parent, in increasing order.
            std::vector<uint32_t> point(P.topo.vertexCount(), kNone);
            for (uint32_t v = 0, w0 = 0; v < point.size(); ++v) {
                while (w0 < W.topo.vertexCount() &&
                       (W.vertexOrigin[w0] != P.vertexOrigin[v] || W.vertexParent[w0] != P.vertexParent[v]))
                    ++w0;
                ASSERT_LT(w0, W.topo.vertexCount()) << "point " << v << " not the whole level's, or out of order";
                point[v] = w0++;
            }
            auto mapped = [&](uint32_t v) { return point[v]; };
            auto same = [](uint32_t v) { return v; };
            for (uint32_t v = 0; v < point.size(); ++v) {
                EXPECT_EQ(std::bit_cast<uint32_t>(P.vertexSharpness[v]), std::bit_cast<uint32_t>(W.vertexSharpness[point[v]]));
                EXPECT_EQ(P.vertexRule[v], W.vertexRule[point[v]]);
            }
            // Faces: those at f's corners, in the whole level's order, with its corners.
            uint32_t made = 0;
            for (uint32_t g = 0, p = 0; g < W.topo.faceCount(); ++g) {
                const uint32_t corner = W.topo.vertex(W.topo.faceHalfedge(g)); // the child's corner 0: a vertex point
                if (!corners[W.vertexParent[corner]]) continue;
                ASSERT_LT(p, P.topo.faceCount());
                EXPECT_EQ(P.faceParent[p], W.faceParent[g]);
                auto pv = P.topo.faceVertices(p), wv = W.topo.faceVertices(g);
                for (uint32_t k = 0; k < 4; ++k) EXPECT_EQ(point[pv[k]], wv[k]);
                ++p, ++made;
            }
            EXPECT_EQ(made, P.topo.faceCount());
            // The rows of the points made, entry for entry and bit for bit.
            for (uint32_t v = 0; v < point.size(); ++v)
                EXPECT_EQ(rowOf(P, part, v, mapped), rowOf(W, whole, point[v], same)) << "point " << v;
            // Edges between two faces made: in the whole level's order, with its sharpness.
            uint32_t last = 0;
            bool first = true;
            for (uint32_t e = 0; e < P.topo.edgeCount(); ++e) {
                if (P.topo.edgeFaceCount(e) != 2) continue;
                const auto [a, b] = P.topo.edgeVertices(e);
                uint32_t we = kNone;
                for (uint32_t h : W.topo.vertexOutgoing(point[a]))
                    if (W.topo.destination(h) == point[b]) we = W.topo.edge(h);
                ASSERT_NE(we, kNone);
                EXPECT_TRUE(first || we > last) << "edge " << e;
                EXPECT_EQ(std::bit_cast<uint32_t>(P.edgeSharpness[e]), std::bit_cast<uint32_t>(W.edgeSharpness[we]));
                last = we, first = false;
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 100u);
}
