// limn's subdivision tables against OpenSubdiv (the oracle): refined vertex positions, tiling of
// the ptex domains, regular patches and limit points on real meshes with extraordinary vertices,
// boundaries, creases, holes and non-quad faces.
#include "base/error.h"
#include "mesh/import.h"
#include "osd_oracle.h"
#include "subdiv/evaluate.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/tables.h"
#include "subdiv/tables_chunk.h"
#include "tables_fixture.h"
#include "test_support.h"
#include "topology/features.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <optional>
#include <tuple>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

using namespace limn;
using namespace limn::test;

namespace {

class Tables : public ::testing::TestWithParam<Case> {};

// Every vertex limn computes at level l coincides with a vertex of OpenSubdiv's uniform
// refinement at level l (Far::PrimvarRefiner::Interpolate), to float precision.
TEST_P(Tables, RefinedVerticesMatchOpenSubdiv) {
    Fixture f = build(GetParam());
    auto osd = test::osdUniformLevels(f.mesh, f.options, GetParam().depth);
    const double tol = 1e-6 * f.diag, cell = 1e-4 * f.diag;
    for (uint32_t l = 1; l <= f.tables.depth; ++l) {
        std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
        auto key = [&](glm::ivec3 c) {
            return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) |
                   (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) | uint64_t(uint32_t(c.z) & 0x1FFFFF);
        };
        for (uint32_t i = 0; i < osd[l].size(); ++i)
            grid[key(glm::ivec3(glm::floor(osd[l][i] / cell)))].push_back(i);
        const LevelInfo& info = f.tables.levels[l];
        size_t unmatched = 0;
        double worst = 0;
        for (uint32_t v = info.first; v < info.first + info.count(); ++v) {
            glm::ivec3 c(glm::floor(f.vertices[v] / cell));
            double best = 1e300;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
                        if (it == grid.end()) continue;
                        for (uint32_t i : it->second)
                            best = std::min(best, glm::length(osd[l][i] - f.vertices[v]));
                    }
            if (best > tol)
                ++unmatched;
            else
                worst = std::max(worst, best);
        }
        EXPECT_EQ(unmatched, 0u) << "level " << l << ": " << unmatched << " of " << info.count()
                                 << " vertices match no OpenSubdiv vertex within " << tol;
        EXPECT_LE(worst, tol);
    }
}

// For each ptex face, the patches and irregular faces cover its [0,1]^2 exactly once (sampled at
// the centres of a grid finer than the finest level); holes and faces without a limit surface
// are covered zero times.
TEST_P(Tables, DomainsTileEveryPtexFaceOnce) {
    Fixture f = build(GetParam());
    test::OsdLimitSurface osd(f.mesh, f.options, 2);
    const int res = 1 << (f.tables.depth + 1);
    std::vector<std::vector<uint8_t>> cover(osd.ptexFaceCount(),
                                            std::vector<uint8_t>(res * res, 0));
    auto paint = [&](uint32_t ptex, double u0, double v0, double size) {
        ASSERT_LT(ptex, cover.size());
        int i0 = int(std::lround(u0 * res)), j0 = int(std::lround(v0 * res)),
            n = int(std::lround(size * res));
        ASSERT_NEAR(u0 * res, i0, 1e-6);
        ASSERT_NEAR(v0 * res, j0, 1e-6);
        for (int j = j0; j < j0 + n; ++j)
            for (int i = i0; i < i0 + n; ++i) ++cover[ptex][j * res + i];
    };
    for (const auto& p : f.tables.patches) paint(p.ptex, p.u0, p.v0, p.size);
    for (const auto& q : f.tables.irregular) paint(q.ptex, q.u0, q.v0, q.size);
    for (int ptex = 0; ptex < osd.ptexFaceCount(); ++ptex) {
        glm::dvec3 P, N;
        bool hasLimit = osd.evaluate(ptex, 0.5, 0.5, P, N);
        for (int c = 0; c < res * res; ++c)
            ASSERT_EQ(cover[ptex][c], hasLimit ? 1 : 0) << "ptex " << ptex << " cell " << c;
    }
}

