// lib/topology's base-level features against OpenSubdiv's Far on every catmark regression shape:
// per vertex the boundary/non-manifold flags, valence, sharpness and rule; per edge the boundary/
// non-manifold flags and sharpness; per face whether it has a limit surface. features.h promises
// "base-level sharpness exactly as OpenSubdiv's Far factory prepares it"; this holds it to that.
#include "mesh/import.h"
#include "reference_mesh.h"
#include "test_support.h"
#include "topology/features.h"
#include "topology/topology.h"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <gtest/gtest.h>

#include <memory>

using namespace limn;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

std::unique_ptr<Far::TopologyRefiner> osdRefiner(const Mesh& m, BoundaryRule boundary) {
    std::vector<int> sizes, verts(m.faceVertices.begin(), m.faceVertices.end()), pairs, corners;
    std::vector<float> creaseWeights, cornerWeights;
    for (size_t f = 0; f < m.faceCount(); ++f) sizes.push_back(static_cast<int>(m.faceSize(f)));
    for (const auto& c : m.tags.creases) {
        pairs.push_back(static_cast<int>(c.v0));
        pairs.push_back(static_cast<int>(c.v1));
        creaseWeights.push_back(c.sharpness);
    }
    for (const auto& c : m.tags.corners) {
        corners.push_back(static_cast<int>(c.vertex));
        cornerWeights.push_back(c.sharpness);
    }
    std::vector<int> holes(m.tags.holes.begin(), m.tags.holes.end());
    Far::TopologyDescriptor d;
    d.numVertices = static_cast<int>(m.vertexCount());
    d.numFaces = static_cast<int>(m.faceCount());
    d.numVertsPerFace = sizes.data();
    d.vertIndicesPerFace = verts.data();
    d.numCreases = static_cast<int>(creaseWeights.size());
    d.creaseVertexIndexPairs = pairs.data();
    d.creaseWeights = creaseWeights.data();
    d.numCorners = static_cast<int>(cornerWeights.size());
    d.cornerVertexIndices = corners.data();
    d.cornerWeights = cornerWeights.data();
    d.numHoles = static_cast<int>(holes.size());
    d.holeIndices = holes.data();
    Sdc::Options o;
    // limn's BoundaryRule is numbered as Sdc's VtxBoundaryInterpolation (mesh.h).
    o.SetVtxBoundaryInterpolation(static_cast<Sdc::Options::VtxBoundaryInterpolation>(boundary));
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return std::unique_ptr<Far::TopologyRefiner>(
        Factory::Create(d, Factory::Options(Sdc::SCHEME_CATMARK, o)));
}

// Every catmark shape limn accepts; those with a face that uses a vertex twice are refused
// (tests/golden checks that).
std::vector<std::string> catmarkShapes() {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(test::modelPath("osd/catmark")))
        if (test::readReferenceObj(e.path().string()).firstDegenerateFace() < 0)
            out.push_back(e.path().stem().string());
    std::sort(out.begin(), out.end());
    return out;
}

// Every vertex, edge and face of `mesh` under all three boundary rules, not only its own tag.
void expectSameFeatures(const Mesh& mesh) {
    Warnings w;
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    for (BoundaryRule rule :
         {BoundaryRule::None, BoundaryRule::EdgeOnly, BoundaryRule::EdgeAndCorner}) {
        SCOPED_TRACE("boundary rule " + std::to_string(int(rule)));
        auto refiner = osdRefiner(mesh, rule);
        ASSERT_TRUE(refiner);
        const Far::TopologyLevel& L = refiner->GetLevel(0);
        Sharpness sharp = baseSharpness(topo, mesh.tags, rule, w);

        ASSERT_EQ(int(topo.edgeCount()), L.GetNumEdges());
        for (uint32_t v = 0; v < topo.vertexCount(); ++v) {
            SCOPED_TRACE("vertex " + std::to_string(v));
            if (topo.vertexIsIsolated(v)) continue;
            EXPECT_EQ(topo.vertexIsBoundary(v), L.IsVertexBoundary(int(v)));
            EXPECT_EQ(topo.vertexIsNonManifold(v), L.IsVertexNonManifold(int(v)));
            EXPECT_EQ(int(topo.vertexEdgeCount(v)), L.GetVertexEdges(int(v)).size());
            EXPECT_EQ(int(topo.vertexFaceCount(v)), L.GetVertexFaces(int(v)).size());
            EXPECT_EQ(sharp.vertex[v], L.GetVertexSharpness(int(v)));
            EXPECT_EQ(int(vertexRule(topo, sharp, v)), int(L.GetVertexRule(int(v))));
        }
        for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
            auto [a, b] = topo.edgeVertices(e);
            int oe = L.FindEdge(int(a), int(b));
            SCOPED_TRACE("edge " + std::to_string(a) + "-" + std::to_string(b));
            ASSERT_GE(oe, 0);
            EXPECT_EQ(topo.edgeIsBoundary(e), L.IsEdgeBoundary(oe));
            EXPECT_EQ(topo.edgeIsNonManifold(e), L.IsEdgeNonManifold(oe));
            EXPECT_EQ(sharp.edge[e], L.GetEdgeSharpness(oe));
        }
        for (uint32_t f = 0; f < topo.faceCount(); ++f)
            EXPECT_EQ(bool(sharp.faceNoLimit[f]), L.IsFaceHole(int(f))) << "face " << f;
    }
}

