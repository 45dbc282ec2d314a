// A refined level's topology takes its twins from the parent level's (Topology::withTwins, called
// by lib/subdiv/level.cpp) instead of matching edges: it must be the constructor's, array for
// array, because the tables' bytes follow the constructor's numbering of edges and fans.
#include "mesh/import.h"
#include "subdiv/crease_basis.h"
#include "subdiv/level.h"
#include "test_support.h"
#include "topology/features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

using namespace limn;

namespace {

// The constructor's topology of the same faces.
Topology rebuilt(const Topology& t) {
    std::vector<uint32_t> offsets{0}, corners;
    for (uint32_t f = 0; f < t.faceCount(); ++f) {
        auto fv = t.faceVertices(f);
        corners.insert(corners.end(), fv.begin(), fv.end());
        offsets.push_back(uint32_t(corners.size()));
    }
    return Topology(t.vertexCount(), offsets, corners);
}

// The fans as topology.h describes them, found the plain way: a vertex none of whose edges is
// non-manifold has one fan (walking counter-clockwise from its start reaches every outgoing
// half-edge), starting at its outgoing half-edge without a twin, or at its first outgoing one
// where none lacks a twin. Counts the vertices that disagree.
uint32_t fanMismatches(const Topology& t) {
    uint32_t bad = 0;
    for (uint32_t v = 0; v < t.vertexCount(); ++v) {
        auto out = t.vertexOutgoing(v);
        if (out.empty()) continue;
        bool edgesManifold = true;
        for (uint32_t h : out)
            edgesManifold &= !t.edgeIsNonManifold(t.edge(h)) && !t.edgeIsNonManifold(t.edge(t.prev(h)));
        if (!edgesManifold) {
            bad += !t.vertexIsNonManifold(v);
            continue;
        }
        uint32_t start = out[0], open = 0;
        for (auto it = out.rbegin(); it != out.rend(); ++it)
            if (t.twin(*it) == kNone) start = *it, ++open;
        uint32_t reached = 0, h = start;
        do {
            ++reached;
            h = t.twin(t.prev(h));
        } while (h != kNone && h != start && reached <= out.size());
        const bool oneFan = reached == out.size() && open <= 1;
        bad += t.vertexIsNonManifold(v) == oneFan || t.vertexIsBoundary(v) != (open > 0 || h == kNone);
        if (oneFan) bad += t.vertexFirstOutgoing(v) != start;
    }
    return bad;
}

} // namespace

// Every catmark shape that imports (non-manifold ones included: their levels take the constructor's path)
// refined three times, the first level whole and then a scattered quarter of the faces, so that
// refined faces border unrefined ones (boundaries of the sparse level) at every level.
TEST(RefinedTopology, IsTheConstructorsForEveryCatmarkShape) {
    const std::vector<std::filesystem::path> models = test::objModelsIn("osd/catmark");
    ASSERT_GT(models.size(), 50u);
    uint32_t levels = 0;
    for (const auto& model : models) {
        SCOPED_TRACE(model.filename().string());
        Warnings w;
        Mesh m;
        try {
            m = importMeshFile(model.string(), w);
        } catch (const std::exception&) {
            continue; // refused on import (degenerate faces): never refined
        }
        const SchemeOptions options = resolveSchemeOptions(m.tags, {});
        Topology base(uint32_t(m.vertexCount()), m.faceOffsets, m.faceVertices);
        Sharpness sharpness = baseSharpness(base, m.tags, options.boundary, w);
        Level level = makeBaseLevel(std::move(base), std::move(sharpness));
        std::vector<uint32_t> ptexBase(level.topo.faceCount());
        for (uint32_t f = 0; f < ptexBase.size(); ++f) ptexBase[f] = level.frames[f].ptex;
        for (int depth = 1; depth <= 3; ++depth) {
            const uint32_t F = level.topo.faceCount();
            std::vector<uint8_t> selected(F, depth == 1 ? 1 : 0);
            for (uint32_t f = 0; f < F && depth > 1; ++f) selected[f] = (f * 2654435761u >> 29) < 2;
            // withTwins given the constructor's own twins gives the constructor's topology
            // (level 0: faces of any size).
            const Topology& t = level.topo;
            EXPECT_EQ(fanMismatches(t), 0u) << "depth " << depth - 1;
            if (t.nonManifoldEdgeCount() == 0) {
                std::vector<uint32_t> offsets{0}, corners, twins;
                for (uint32_t f = 0; f < t.faceCount(); ++f) {
                    auto fv = t.faceVertices(f);
                    corners.insert(corners.end(), fv.begin(), fv.end());
                    offsets.push_back(uint32_t(corners.size()));
                }
                for (uint32_t h = 0; h < t.halfedgeCount(); ++h) twins.push_back(t.twin(h));
                EXPECT_TRUE(Topology::withTwins(t.vertexCount(), offsets, corners, twins) == t);
            }
            Level child = refineLevelTopology(level, selected, options, ptexBase);
            ASSERT_TRUE(child.topo == rebuilt(child.topo)) << "depth " << depth;
            // The chains' copies of a few faces' one-rings (localLevel) likewise.
            for (uint32_t f = 0; f < child.topo.faceCount(); f += 1 + child.topo.faceCount() / 8) {
                std::vector<uint32_t> faces, support;
                for (uint32_t v : child.topo.faceVertices(f))
                    for (uint32_t h : child.topo.vertexOutgoing(v)) faces.push_back(child.topo.face(h));
                for (uint32_t g : faces)
                    for (uint32_t v : child.topo.faceVertices(g))
                        if (std::find(support.begin(), support.end(), v) == support.end()) support.push_back(v);
                uint32_t face0 = 0;
                const Level copy = localLevel(child, support, faces, f, 0, face0);
                EXPECT_TRUE(copy.topo == rebuilt(copy.topo)) << "depth " << depth << " face " << f;
            }
            ++levels;
            level = std::move(child);
        }
    }
    EXPECT_GT(levels, 3 * 50u);
    EXPECT_TRUE(Topology() == Topology(0, std::vector<uint32_t>{0}, {}));
}
