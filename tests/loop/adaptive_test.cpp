// Adaptive refinement on real meshes: the result is conforming (no T-junctions), manifold where the
// input was, consistently oriented, keeps the boundary and the UV layout, E = 0 gives uniform Loop
// and a huge E gives the input back. In exact mode every vertex is a vertex of OpenSubdiv's
// uniform refinement of the input.
#include "loop/adaptive.h"
#include "mesh/import.h"
#include "osd_oracle.h"
#include "test_support.h"
#include "tri_mesh_models.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <map>
#include <set>

using namespace limn;
using namespace limn::loop;

namespace {

struct Shape {
    int euler = 0, boundaryLoops = 0, boundaryEdges = 0;
};

// Euler characteristic and boundary loops, from limn's half-edge topology; fails the test on any
// non-manifold or inconsistently oriented edge or vertex.
Shape shapeOf(const TriMesh& m) {
    Topology topo = triangleTopology(m.vertexCount(), m.triangles);
    EXPECT_EQ(topo.nonManifoldEdgeCount(), 0u);
    for (uint32_t v = 0; v < topo.vertexCount(); ++v) EXPECT_FALSE(topo.vertexIsNonManifold(v)) << v;
    Shape s;
    s.euler = static_cast<int>(m.vertexCount()) - static_cast<int>(topo.edgeCount()) +
              static_cast<int>(m.triangleCount());
    // Boundary half-edges chained by their vertices form the loops.
    std::map<uint32_t, uint32_t> nextOnBoundary;
    for (uint32_t h = 0; h < topo.halfedgeCount(); ++h)
        if (topo.twin(h) == kNone) nextOnBoundary[topo.vertex(h)] = topo.destination(h);
    s.boundaryEdges = static_cast<int>(nextOnBoundary.size());
    std::set<uint32_t> seen;
    for (auto [start, unused] : nextOnBoundary) {
        if (seen.count(start)) continue;
        ++s.boundaryLoops;
        for (uint32_t v = start; !seen.count(v); v = nextOnBoundary[v]) seen.insert(v);
    }
    return s;
}

double uvArea(const TriMesh& m) {
    double area = 0;
    for (const Tri& t : m.uvTriangles) {
        glm::dvec2 a = m.uvs[t[0]], b = m.uvs[t[1]], c = m.uvs[t[2]];
        area += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    }
    return area;
}

double signedVolume(const TriMesh& m) {
    double v = 0;
    for (const Tri& t : m.triangles)
        v += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6;
    return v;
}

struct Case {
    std::string model;
    int levels;
    double epsilon;
    Positions positions;
    Metric metric;
    EvenUpdate even;
};

std::ostream& operator<<(std::ostream& os, const Case& c) {
    return os << c.model << " L" << c.levels << " eps " << c.epsilon;
}

class AdaptiveMesh : public ::testing::TestWithParam<Case> {};

TEST_P(AdaptiveMesh, ConformingOrientedAndBoundaryPreserved) {
    const Case& c = GetParam();
    TriMesh input = test::loadTriMesh(c.model);
    AdaptiveOptions o;
    o.levels = c.levels;
    o.epsilon = c.epsilon;
    o.positions = c.positions;
    o.metric = c.metric;
    o.evenUpdate = c.even;
    AdaptiveResult r = subdivide(input, o);
    const TriMesh& m = r.mesh;

    // A real mix of levels: more than the input, fewer than uniform.
    AdaptiveOptions u = o;
    u.uniform = true;
    uint32_t uniformVertices = subdivide(input, u).mesh.vertexCount();
    EXPECT_GT(m.vertexCount(), input.vertexCount());
    EXPECT_LT(m.vertexCount(), uniformVertices);

    // Conforming: a T-junction would leave the two sides of an edge unmatched, which shows up as
    // extra boundary edges and loops (or breaks manifoldness); a closed input stays closed.
    Shape before = shapeOf(input), after = shapeOf(m);
    EXPECT_EQ(after.euler, before.euler);
    EXPECT_EQ(after.boundaryLoops, before.boundaryLoops);
    if (before.boundaryEdges == 0) {
        EXPECT_EQ(after.boundaryEdges, 0);
    }
    // Control vertices keep their place on or off the boundary.
    Topology t0 = triangleTopology(input.vertexCount(), input.triangles);
    Topology t1 = triangleTopology(m.vertexCount(), m.triangles);
    for (uint32_t v = 0; v < input.vertexCount(); ++v)
        ASSERT_EQ(t0.vertexIsBoundary(v), t1.vertexIsBoundary(v)) << "vertex " << v;

    // Consistent orientation keeps the enclosed volume's sign on closed meshes.
    if (before.boundaryEdges == 0) {
        EXPECT_GT(signedVolume(m) * signedVolume(input), 0);
    }
    // Linear UVs: the children of a triangle tile it in UV space, so the total is unchanged.
    if (input.hasUVs()) {
        EXPECT_NEAR(uvArea(m), uvArea(input), 1e-9 * std::abs(uvArea(input)) + 1e-12);
    }
    // Creases name edges of the result.
    for (const VertexPair& p : m.creases) EXPECT_NE(t1.findEdge(p[0], p[1]), kNone);

    // Per-level counts agree with the result.
    ASSERT_FALSE(r.levels.empty());
    EXPECT_EQ(r.levels.back().vertices, m.vertexCount());
    EXPECT_EQ(r.levels.back().faces, m.triangleCount());
}

std::string caseName(const ::testing::TestParamInfo<Case>& p) {
    std::string n = std::filesystem::path(p.param.model).stem().string();
    n += p.param.positions == Positions::Exact ? "_exact" : "_paper";
    n += p.param.metric == Metric::Full ? "_full" : p.param.metric == Metric::Normal ? "_normal" : "_chord";
    n += p.param.even == EvenUpdate::Split ? "_split" : "_all";
    return n + "_" + std::to_string(p.index);
}

constexpr Positions E = Positions::Exact, P = Positions::Paper;
constexpr Metric F = Metric::Full, N = Metric::Normal, C = Metric::Chord;
constexpr EvenUpdate S = EvenUpdate::Split, A = EvenUpdate::All;

INSTANTIATE_TEST_SUITE_P(
    Shapes, AdaptiveMesh,
    ::testing::Values(Case{"tri/cube_no_bottom.obj", 3, 2e-3, E, F, S}, Case{"tri/cube_no_bottom.obj", 3, 2e-3, P, F, S},
                      Case{"osd/loop/loop_fvar_bound1.obj", 3, 1e-3, E, F, A},
                      Case{"osd/loop/loop_fvar_bound1.obj", 3, 1e-3, P, N, A},
                      Case{"osd/loop/loop_icos_infsharp.obj", 3, 2e-3, E, F, S},
                      Case{"osd/loop/loop_icos_infsharp.obj", 3, 2e-3, P, F, A},
                      Case{"osd/loop/loop_triangle_edgecorner.obj", 3, 1e-3, E, C, S},
                      Case{"tri/spot_triangulated.obj", 2, 4e-5, E, F, S},
                      Case{"tri/spot_triangulated.obj", 2, 4e-5, P, F, S},
                      Case{"tri/plane_holes.obj", 2, 2e-5, E, F, S},
                      Case{"tri/plane_holes.obj", 2, 2e-5, P, N, S},
                      Case{"tri/goathead.obj", 2, 4e-5, E, C, A}),
    caseName);

// E = 0 splits every edge: the uniform mesh, bit for bit (the uniform path is checked against
// OpenSubdiv in osd_uniform_test.cpp). A huge E splits nothing: the input comes back unchanged.
TEST(AdaptiveLimits, ZeroEpsilonIsUniformAndHugeEpsilonIsIdentity) {
    for (const char* model : {"tri/cube_no_bottom.obj", "tri/spot_triangulated.obj", "osd/loop/loop_icos_infsharp.obj"}) {
        TriMesh input = test::loadTriMesh(model);
        AdaptiveOptions u;
        u.uniform = true;
        u.levels = 2;
        TriMesh uniform = subdivide(input, u).mesh;
        for (Positions pos : {Positions::Exact, Positions::Paper})
            for (EvenUpdate even : {EvenUpdate::Split, EvenUpdate::All}) {
                AdaptiveOptions o;
                o.levels = 2;
                o.positions = pos;
                o.evenUpdate = even;
                o.epsilon = 0;
                TriMesh zero = subdivide(input, o).mesh;
                EXPECT_EQ(zero.positions, uniform.positions) << model;
                EXPECT_EQ(zero.triangles, uniform.triangles) << model;
                EXPECT_EQ(zero.uvs, uniform.uvs) << model;
                EXPECT_EQ(zero.uvTriangles, uniform.uvTriangles) << model;
                EXPECT_EQ(zero.creases, uniform.creases) << model;
                o.epsilon = 1e300;
                AdaptiveResult huge = subdivide(input, o);
                EXPECT_EQ(huge.mesh.positions, input.positions) << model;
                EXPECT_EQ(huge.mesh.triangles, input.triangles) << model;
                EXPECT_EQ(huge.mesh.uvs, input.uvs) << model;
                EXPECT_EQ(huge.mesh.uvTriangles, input.uvTriangles) << model;
                ASSERT_EQ(huge.levels.size(), 1u); // the first level splits nothing and stops
                EXPECT_EQ(huge.levels[0].splitEdges, 0u);
            }
    }
}

// Exact mode: every vertex of the result is a vertex of OpenSubdiv's uniform refinement of the
// input at some level 0..L, at its position there.
TEST(AdaptiveExact, VerticesLieOnOpenSubdivsHierarchy) {
    for (const char* model : {"tri/cube_no_bottom.obj", "osd/loop/loop_xord_boundary.obj",
                              "osd/loop/loop_icos_infsharp.obj"}) {
        Warnings w;
        Mesh mesh = importMeshFile(test::modelPath(model).string(), w);
        const int levels = 3;
        test::OsdLoop osd = test::osdUniformLoop(mesh, levels);
        const double tol = 1e-9 * boundingBoxDiagonal(mesh.positions);
        for (EvenUpdate even : {EvenUpdate::Split, EvenUpdate::All}) {
            AdaptiveOptions o;
            o.levels = levels;
            o.epsilon = 1e-3;
            o.evenUpdate = even;
            TriMesh m = subdivide(fromMesh(mesh, {}, w), o).mesh;
            int onLevel[4] = {0, 0, 0, 0};
            for (const glm::dvec3& p : m.positions) {
                int found = -1;
                for (int l = levels; l >= 0 && found < 0; --l)
                    for (const glm::dvec3& q : osd.positions[l])
                        if (glm::length(p - q) <= tol) {
                            found = l;
                            break;
                        }
                ASSERT_GE(found, 0) << model << ": vertex at (" << p.x << ", " << p.y << ", " << p.z
                                    << ") is on no level of the uniform hierarchy";
                ++onLevel[found];
            }
            EXPECT_GT(onLevel[levels], 0) << model; // the finest level is reached somewhere
            EXPECT_LT(m.vertexCount(), osd.positions[levels].size()) << model;
        }
    }
}

// The paper's mode re-applies the masks to the adaptive mesh; after the first level its vertices
// leave the uniform hierarchy where levels meet (the drift the exact mode avoids).
TEST(AdaptivePaper, DriftsOffTheHierarchyAtTransitions) {
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath("tri/cube_no_bottom.obj").string(), w);
    test::OsdLoop osd = test::osdUniformLoop(mesh, 2);
    AdaptiveOptions o;
    o.levels = 2;
    o.epsilon = 2e-3;
    o.positions = Positions::Paper;
    TriMesh m = subdivide(fromMesh(mesh, {}, w), o).mesh;
    const double tol = 1e-9 * boundingBoxDiagonal(mesh.positions);
    int off = 0;
    for (const glm::dvec3& p : m.positions) {
        bool on = false;
        for (const auto& level : osd.positions)
            for (const glm::dvec3& q : level) on = on || glm::length(p - q) <= tol;
        off += on ? 0 : 1;
    }
    EXPECT_GT(off, 0);
}

} // namespace
