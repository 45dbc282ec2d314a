// Uniform Loop refinement (refine() with every edge split, as `limn-loop --uniform` runs it) equals
// OpenSubdiv's Sdc::SCHEME_LOOP uniform refinement vertex for vertex, face for face and UV for UV,
// and limit positions equal PrimvarRefiner::Limit, on OpenSubdiv's Loop regression shapes and the
// shared triangle meshes. Vertices are matched through their parents (OpenSubdiv's
// GetVertexChildVertex / GetEdgeChildVertex), not through limn's ordering.
#include "loop/adaptive.h"
#include "loop/rules.h"
#include "mesh/import.h"
#include "osd_oracle.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <map>

using namespace limn;
using namespace limn::loop;

namespace {

struct Case {
    std::string model;
    int levels;
};

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.model << " L" << c.levels; }

// Float precision relative to the model's size (both sides compute in double; only the order
// of the additions differs).
constexpr double kTolerance = 1e-9;

std::string caseName(const ::testing::TestParamInfo<Case>& p) {
    return std::filesystem::path(p.param.model).stem().string() + "_L" +
           std::to_string(p.param.levels);
}

class UniformVsOsd : public ::testing::TestWithParam<Case> {};

TEST_P(UniformVsOsd, PositionsFacesUVsAndLimits) {
    const Case& c = GetParam();
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath(c.model).string(), w);
    test::OsdLoop osd = test::osdUniformLoop(mesh, c.levels);
    TriMesh cur = fromMesh(mesh, {}, w);
    const double tol = kTolerance * boundingBoxDiagonal(mesh.positions);
    namespace Far = OpenSubdiv::Far;

    std::vector<int> toOsd(cur.vertexCount()); // limn vertex -> OpenSubdiv vertex of this level
    for (size_t v = 0; v < toOsd.size(); ++v) toOsd[v] = static_cast<int>(v);
    for (int l = 1; l <= c.levels; ++l) {
        const Far::TopologyLevel& parent = osd.level(l - 1);
        const Far::TopologyLevel& child = osd.level(l);
        Refinement r;
        {
            Level level(cur);
            auto even = evenPositions(level), odd = oddPositions(level);
            std::vector<uint8_t> all(level.topology().edgeCount(), 1);
            r = refine(level, all, EvenUpdate::All, even, odd);
        }
        const uint32_t oldCount = cur.vertexCount();
        ASSERT_EQ(r.mesh.vertexCount(), static_cast<uint32_t>(child.GetNumVertices())) << "level " << l;
        ASSERT_EQ(r.mesh.triangleCount(), static_cast<uint32_t>(child.GetNumFaces())) << "level " << l;
        std::vector<int> next(r.mesh.vertexCount(), -1);
        for (uint32_t v = 0; v < oldCount; ++v) next[v] = parent.GetVertexChildVertex(toOsd[v]);
        for (size_t i = 0; i < r.oddParents.size(); ++i) {
            int e = parent.FindEdge(toOsd[r.oddParents[i][0]], toOsd[r.oddParents[i][1]]);
            ASSERT_GE(e, 0);
            next[oldCount + i] = parent.GetEdgeChildVertex(e);
        }
        toOsd = next;
        for (uint32_t v = 0; v < r.mesh.vertexCount(); ++v)
            ASSERT_LE(glm::length(r.mesh.positions[v] - osd.positions[l][toOsd[v]]), tol)
                << "level " << l << " vertex " << v;

        // Faces: the same corner cycles (any rotation), and the same UV at every corner.
        std::map<std::array<int, 3>, std::pair<int, int>> osdFaces; // -> (face, rotation)
        for (int f = 0; f < child.GetNumFaces(); ++f) {
            auto fv = child.GetFaceVertices(f);
            int k = 0;
            for (int i = 1; i < 3; ++i)
                if (fv[i] < fv[k]) k = i;
            osdFaces[{fv[k], fv[(k + 1) % 3], fv[(k + 2) % 3]}] = {f, k};
        }
        for (uint32_t f = 0; f < r.mesh.triangleCount(); ++f) {
            const Tri& t = r.mesh.triangles[f];
            int k = 0;
            for (int i = 1; i < 3; ++i)
                if (toOsd[t[i]] < toOsd[t[k]]) k = i;
            std::array<int, 3> key{toOsd[t[k]], toOsd[t[(k + 1) % 3]], toOsd[t[(k + 2) % 3]]};
            auto it = osdFaces.find(key);
            ASSERT_NE(it, osdFaces.end()) << "level " << l << " face " << f << " has no OpenSubdiv twin";
            if (!mesh.hasUVs()) continue;
            auto [osdFace, osdRotation] = it->second;
            auto fvv = child.GetFaceFVarValues(osdFace, 0);
            for (int i = 0; i < 3; ++i) {
                glm::dvec2 mine = r.mesh.uvs[r.mesh.uvTriangles[f][(k + i) % 3]];
                glm::dvec2 theirs = osd.uvs[l][fvv[(osdRotation + i) % 3]];
                ASSERT_LE(glm::length(mine - theirs), 1e-12) << "level " << l << " face " << f;
            }
        }
        cur = std::move(r.mesh);
    }

    // Limit positions of the last level's vertices (math.md B.2/B.3 vs PrimvarRefiner::Limit).
    Level last(cur);
    auto limit = limitPositions(last);
    for (uint32_t v = 0; v < cur.vertexCount(); ++v)
        ASSERT_LE(glm::length(limit[v] - osd.limit[toOsd[v]]), tol) << "limit of vertex " << v;

    // The level loop (what --uniform runs) gives the same mesh as the steps above.
    AdaptiveOptions uniform;
    uniform.uniform = true;
    uniform.levels = c.levels;
    AdaptiveResult u = subdivide(fromMesh(mesh, {}, w), uniform);
    EXPECT_EQ(u.mesh.positions, cur.positions);
    EXPECT_EQ(u.mesh.triangles, cur.triangles);
}

