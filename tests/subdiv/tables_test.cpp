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

namespace {

struct Case {
    std::string model;
    int depth;
    bool uniform;
    std::optional<BoundaryRule> boundary = {}; // overrides the mesh's tag (limn-classify --boundary)
};
void PrintTo(const Case& c, std::ostream* os) {
    *os << c.model << " depth " << c.depth << (c.uniform ? " uniform" : " adaptive");
    if (c.boundary) *os << " boundary rule " << int(*c.boundary);
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    static const char* rules[] = {"_bnone", "_bedge", "_bedgecorner"};
    return s + "_d" + std::to_string(info.param.depth) + (info.param.uniform ? "_uniform" : "") +
           (info.param.boundary ? rules[int(*info.param.boundary)] : "");
}

double diagonal(const Mesh& m) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return glm::length(hi - lo);
}

struct Fixture {
    Mesh mesh;
    SchemeOptions options;
    Tables tables;
    std::vector<glm::dvec3> vertices;
    double diag = 1;
};

// `bases`: boundary bases and interior bases with features on their rim (the default), or
// neither (more faces refined, and smooth faces below level N where those features decay).
Fixture build(const Case& c, bool bases = true) {
    Fixture f;
    Warnings w;
    f.mesh = importMeshFile(test::modelPath(c.model).string(), w);
    f.options = resolveSchemeOptions(f.mesh.tags, c.boundary);
    TablesOptions opts;
    opts.depth = c.depth;
    opts.uniform = c.uniform;
    opts.boundaryBases = opts.basisRimFeatures = bases;
    f.tables = buildTables(f.mesh, f.options, opts, w);
    f.vertices = evaluateVertices(f.tables, f.mesh.positions);
    f.diag = diagonal(f.mesh);
    return f;
}

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

// The per-valence weights of irregular_basis.h against the whole tables of the same mesh:
// three rings of quads around a valence-n vertex (written here), built by buildTables with the
// default boundary rule, evaluated by evaluateVertices for unit control points, and face 0's
// sub-patches read from those tables (the way the weights were first computed).
// buildIrregularBasis refines one level around face 0, evaluates only what its sub-patches read,
// all columns at once, and runs that level's rows again for the deeper bands: the two must agree
// to the bit (checked once for every valence 3 to 64 at K = 16; five valences here at K = 6,
// bands 2 to 6 from the rerun rows).
TEST(IrregularBasis, WeightsAreThoseOfTheWholeTables) {
    for (uint32_t n : {3u, 5u, 6u, 9u, 20u}) {
        SCOPED_TRACE("valence " + std::to_string(n));
        const uint32_t K = 6;
        const Mesh m = irregularBasisMesh(n); // the mesh the basis is refined from
        Warnings w;
        TablesOptions opts;
        opts.depth = int(K);
        opts.irregularLevels = 0;
        const limn::Tables t = buildTables(m, SchemeOptions{}, opts, w);
        const IrregularBasis basis = buildIrregularBasis(n, K);
        // The support in smoothSupport's order (its order is the basis's convention).
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        Sharpness sharp = baseSharpness(topo, m.tags, BoundaryRule::EdgeOnly, w);
        const Level L0 = makeBaseLevel(std::move(topo), std::move(sharp));
        int corner = -1;
        uint32_t valence = 0;
        std::vector<uint32_t> support;
        ASSERT_TRUE(smoothSupport(L0, 0, corner, valence, support));
        ASSERT_EQ(corner, 0);
        ASSERT_EQ(valence, n);
        ASSERT_EQ(support.size(), basis.supportSize());
        const size_t M = support.size();
        size_t compared = 0, differ = 0;
        for (size_t i = 0; i < M; ++i) {
            std::vector<glm::dvec3> control(m.vertexCount(), glm::dvec3(0.0));
            control[support[i]] = glm::dvec3(1.0);
            const std::vector<glm::dvec3> V = evaluateVertices(t, control);
            for (const Patch& p : t.patches) {
                if (p.ptex != 0 || p.level < 1) continue;
                const int q = (p.u0 > 0 ? 1 : 0) + (p.v0 > 0 ? 2 : 0); // 1, 3 or 2 (both)
                const size_t block = size_t(p.level - 1) * 3 + size_t(q == 1 ? 0 : q == 3 ? 1 : 2);
                glm::dvec3 P[4][4];
                gatherControlPoints(p, V, P);
                for (int j = 0; j < 16; ++j, ++compared)
                    differ += basis.weights[block * 16 * M + size_t(j) * M + i] != static_cast<float>(P[j % 4][j / 4].x);
            }
        }
        EXPECT_EQ(compared, size_t(K) * 3 * 16 * M);
        EXPECT_EQ(differ, 0u);
    }
}

