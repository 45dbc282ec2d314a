// The renderer's tessellation is watertight by construction: closed inputs give closed,
// consistently oriented triangle meshes without degenerate triangles, at every depth, adaptive
// and uniform, with and without the segment cap; points owned by regular patches lie on
// OpenSubdiv's limit surface.
#include "mesh/import.h"
#include "osd_oracle.h"
#include "subdiv/evaluate.h"
#include "tess/tessellation.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <map>

using namespace limn;

namespace {

struct Case {
    std::string model;
    int depth;
    bool uniform;
    uint32_t cap;
    bool closed;
    bool expectStitching = false;
};

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s + "_d" + std::to_string(info.param.depth) + (info.param.uniform ? "_uniform" : "") +
           "_cap" + std::to_string(info.param.cap);
}

class Tess : public ::testing::TestWithParam<Case> {};

TEST_P(Tess, ClosedOrientedAndNonDegenerate) {
    const Case& c = GetParam();
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath(c.model).string(), w);
    TablesOptions o;
    o.depth = c.depth;
    o.uniform = c.uniform;
    Tables t = buildTables(mesh, resolveSchemeOptions(mesh.tags, {}), o, w);
    Tessellation tess = buildTessellation(mesh, t, c.cap);
    ASSERT_EQ(tess.indices.size() % 3, 0u);
    ASSERT_FALSE(tess.indices.empty());
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t i = 0; i < tess.indices.size(); i += 3) {
        uint32_t a = tess.indices[i], b = tess.indices[i + 1], d = tess.indices[i + 2];
        ASSERT_LT(std::max({a, b, d}), tess.vertices.size());
        ASSERT_TRUE(a != b && b != d && a != d) << "degenerate triangle " << i / 3;
        ++directed[{a, b}];
        ++directed[{b, d}];
        ++directed[{d, a}];
    }
    size_t open = 0;
    for (const auto& [e, n] : directed) {
        EXPECT_EQ(n, 1) << "directed edge used twice: inconsistent orientation or overlap";
        if (!directed.count({e.second, e.first})) ++open;
    }
    if (c.closed) {
        EXPECT_EQ(open, 0u) << "edges used by one triangle in a closed surface";
    }
    // Every vertex is used by some triangle.
    std::vector<uint8_t> used(tess.vertices.size(), 0);
    for (uint32_t i : tess.indices) used[i] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    // Where the cap binds on a patch next to finer ones, stitching must have happened (so the
    // closedness above was checked on stitched edges, not only on matching grids).
    if (c.expectStitching) {
        EXPECT_GT(tess.stitchedEdges, 0u);
    }
}

// Every vertex owned by a regular patch is on OpenSubdiv's limit surface at its (ptex, u, v).
TEST_P(Tess, PatchVerticesLieOnTheLimitSurface) {
    const Case& c = GetParam();
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath(c.model).string(), w);
    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    TablesOptions o;
    o.depth = c.depth;
    o.uniform = c.uniform;
    Tables t = buildTables(mesh, so, o, w);
    Tessellation tess = buildTessellation(mesh, t, c.cap);
    auto V = evaluateVertices(t, mesh.positions);
    auto L = evaluateLimitPoints(t, V);
    auto pts = evaluateTessellation(t, tess, V, L);
    test::OsdLimitSurface osd(mesh, so, c.depth + 2);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    double worst = 0;
    for (size_t i = 0; i < pts.size(); i += 7) { // a sample keeps the test fast
        if (tess.vertices[i].element >= t.patches.size()) continue;
        PtexPoint pp = ptexOf(t, tess.vertices[i]);
        glm::dvec3 P, N;
        ASSERT_TRUE(osd.evaluate(int(pp.ptex), pp.u, pp.v, P, N));
        worst = std::max(worst, glm::length(P - pts[i].position) / diag);
    }
    EXPECT_LE(worst, 1e-5);
}

// Split at UV seams (for textures and displacement): copies share their first vertex's geometry,
// so mapping every index through `geometry` still gives the closed surface, and every copy
// carries a UV different from its first vertex's.
TEST(TessSplit, SeamCopiesShareGeometryAndCloseTheSurface) {
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath("quad/spot_control_mesh.obj").string(), w);
    TablesOptions o;
    o.depth = 2;
    Tables t = buildTables(mesh, resolveSchemeOptions(mesh.tags, {}), o, w);
    Tessellation plain = buildTessellation(mesh, t, 64, false);
    Tessellation split = buildTessellation(mesh, t, 64, true);
    ASSERT_EQ(split.geometry.size(), split.vertices.size());
    ASSERT_EQ(split.uvs.size(), split.vertices.size());
    size_t copies = 0;
    for (uint32_t v = 0; v < split.vertices.size(); ++v) {
        uint32_t g = split.geometry[v];
        ASSERT_LE(g, v);
        ASSERT_EQ(split.geometry[g], g);
        if (g == v) continue;
        ++copies;
        EXPECT_EQ(split.vertices[v].element, split.vertices[g].element);
        EXPECT_EQ(split.vertices[v].s, split.vertices[g].s);
        EXPECT_EQ(split.vertices[v].t, split.vertices[g].t);
        EXPECT_NE(split.uvs[v], split.uvs[g]);
    }
    EXPECT_GT(copies, 0u);
    EXPECT_EQ(split.vertices.size() - copies, plain.vertices.size());
    EXPECT_EQ(split.indices.size(), plain.indices.size());
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t i = 0; i < split.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = split.geometry[split.indices[i + k]], b = split.geometry[split.indices[i + (k + 1) % 3]];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    for (const auto& [e, n] : edges) EXPECT_EQ(n, 2);
}

const Case kCases[] = {
    {"quad/spot_control_mesh.obj", 1, false, 64, true},
    {"quad/spot_control_mesh.obj", 3, false, 64, true},
    {"quad/spot_control_mesh.obj", 4, false, 2, true, true},
    {"quad/spot_control_mesh.obj", 2, true, 64, true},
    {"quad/blub_control_mesh.obj", 3, false, 2, true, true},
    {"quad/osd_catmark_lefthanded.obj", 2, false, 64, true},
    {"quad/osd_catmark_toroidal_tet.obj", 4, false, 1, true},
    {"quad/osd_catmark_pyramid.obj", 3, false, 64, true},
    {"osd/catmark/catmark_cubes_semisharp.obj", 3, false, 2, true},
    {"quad/osd_catmark_xord_boundary.obj", 3, false, 64, false},
    {"osd/catmark/catmark_hole_test2.obj", 3, false, 2, false},
    {"osd/catmark/catmark_nonquads.obj", 2, false, 64, false},
    // Infinitely sharp creases and corners drawn as boundary and corner patches.
    {"osd/catmark/catmark_cube_creases2.obj", 5, false, 64, true},
    {"osd/catmark/catmark_cubes_infsharp.obj", 3, false, 2, true},
    {"osd/catmark/catmark_cube_corner4.obj", 3, false, 64, true},
    {"osd/catmark/catmark_inf_crease0.obj", 3, false, 64, false},
    {"osd/catmark/catmark_inf_crease1.obj", 3, false, 2, false},
};

INSTANTIATE_TEST_SUITE_P(Shared, Tess, ::testing::ValuesIn(kCases), caseName);

} // namespace