// The half-edge structure's own invariants, and its edge numbering: by first half-edge, i.e.
// in order of first appearance in face order (later stages rely on it being deterministic).
void expectConsistentHalfedges(const Mesh& mesh) {
    Topology t(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    std::vector<uint32_t> uses(t.edgeCount(), 0);
    uint32_t nextNew = 0;
    for (uint32_t h = 0; h < t.halfedgeCount(); ++h) {
        uint32_t e = t.edge(h);
        ASSERT_LT(e, t.edgeCount());
        if (uses[e]++ == 0) {
            EXPECT_EQ(e, nextNew++) << "edges are numbered by first half-edge";
            EXPECT_EQ(t.edgeHalfedge(e), h);
        }
        auto [a, b] = t.edgeVertices(e);
        EXPECT_EQ(std::minmax(a, b), std::minmax(t.vertex(h), t.destination(h)));
        if (uint32_t tw = t.twin(h); tw != kNone) {
            EXPECT_EQ(t.twin(tw), h);
            EXPECT_EQ(t.edge(tw), e);
            EXPECT_EQ(t.vertex(tw), t.destination(h));
        }
    }
    for (uint32_t e = 0; e < t.edgeCount(); ++e) {
        EXPECT_EQ(t.edgeFaceCount(e), uses[e]);
        bool twinned = t.twin(t.edgeHalfedge(e)) != kNone;
        EXPECT_EQ(twinned, uses[e] == 2 && !t.edgeIsNonManifold(e));
    }
}

class FeaturesVsOsd : public ::testing::TestWithParam<std::string> {};

TEST_P(FeaturesVsOsd, BaseLevelAgrees) {
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath("osd/catmark/" + GetParam() + ".obj").string(), w);
    expectSameFeatures(mesh);
    expectConsistentHalfedges(mesh);
}

// Three two-quad sheets share the polyline 1-0-2 (a non-manifold crease through vertex 0), and a
// fourth quad touches vertex 0 alone. Far sharpens vertex 0 because it also has boundary edges;
// it would leave it smooth on a plain non-manifold crease (the second mesh).
TEST(FeaturesVsOsdConstructed, NonManifoldCreaseVertex) {
    Mesh fins;
    fins.positions.resize(15);
    for (uint32_t i = 0; i < 3; ++i) {
        uint32_t p = 3 + 3 * i, q = 4 + 3 * i, r = 5 + 3 * i;
        fins.addFace(std::vector<uint32_t>{1, 0, p, q});
        fins.addFace(std::vector<uint32_t>{0, 2, r, p});
    }
    Mesh withDangling = fins;
    withDangling.addFace(std::vector<uint32_t>{0, 12, 13, 14});
    fins.positions.resize(12);
    {
        SCOPED_TRACE("fins only");
        expectSameFeatures(fins);
    }
    {
        SCOPED_TRACE("fins and a dangling quad");
        expectSameFeatures(withDangling);
    }
}

INSTANTIATE_TEST_SUITE_P(Catmark, FeaturesVsOsd, ::testing::ValuesIn(catmarkShapes()),
                         [](const auto& p) { return p.param; });

} // namespace