// Below level N, a descendant of an irregular face whose semi-sharp creases have decayed (or,
// with two extraordinary corners, that has only one left) is drawn from the per-valence basis
// at its level instead of being refined on (TBLS version 5): such faces exist on these meshes
// (a decaying crease through extraordinary vertices; faces between two n-gon centres), and the
// surface evaluateIrregular gives there is OpenSubdiv's limit (isolation 10): positions within
// 1e-6 of the diagonal and normals within 0.05 degrees wherever it says it is exact, on a grid
// of every irregular face finer than the nested faces' bands. The tables round-trip through
// TBLS (whose reader checks each nested face's level and bands) and cannot be written as
// version 4.
TEST(IrregularSurface, SmoothFacesBelowDepthMatchOpenSubdiv) {
    for (auto [model, depth] : {std::pair{"osd/catmark/catmark_pyramid_creases0.obj", 2},
                                std::pair{"osd/catmark/catmark_nonquads.obj", 2}}) {
        SCOPED_TRACE(model);
        // Without the rim rule: nonquads' roots whose support meets the boundary on its rim are
        // refined, and their corner children take the basis below level N (with it, the roots
        // take it at level N).
        const Fixture f = build({model, depth, false}, false);
        size_t nested = 0;
        for (size_t i = 0; i < f.tables.irregularNodes.size(); ++i)
            for (uint32_t c : f.tables.irregularNodes[i])
                nested += c != kNodeNone && (c & ~kNodeIndexMask) == kNodeBasis &&
                          !(i < f.tables.irregular.size() && smoothRoot(f.tables.irregularNodes[i]));
        EXPECT_GT(nested, 0u) << "no smooth face below level N";
        const Chunk c = encodeTablesChunk(f.tables);
        EXPECT_EQ(c.version, kTablesChunkVersion);
        EXPECT_EQ(encodeTablesChunk(decodeTablesChunk(c, &f.mesh)).payload, c.payload);
        EXPECT_THROW(encodeTablesChunk(f.tables, 4), std::logic_error);
        test::OsdLimitSurface osd(f.mesh, f.options, 10);
        const std::vector<LimitPoint> limits = evaluateLimitPoints(f.tables, f.vertices);
        double worstP = 0, worstN = 0;
        size_t compared = 0;
        const int R = 32; // 1/32 of a face: inside the bands of faces 1 to 4 levels down
        for (uint32_t q = 0; q < f.tables.irregular.size(); ++q) {
            const IrregularFace& face = f.tables.irregular[q];
            for (int j = 0; j <= R; ++j)
                for (int i = 0; i <= R; ++i) {
                    const double s = double(i) / R, t = double(j) / R;
                    bool exact = false;
                    const SurfacePoint x = evaluateIrregular(f.tables, f.vertices, limits, q, s, t, &exact);
                    if (!exact || ((i == 0 || i == R) && (j == 0 || j == R))) continue; // corners: LimitPoints test
                    const double u = face.u0 + s * face.size, v = face.v0 + t * face.size;
                    // OpenSubdiv's patch inside this face (its derivatives can degenerate on an edge).
                    const double iu = u + (i == R ? -1e-9 : 1e-9), iv = v + (j == R ? -1e-9 : 1e-9);
                    glm::dvec3 P, N;
                    ASSERT_TRUE(osd.evaluate(int(face.ptex), u, v, iu, iv, P, N));
                    worstP = std::max(worstP, glm::length(P - x.position) / f.diag);
                    worstN = std::max(worstN, std::acos(std::min(1.0, glm::dot(N, x.normal))) * 180 / M_PI);
                    ++compared;
                }
        }
        EXPECT_GT(compared, 1000u);
        EXPECT_LE(worstP, 1e-6) << compared << " points";
        EXPECT_LE(worstN, 0.05) << compared << " points";
        std::printf("%s d%d: %zu smooth faces below level N, %zu points, max %.3g of the diagonal, %.3g degrees\n",
                    model, depth, nested, compared, worstP, worstN);
    }
}