// Points on regular patches equal OpenSubdiv's limit surface at the same (ptex, u, v): relative
// 1e-5 of the bounding-box diagonal in position, 0.5 degrees in normal.
TEST_P(Tables, RegularPatchesMatchOpenSubdivLimit) {
    Fixture f = build(GetParam());
    test::OsdLimitSurface osd(f.mesh, f.options, 10);
    const double samples[3][2] = {{0.25, 0.5}, {0.75, 0.125}, {0.5, 0.875}};
    double worstP = 0, worstN = 0;
    for (const auto& p : f.tables.patches)
        for (const auto& st : samples) {
            SurfacePoint s = evaluatePatch(p, f.vertices, st[0], st[1]);
            double u = p.u0 + st[0] * p.size, v = p.v0 + st[1] * p.size;
            glm::dvec3 P, N;
            ASSERT_TRUE(osd.evaluate(int(p.ptex), u, v, P, N));
            worstP = std::max(worstP, glm::length(P - s.position) / f.diag);
            worstN = std::max(worstN, std::acos(std::min(1.0, glm::dot(N, s.normal))) * 180 / M_PI);
        }
    EXPECT_LE(worstP, 1e-5);
    EXPECT_LE(worstN, 0.5);
}

// Limit positions at the corners of the irregular faces equal OpenSubdiv's limit surface there,
// and so do the normals, except where limn's tables report the point as approximate (valence-2
// vertices and corner sectors whose normals converge like 1/level: the surface has no tangent
// plane there, exact_limits.h). At smooth corners the normal is checked by SmoothCornerNormal
// below instead: OpenSubdiv's end-cap patches fix it at the value of their isolation level,
// while the exact surface keeps turning toward limn's.
TEST_P(Tables, LimitPointsMatchOpenSubdiv) {
    Fixture f = build(GetParam());
    test::OsdLimitSurface osd(f.mesh, f.options, 10);
    auto smooth = test::smoothCorners(f.mesh, f.options);
    auto limits = evaluateLimitPoints(f.tables, f.vertices);
    static const double cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    double worstP = 0, worstN = 0;
    size_t compared = 0;
    for (const auto& q : f.tables.irregular)
        for (int k = 0; k < 4; ++k) {
            uint32_t li = q.corner[k];
            double u = q.u0 + cu[k] * q.size, v = q.v0 + cv[k] * q.size;
            // Pick OpenSubdiv's patch that has this corner and lies inside this face (the side
            // of a crease matters; near extraordinary vertices its patches are much smaller).
            // OpenSubdiv's derivatives can degenerate exactly at a patch corner, so its normal is
            // taken a millionth of the face size inside (the position at the corner itself).
            double du = (cu[k] ? -1e-6 : 1e-6) * q.size, dv = (cv[k] ? -1e-6 : 1e-6) * q.size;
            glm::dvec3 P, N, Pin;
            ASSERT_TRUE(osd.evaluate(int(q.ptex), u, v, u + du, v + dv, P, N));
            ASSERT_TRUE(osd.evaluate(int(q.ptex), u + du, v + dv, Pin, N));
            worstP = std::max(worstP, glm::length(P - limits[li].position) / f.diag);
            int bv = test::baseVertexAt(f.mesh, q.ptex, u, v);
            if ((bv < 0 || !smooth[bv]) && f.tables.limitExact[li])
                worstN = std::max(worstN, std::acos(std::min(1.0, glm::dot(N, limits[li].normal))) *
                                              180 / M_PI);
            ++compared;
        }
    EXPECT_LE(worstP, 1e-5) << compared << " corners compared";
    EXPECT_LE(worstN, 0.5) << compared << " corners compared";
}

// A smooth corner's subdivision matrix has a Jordan block in the cross direction, so normals near
// it converge like 1/level. The exact B-spline patches of a deep isolation approach the corner;
// their normals must keep turning toward limn's corner normal, past OpenSubdiv's value (which
// freezes at its end-cap level).
// A model's tables at depth 14 (patches close to its smooth corners), their vertices and limits.
struct DeepTables {
    Mesh m;
    SchemeOptions o;
    limn::Tables t;
    std::vector<glm::dvec3> V;
    std::vector<LimitPoint> L;
};
DeepTables deepTables(const std::string& model) {
    DeepTables d;
    Warnings w;
    d.m = importMeshFile(test::modelPath(model).string(), w);
    d.o = resolveSchemeOptions(d.m.tags, {});
    TablesOptions opts;
    opts.depth = 14;
    d.t = buildTables(d.m, d.o, opts, w);
    d.V = evaluateVertices(d.t, d.m.positions);
    d.L = evaluateLimitPoints(d.t, d.V);
    return d;
}