INSTANTIATE_TEST_SUITE_P(
    LoopShapes, UniformVsOsd,
    ::testing::Values(Case{"osd/loop/loop_cube.obj", 3}, Case{"osd/loop/loop_cube_asymmetric.obj", 3},
                      Case{"osd/loop/loop_cubes_infsharp.obj", 3},
                      Case{"osd/loop/loop_fvar_bound0.obj", 3}, Case{"osd/loop/loop_fvar_bound1.obj", 3},
                      Case{"osd/loop/loop_fvar_bound3.obj", 3},
                      Case{"osd/loop/loop_icos_infsharp.obj", 3},
                      Case{"osd/loop/loop_icosahedron.obj", 3}, Case{"osd/loop/loop_pole8.obj", 3},
                      Case{"osd/loop/loop_pole64.obj", 2}, Case{"osd/loop/loop_pole360.obj", 2},
                      Case{"osd/loop/loop_saddle_edgecorner.obj", 3},
                      Case{"osd/loop/loop_saddle_edgeonly.obj", 3},
                      Case{"osd/loop/loop_tetrahedron.obj", 3}, Case{"osd/loop/loop_toroidal_tet.obj", 3},
                      Case{"osd/loop/loop_triangle_edgecorner.obj", 3},
                      Case{"osd/loop/loop_triangle_edgenone.obj", 3},
                      Case{"osd/loop/loop_xord_boundary.obj", 3},
                      Case{"osd/loop/loop_xord_interior.obj", 3}),
    caseName);

INSTANTIATE_TEST_SUITE_P(
    TriangleMeshes, UniformVsOsd,
    ::testing::Values(Case{"tri/cube_no_bottom.obj", 3}, Case{"tri/sphere.obj", 2},
                      Case{"tri/torus.obj", 1}, Case{"tri/osd_loop_xord_boundary.obj", 2},
                      Case{"tri/spot_triangulated.obj", 1}, Case{"tri/plane_holes.obj", 1},
                      Case{"tri/goathead.obj", 1}),
    caseName);

// Limits on the control mesh itself (level 0, where every face is a triangle, Limit() is exact
// for smooth, crease and corner vertices alike).
class LimitVsOsd : public ::testing::TestWithParam<std::string> {};

TEST_P(LimitVsOsd, ControlMeshLimits) {
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath(GetParam()).string(), w);
    test::OsdLoop osd = test::osdUniformLoop(mesh, 0);
    TriMesh tm = fromMesh(mesh, {}, w);
    Level level(tm);
    auto limit = limitPositions(level);
    const double tol = kTolerance * boundingBoxDiagonal(mesh.positions);
    for (uint32_t v = 0; v < tm.vertexCount(); ++v)
        ASSERT_LE(glm::length(limit[v] - osd.limit[v]), tol) << "vertex " << v;
}

INSTANTIATE_TEST_SUITE_P(Shapes, LimitVsOsd,
                         ::testing::Values("osd/loop/loop_triangle_edgecorner.obj",
                                           "osd/loop/loop_triangle_edgenone.obj",
                                           "osd/loop/loop_icos_infsharp.obj",
                                           "osd/loop/loop_cubes_infsharp.obj",
                                           "osd/loop/loop_xord_boundary.obj",
                                           "osd/loop/loop_pole360.obj", "tri/cat_lowres.obj",
                                           "tri/plane_holes.obj"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             return std::filesystem::path(p.param).stem().string();
                         });

} // namespace