// Faces around one boundary vertex (a smooth boundary vertex of any number of faces, or a corner;
// or a vertex whose sector is bounded by infinitely sharp creases) take a basis per configuration
// (TBLS version 7) instead of K more levels, under the mesh's own boundary rule: the surface evaluateIrregular gives there is OpenSubdiv's limit (isolation 10)
// wherever it says it is exact, on a 1/32 grid of every irregular face, within 1e-6 of the
// diagonal and 0.05 degrees; each such face's surface lies in its support's box (the cull
// pass's hull test: the boundary rules are convex too, whatever the phantom points' weights);
// the tables round-trip through TBLS, whose version 6 cannot hold them.
TEST(IrregularSurface, BoundaryBasesMatchOpenSubdiv) {
    for (auto [model, depth, rule] : {std::tuple{"tri/cube_no_bottom.obj", 2, std::optional<BoundaryRule>{}},
                                      std::tuple{"osd/catmark/catmark_edgeonly.obj", 2, std::optional<BoundaryRule>{}},
                                      std::tuple{"osd/catmark/catmark_xord_boundary.obj", 1,
                                                 std::optional<BoundaryRule>{BoundaryRule::EdgeOnly}},
                                      std::tuple{"osd/catmark/catmark_xord_boundary.obj", 2,
                                                 std::optional<BoundaryRule>{BoundaryRule::EdgeAndCorner}},
                                      // Sectors bounded by infinitely sharp creases.
                                      std::tuple{"osd/catmark/catmark_cubes_infsharp.obj", 2, std::optional<BoundaryRule>{}}}) {
        SCOPED_TRACE(std::string(model) + " d" + std::to_string(depth));
        Fixture f;
        Warnings w;
        f.mesh = importMeshFile(test::modelPath(model).string(), w);
        f.options = resolveSchemeOptions(f.mesh.tags, rule);
        TablesOptions opts;
        opts.depth = depth;
        opts.boundaryBases = opts.basisRimFeatures = true;
        f.tables = buildTables(f.mesh, f.options, opts, w);
        f.vertices = evaluateVertices(f.tables, f.mesh.positions);
        f.diag = diagonal(f.mesh);
        const limn::Tables& t = f.tables;
        size_t boundaryFaces = 0, quadtreeRoots = 0;
        for (const auto& sm : t.smoothIrregular) boundaryFaces += t.irregularBases[sm.basis].configuration.boundary;
        for (uint32_t q = 0; q < t.irregular.size() && q < t.irregularNodes.size(); ++q)
            quadtreeRoots += !smoothRoot(t.irregularNodes[q]);
        EXPECT_GT(boundaryFaces, 0u) << "no face takes a boundary basis";
        const Chunk c = encodeTablesChunk(t);
        EXPECT_EQ(c.version, kTablesChunkVersion);
        EXPECT_EQ(encodeTablesChunk(decodeTablesChunk(c, &f.mesh)).payload, c.payload);
        EXPECT_THROW(encodeTablesChunk(t, 6), std::logic_error);
        // Each smooth root's surface in its support's box.
        std::vector<int> smoothOf(t.irregular.size(), -1);
        for (uint32_t q = 0; q < t.irregular.size() && q < t.irregularNodes.size(); ++q)
            if (smoothRoot(t.irregularNodes[q])) smoothOf[q] = int(t.irregularNodes[q][0] & kNodeIndexMask);
        test::OsdLimitSurface osd(f.mesh, f.options, 10);
        const std::vector<LimitPoint> limits = evaluateLimitPoints(t, f.vertices);
        double worstP = 0, worstN = 0, outside = 0;
        size_t compared = 0;
        const int R = 32;
        for (uint32_t q = 0; q < t.irregular.size(); ++q) {
            const IrregularFace& face = t.irregular[q];
            glm::dvec3 lo(1e300), hi(-1e300);
            if (smoothOf[q] >= 0) {
                const auto& sm = t.smoothIrregular[size_t(smoothOf[q])];
                for (uint32_t i = 0; i < t.irregularBases[sm.basis].supportSize(); ++i) {
                    lo = glm::min(lo, f.vertices[t.smoothPoints[sm.first + i]]);
                    hi = glm::max(hi, f.vertices[t.smoothPoints[sm.first + i]]);
                }
            }
            for (int j = 0; j <= R; ++j)
                for (int i = 0; i <= R; ++i) {
                    const double s = double(i) / R, tt = double(j) / R;
                    bool exact = false;
                    const SurfacePoint x = evaluateIrregular(t, f.vertices, limits, q, s, tt, &exact);
                    if (smoothOf[q] >= 0) {
                        const glm::dvec3 below = glm::max(lo - x.position, glm::dvec3(0.0));
                        const glm::dvec3 above = glm::max(x.position - hi, glm::dvec3(0.0));
                        outside = std::max(outside, glm::length(below + above) / f.diag);
                    }
                    if (!exact || ((i == 0 || i == R) && (j == 0 || j == R))) continue;
                    const double u = face.u0 + s * face.size, v = face.v0 + tt * face.size;
                    const double iu = u + (i == R ? -1e-9 : 1e-9), iv = v + (j == R ? -1e-9 : 1e-9);
                    glm::dvec3 P, N;
                    ASSERT_TRUE(osd.evaluate(int(face.ptex), u, v, iu, iv, P, N));
                    worstP = std::max(worstP, glm::length(P - x.position) / f.diag);
                    worstN = std::max(worstN, std::acos(std::min(1.0, glm::dot(N, x.normal))) * 180 / M_PI);
                    ++compared;
                }
        }
        EXPECT_GT(compared, 1000u);
        EXPECT_LE(worstP, 1e-6) << compared << " points";
        EXPECT_LE(worstN, 0.05) << compared << " points";
        EXPECT_LE(outside, 1e-7);
        std::printf("%s d%d: %zu boundary-basis faces, %zu quadtrees, %zu points, max %.3g of the diagonal, %.3g degrees\n",
                    model, depth, boundaryFaces, quadtreeRoots, compared, worstP, worstN);
    }
}