TEST(SmoothCorner, DeepPatchNormalsConvergeToLimnsCornerNormal) {
    const auto [m, o, t, V, L] = deepTables("quad/osd_catmark_fvar_bound2.obj");
    // The corner (0,0) of ptex 0 is base vertex 0, a smooth corner.
    ASSERT_EQ(test::baseVertexAt(m, 0, 0, 0), 0);
    ASSERT_TRUE(test::smoothCorners(m, o)[0]);
    glm::dvec3 corner(0);
    for (const auto& q : t.irregular)
        if (q.ptex == 0 && q.u0 == 0 && q.v0 == 0) corner = L[q.corner[0]].normal;
    ASSERT_NE(glm::length(corner), 0.0);
    test::OsdLimitSurface osd(m, o, 10);
    glm::dvec3 P, Nosd;
    ASSERT_TRUE(osd.evaluate(0, 1e-9, 1e-9, P, Nosd));
    double osdAngle = std::acos(std::min(1.0, glm::dot(Nosd, corner)));
    std::vector<double> angles(15, -1);
    for (const auto& p : t.patches)
        if (p.ptex == 0 && p.u0 == 0 && p.v0 == p.size) // the patch just above the corner
            angles[p.level] =
                std::acos(std::min(1.0, glm::dot(evaluatePatch(p, V, 0, 0).normal, corner)));
    for (int l = 6; l <= 14; ++l) {
        ASSERT_GE(angles[l], 0) << "no patch at level " << l;
        EXPECT_LT(angles[l], angles[l - 1]) << "level " << l;
    }
    EXPECT_LT(angles[14], osdAngle) << "the exact surface turns past OpenSubdiv's corner normal";
}

// Boundary rule None with both boundary edges of a one-face vertex tagged sharp
// (catmark_edgenone's base vertex 51, ptex 29's corner (1, 0)) is the crease rule too: a smooth
// corner, left out of the normal checks like the edge-only ones. There the surface does not turn:
// the exact patches of a deep isolation beside the corner and OpenSubdiv's normal a billionth
// inside both give limn's corner normal, while OpenSubdiv's du x dv exactly at the corner (what
// bench_accuracy --ply compared before) is 25 degrees off.
TEST(SmoothCorner, BoundaryNoneCornerHasTheSurfacesNormal) {
    const auto [m, o, t, V, L] = deepTables("osd/catmark/catmark_edgenone.obj");
    ASSERT_EQ(o.boundary, BoundaryRule::None);
    ASSERT_EQ(test::baseVertexAt(m, 29, 1, 0), 51);
    ASSERT_TRUE(test::smoothCorners(m, o)[51]);
    glm::dvec3 corner(0); // corner 1 of the irregular leaf at (1, 0) is at (u0 + size, v0)
    for (const auto& q : t.irregular)
        if (q.ptex == 29 && q.u0 + q.size == 1.0f && q.v0 == 0.0f) corner = L[q.corner[1]].normal;
    ASSERT_NE(glm::length(corner), 0.0);
    auto degrees = [&](const glm::dvec3& n) { return std::acos(std::min(1.0, glm::dot(n, corner))) * 180 / M_PI; };
    double deep = -1; // the level-14 patch beside the leaf along v, at its point nearest the corner
    for (const auto& p : t.patches)
        if (p.ptex == 29 && p.level == 14 && p.u0 + p.size == 1.0f && p.v0 == p.size)
            deep = degrees(evaluatePatch(p, V, 1, 0).normal);
    ASSERT_GE(deep, 0) << "no level-14 patch beside the corner";
    EXPECT_LT(deep, 1e-4);
    test::OsdLimitSurface osd(m, o, 10);
    glm::dvec3 P, N;
    ASSERT_TRUE(osd.evaluate(29, 1 - 1e-9, 1e-9, P, N));
    EXPECT_LT(degrees(N), 0.01);
}