// Faces whose feature corner is on a semi-sharp crease that has not decayed at level N take
// their configuration's decaying-crease chain as a basis of their own support
// (TablesOptions::creaseChains; crease_basis.h, expandCreaseChain) instead of K more levels: the
// surface evaluateIrregular gives there is OpenSubdiv's limit (isolation 10) wherever it says
// it is exact, on a 1/16 grid of every irregular face (single-crease bands, boundary phantoms,
// smooth and regular ends), within 1e-6 of the diagonal and 0.05 degrees, and it lies in its
// support's box (the creasing rules are convex combinations); TBLS version 8 holds them (its
// reader expands the chains to the same weights), older versions cannot.
TEST(IrregularSurface, CreaseChainsMatchOpenSubdiv) {
    for (auto [model, depth] : {std::pair{"osd/catmark/catmark_car.obj", 3}, std::pair{"osd/catmark/catmark_rook.obj", 2},
                                std::pair{"osd/catmark/catmark_chaikin0.obj", 2},
                                std::pair{"osd/catmark/catmark_cubes_semisharp.obj", 2}}) {
        SCOPED_TRACE(std::string(model) + " d" + std::to_string(depth));
        Fixture f;
        Warnings w;
        f.mesh = importMeshFile(test::modelPath(model).string(), w);
        f.options = resolveSchemeOptions(f.mesh.tags, {});
        TablesOptions opts;
        opts.depth = depth;
        opts.creaseChains = true;
        f.tables = buildTables(f.mesh, f.options, opts, w);
        f.vertices = evaluateVertices(f.tables, f.mesh.positions);
        f.diag = diagonal(f.mesh);
        const limn::Tables& t = f.tables;
        // TBLS version 8 holds the chains: the reader expands them to the same weights.
        const Chunk c = encodeTablesChunk(t);
        EXPECT_EQ(c.version, kTablesChunkChainVersion);
        const limn::Tables back = decodeTablesChunk(c, &f.mesh);
        EXPECT_EQ(encodeTablesChunk(back).payload, c.payload);
        ASSERT_EQ(back.irregularBases.size(), t.irregularBases.size());
        for (size_t b = 0; b < t.irregularBases.size(); ++b) {
            EXPECT_EQ(back.irregularBases[b].weights, t.irregularBases[b].weights);
            EXPECT_EQ(back.irregularBases[b].kinds, t.irregularBases[b].kinds);
        }
        EXPECT_THROW(encodeTablesChunk(t, 6), std::logic_error);
        std::vector<int> chainOf(t.irregular.size(), -1);
        size_t chainFaces = 0, quadtreeRoots = 0;
        for (uint32_t q = 0; q < t.irregular.size() && q < t.irregularNodes.size(); ++q) {
            if (!smoothRoot(t.irregularNodes[q])) {
                ++quadtreeRoots;
                continue;
            }
            const auto& sm = t.smoothIrregular[t.irregularNodes[q][0] & kNodeIndexMask];
            if (t.irregularBases[sm.basis].kinds.empty()) continue;
            chainOf[q] = int(t.irregularNodes[q][0] & kNodeIndexMask);
            ++chainFaces;
        }
        EXPECT_GT(chainFaces, 0u) << "no face takes a chain";
        test::OsdLimitSurface osd(f.mesh, f.options, 10);
        const std::vector<LimitPoint> limits = evaluateLimitPoints(t, f.vertices);
        double worstP = 0, worstN = 0, outside = 0;
        size_t compared = 0;
        const int R = 16;
        for (uint32_t q = 0; q < t.irregular.size(); ++q) {
            if (chainOf[q] < 0) continue;
            const IrregularFace& face = t.irregular[q];
            const auto& sm = t.smoothIrregular[size_t(chainOf[q])];
            glm::dvec3 lo(1e300), hi(-1e300);
            for (uint32_t i = 0; i < t.irregularBases[sm.basis].supportSize(); ++i) {
                lo = glm::min(lo, f.vertices[t.smoothPoints[sm.first + i]]);
                hi = glm::max(hi, f.vertices[t.smoothPoints[sm.first + i]]);
            }
            for (int j = 0; j <= R; ++j)
                for (int i = 0; i <= R; ++i) {
                    const double s = double(i) / R, tt = double(j) / R;
                    bool exact = false;
                    const SurfacePoint x = evaluateIrregular(t, f.vertices, limits, q, s, tt, &exact);
                    const glm::dvec3 below = glm::max(lo - x.position, glm::dvec3(0.0));
                    const glm::dvec3 above = glm::max(x.position - hi, glm::dvec3(0.0));
                    outside = std::max(outside, glm::length(below + above) / f.diag);
                    if (!exact || ((i == 0 || i == R) && (j == 0 || j == R))) continue;
                    const double u = face.u0 + s * face.size, v = face.v0 + tt * face.size;
                    const double iu = u + (i == R ? -1e-9 : 1e-9), iv = v + (j == R ? -1e-9 : 1e-9);
                    glm::dvec3 P, N;
                    ASSERT_TRUE(osd.evaluate(int(face.ptex), u, v, iu, iv, P, N));
                    worstP = std::max(worstP, glm::length(P - x.position) / f.diag);
                    worstN = std::max(worstN, std::acos(std::min(1.0, glm::dot(N, x.normal))) * 180 / M_PI);
                    ++compared;
                }
        }
        EXPECT_GT(compared, 1000u);
        EXPECT_LE(worstP, 1e-6) << compared << " points";
        EXPECT_LE(worstN, 0.05) << compared << " points";
        EXPECT_LE(outside, 1e-7);
        std::printf("%s d%d: %zu chain faces, %zu quadtrees, %zu points, max %.3g of the diagonal, %.3g degrees\n",
                    model, depth, chainFaces, quadtreeRoots, compared, worstP, worstN);
    }
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