// OpenSubdiv parity: regular faces along infinitely sharp creases are boundary patches, so a creased
// model no longer pays the deep levels along its creases. catmark_cube_creases2 at depth 5:
// OpenSubdiv with useInfSharpPatch draws 96 patches (1,764 without); limn's elements (patches
// plus irregular faces) were 1,764 before, as many as OpenSubdiv's, and are with the option off.
TEST(InfSharpPatches, CreasesAreNotIsolatedToTheLastLevel) {
    Warnings w;
    Mesh m = importMeshFile(test::modelPath("osd/catmark/catmark_cube_creases2.obj").string(), w);
    SchemeOptions o = resolveSchemeOptions(m.tags, {});
    TablesOptions opts;
    opts.depth = 5;
    opts.infSharpPatches = false;
    auto off = buildTables(m, o, opts, w);
    opts.infSharpPatches = true;
    auto on = buildTables(m, o, opts, w);
    EXPECT_EQ(off.patches.size() + off.irregular.size(), 1764u);
    EXPECT_LE(on.patches.size() + on.irregular.size(), 96u);
    // Some patches have a boundary bit on an edge that is no mesh boundary (the mesh is closed).
    size_t creasePatches = 0;
    for (const auto& p : on.patches) creasePatches += p.boundary != 0;
    EXPECT_GT(creasePatches, 0u);
    for (const auto& p : off.patches) EXPECT_EQ(p.boundary, 0);
}

// Interior vertices with two faces and fewer than two infinitely sharp edges, counted from the
// mesh's faces and tags alone (an edge shared by two faces is interior): the valence-2 vertices
// whose limit surface has no tangent plane (two sharp edges make a crease, which has one).
size_t interiorValence2(const Mesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, int> edgeFaces;
    std::vector<int> faces(m.vertexCount(), 0), sharp(m.vertexCount(), 0);
    for (size_t f = 0; f < m.faceCount(); ++f) {
        auto face = m.face(f);
        for (size_t k = 0; k < face.size(); ++k) {
            uint32_t a = face[k], b = face[(k + 1) % face.size()];
            ++edgeFaces[{std::min(a, b), std::max(a, b)}];
            ++faces[a];
        }
    }
    std::vector<uint8_t> onBoundary(m.vertexCount(), 0);
    for (const auto& [e, n] : edgeFaces)
        if (n != 2) onBoundary[e.first] = onBoundary[e.second] = 1;
    for (const auto& c : m.tags.creases)
        if (c.sharpness >= 10) ++sharp[c.v0], ++sharp[c.v1];
    size_t count = 0;
    for (size_t v = 0; v < m.vertexCount(); ++v)
        count += faces[v] == 2 && !onBoundary[v] && sharp[v] < 2;
    return count;
}

// Exact limit points: at depth 3 every limit point of every OpenSubdiv catmark shape limn accepts is exact
// (undecayed semi-sharp features isolated deeper, darts, cones and corners from the eigenvectors
// of their local subdivision matrix), except the ones whose surface has no tangent plane:
// valence-2 vertices (one each) and, in the two inf_crease shapes, two faces of a corner sector
// whose subdivision matrix has a Jordan block (normals converge like 1/level, as at smooth
// corners; OpenSubdiv's own normals there change by degrees between isolation 9 and 10).
TEST(ExactLimits, NoApproximateLimitPointsOnCatmarkShapes) {
    size_t shapes = 0;
    for (const std::string& name : test::filesIn(test::modelPath("osd/catmark"))) {
        if (name.size() < 4 || name.substr(name.size() - 4) != ".obj") continue;
        const std::string path = test::modelPath("osd/catmark/" + name).string();
        Warnings w;
        Mesh m;
        limn::Tables t;
        try {
            m = importMeshFile(path, w);
            TablesOptions opts;
            opts.depth = 3;
            t = buildTables(m, resolveSchemeOptions(m.tags, {}), opts, w);
        } catch (const Error&) {
            continue; // non-manifold or degenerate: limn refuses it (tested elsewhere)
        }
        ++shapes;
        size_t expected = interiorValence2(m);
        if (name == "catmark_inf_crease0.obj" || name == "catmark_inf_crease1.obj") expected = 2;
        EXPECT_EQ(t.approximateLimitPoints, expected) << name;
    }
    EXPECT_GE(shapes, 75u);
}

const Case kCases[] = {
    {"quad/spot_control_mesh.obj", 1, false},
    {"quad/spot_control_mesh.obj", 3, false},
    {"quad/spot_control_mesh.obj", 2, true},
    {"quad/blub_control_mesh.obj", 4, false},
    {"quad/osd_catmark_xord_boundary.obj", 3, false},
    // Every boundary rule on boundary vertices of valence 2 to 7 (the tag says edge-and-corner).
    {"quad/osd_catmark_xord_boundary.obj", 3, false, BoundaryRule::EdgeOnly},
    {"quad/osd_catmark_xord_boundary.obj", 3, true, BoundaryRule::EdgeOnly},
    {"quad/osd_catmark_xord_boundary.obj", 2, false, BoundaryRule::None},
    {"quad/osd_catmark_fvar_bound2.obj", 3, false},
    {"quad/osd_catmark_torus.obj", 2, false},
    {"quad/osd_catmark_pyramid.obj", 3, false},
    {"osd/catmark/catmark_cube_creases0.obj", 3, false},
    {"osd/catmark/catmark_cube_creases2.obj", 3, false},
    {"osd/catmark/catmark_cubes_semisharp.obj", 4, false},
    {"osd/catmark/catmark_chaikin1.obj", 3, false},
    {"osd/catmark/catmark_hole_test2.obj", 3, false},
    {"osd/catmark/catmark_hole_test3.obj", 2, false},
    {"osd/catmark/catmark_nonquads.obj", 3, false},
    {"osd/catmark/catmark_edgecorner.obj", 3, false},
    {"osd/catmark/catmark_edgeonly.obj", 3, false},
    {"osd/catmark/catmark_edgenone.obj", 2, false},
    {"osd/catmark/catmark_smoothtris1.obj", 2, false},
    {"osd/catmark/catmark_gregory_test3.obj", 3, false},
    {"osd/catmark/catmark_tent_creases1.obj", 3, false},
    {"osd/catmark/catmark_helmet.obj", 2, false},
    // Limit points that were approximate at depth 3 (undecayed semi-sharp creases of
    // sharpness up to 6, uniform and Chaikin; darts; cone points; valence 2), now exact.
    {"osd/catmark/catmark_helmet.obj", 3, false},
    {"osd/catmark/catmark_car.obj", 3, false},
    {"osd/catmark/catmark_pawn.obj", 3, false},
    {"osd/catmark/catmark_rook.obj", 3, false},
    {"osd/catmark/catmark_cube_creases1.obj", 3, false},
    {"osd/catmark/catmark_cube_creases1.obj", 2, true},
    {"osd/catmark/catmark_chaikin0.obj", 3, false},
    {"osd/catmark/catmark_single_crease.obj", 3, false},
    {"osd/catmark/catmark_torus_creases1.obj", 3, false},
    {"osd/catmark/catmark_pyramid_creases2.obj", 3, false},
    {"osd/catmark/catmark_gregory_test7.obj", 3, false},
    {"osd/catmark/catmark_dart_edgeonly.obj", 3, false},
    {"osd/catmark/catmark_dart_edgecorner.obj", 3, false},
    {"osd/catmark/catmark_inf_crease0.obj", 3, false},
    {"osd/catmark/catmark_cube_corner4.obj", 3, false},
    {"osd/catmark/catmark_cubes_infsharp.obj", 3, false},
    {"osd/catmark/catmark_val2_interior.obj", 3, false},
    {"osd/catmark/catmark_gregory_test8.obj", 3, false},
    // Infinitely sharp crease and corner patches (OpenSubdiv's useInfSharpPatch).
    {"osd/catmark/catmark_cube_creases2.obj", 5, false},
    {"osd/catmark/catmark_cube_corner4.obj", 4, false},
    {"osd/catmark/catmark_fvar_project0.obj", 3, false},
};

INSTANTIATE_TEST_SUITE_P(Shared, Tables, ::testing::ValuesIn(kCases), caseName);

} // namespace
