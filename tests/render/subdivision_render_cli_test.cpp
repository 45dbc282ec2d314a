// limn-render on subdivision tables, run as users run it (limn-classify | limn-tables |
// limn-render --mesh-out): the triangles as drawn lie on OpenSubdiv's limit surface at their
// (ptex, u, v), and welding them by exact position gives a closed surface for closed inputs.
#include "drawn_ply.h"
#include "mesh/import.h"
#include "osd_oracle.h"
#include "subdiv/tables.h"
#include "tess/tessellation.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <algorithm>
#include <optional>

#include <cstring>
#include <map>
#include <sstream>

using namespace limn;
using namespace limn::test;

namespace {

struct Case {
    std::string model;
    int depth;
    bool uniform;
    bool closed;
    std::string eval = "compute";
    std::optional<BoundaryRule> boundary = {}; // limn-classify --boundary, else the mesh's tag
};
const char* boundaryName(BoundaryRule r) {
    return r == BoundaryRule::None ? "none" : r == BoundaryRule::EdgeOnly ? "edge" : "edge-corner";
}
// gtest prints parameters in failure messages; without this it dumps the struct's bytes.
void PrintTo(const Case& c, std::ostream* os) {
    *os << c.model << " depth " << c.depth << (c.uniform ? " uniform" : " adaptive") << " eval "
        << c.eval;
    if (c.boundary) *os << " boundary " << boundaryName(*c.boundary);
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model.substr(info.param.model.find_last_of('/') + 1);
    s = s.substr(0, s.find('.'));
    return s + "_d" + std::to_string(info.param.depth) + (info.param.uniform ? "_uniform" : "") +
           "_" + info.param.eval +
           (info.param.boundary ? std::string("_b") + std::to_string(int(*info.param.boundary)) : "");
}

class SubdivisionRender : public ::testing::TestWithParam<Case> {};

TEST_P(SubdivisionRender, DrawnSurfaceIsTheLimitSurfaceAndWatertight) {
    const Case& c = GetParam();
    ScratchDir dir;
    const std::string limn = (dir / "in.limn").string(), ply = (dir / "drawn.ply").string();
    std::vector<std::string> classify = {tool("limn-classify").string(), modelPath(c.model).string(),
                                         "-o", limn};
    if (c.boundary) classify.insert(classify.end(), {"--boundary", boundaryName(*c.boundary)});
    auto r = run(classify);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> tables = {
        tool("limn-tables").string(), limn, "-q", "-o", limn, "--depth", std::to_string(c.depth)};
    if (c.uniform) tables.push_back("--uniform");
    r = run(tables);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--validate", "--eval", c.eval,
             "--mesh-out", ply, "-o", (dir / "image.png").string(), "--edge-pixels", "0"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Drawn drawn = parsePly(readFile(ply));

    // Which element owns each drawn vertex (the tool builds the same tessellation).
    Warnings w;
    Mesh mesh = importMeshFile(modelPath(c.model).string(), w);
    SchemeOptions so = resolveSchemeOptions(mesh.tags, c.boundary);
    TablesOptions to;
    to.depth = c.depth;
    to.uniform = c.uniform;
    Tables t = buildTables(mesh, so, to, w);
    Tessellation tess = buildTessellation(mesh, t, 64, /*splitUVSeams=*/mesh.hasUVs());
    ASSERT_EQ(drawn.vertices.size(), tess.vertices.size());

    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    OsdLimitSurface osd(mesh, so, 10);
    const std::vector<uint8_t> smooth = smoothCorners(mesh, so);
    double worstP = 0, worstN = 0;
    size_t compared = 0, flipped = 0;
    std::string firstFlip;
    const uint32_t P = static_cast<uint32_t>(t.patches.size());
    for (size_t i = 0; i < drawn.vertices.size(); ++i) {
        const TessVertex& tv = tess.vertices[i];
        const PlyVertex& v = drawn.vertices[i];
        PtexPoint pp = ptexOf(t, tv);
        EXPECT_EQ(uint32_t(v.ptex), pp.ptex);
        EXPECT_NEAR(v.uv[0], pp.u, 1e-6);
        EXPECT_NEAR(v.uv[1], pp.v, 1e-6);
        const bool corner =
            (tv.s == 0 || tv.s == kTessParamOne) && (tv.t == 0 || tv.t == kTessParamOne);
        // The element's square in its ptex face: OpenSubdiv's normal is taken a hundred-thousandth
        // of it inside, toward its centre (its derivatives can degenerate exactly at a patch
        // corner), in the patch that lies inside this element (the side of a crease matters).
        double u0, v0, size;
        if (tv.element < P) u0 = t.patches[tv.element].u0, v0 = t.patches[tv.element].v0,
                            size = t.patches[tv.element].size;
        else u0 = t.irregular[tv.element - P].u0, v0 = t.irregular[tv.element - P].v0,
             size = t.irregular[tv.element - P].size;
        const double iu = pp.u + (u0 + size / 2 - pp.u) * 1e-5;
        const double iv = pp.v + (v0 + size / 2 - pp.v) * 1e-5;
        glm::dvec3 ref, refN, inside;
        if (!osd.evaluate(int(pp.ptex), pp.u, pp.v, iu, iv, ref, refN)) continue; // a hole
        ASSERT_TRUE(osd.evaluate(int(pp.ptex), iu, iv, inside, refN));
        const glm::dvec3 got(v.p[0], v.p[1], v.p[2]), gotN(v.n[0], v.n[1], v.n[2]);
        const double angle =
            std::acos(std::clamp(glm::dot(glm::normalize(gotN), refN), -1.0, 1.0)) * 180 / M_PI;
        // The sign of every drawn normal, wherever it is: never on the other side of the surface.
        if (angle > 90 && flipped++ == 0)
            firstFlip = "ptex " + std::to_string(pp.ptex) + " (" + std::to_string(pp.u) + ", " +
                        std::to_string(pp.v) + "): " + std::to_string(angle) + " degrees";
        // Exact by construction: points of regular patches, and corners of irregular faces whose
        // limit point is exact. Smooth corners' normals converge too slowly for OpenSubdiv's
        // patches to reach them (tests/subdiv SmoothCorner); only their sign is checked.
        bool exact = tv.element < P;
        if (!exact) {
            if (!corner) continue;
            const IrregularFace& q = t.irregular[tv.element - P];
            int k = tv.s == 0 ? (tv.t == 0 ? 0 : 3) : (tv.t == 0 ? 1 : 2);
            if (!t.limitExact[q.corner[k]]) continue;
            const int bv = baseVertexAt(mesh, pp.ptex, pp.u, pp.v);
            if (bv >= 0 && smooth[bv]) continue;
        }
        worstP = std::max(worstP, glm::length(got - ref) / diag);
        worstN = std::max(worstN, angle);
        ++compared;
    }
    EXPECT_GT(compared, drawn.vertices.size() / 4);
    EXPECT_LE(worstP, 1e-5) << compared << " vertices compared";
    EXPECT_LE(worstN, 0.5) << compared << " vertices compared";
    EXPECT_EQ(flipped, 0u) << "drawn normals opposite to OpenSubdiv's, the first at " << firstFlip;

    // Watertight: weld by exact position; every edge of a closed surface has two triangles.
    const WeldedEdges welded = weldedEdges(drawn);
    EXPECT_EQ(welded.collapsed, 0u) << "a triangle collapsed when welded";
    const size_t open = welded.open;
    EXPECT_EQ(welded.over, 0u);
    if (c.closed) {
        EXPECT_EQ(open, 0u) << "open edges after welding by exact position";
    } else {
        EXPECT_GT(open, 0u);
    }
}

const Case kCases[] = {
    {"quad/spot_control_mesh.obj", 1, false, true},
    {"quad/spot_control_mesh.obj", 3, false, true},
    {"quad/spot_control_mesh.obj", 3, false, true, "vertex"},
    {"quad/spot_control_mesh.obj", 2, true, true},
    {"quad/blub_control_mesh.obj", 4, false, true},
    {"quad/osd_catmark_toroidal_tet.obj", 2, false, true},
    {"quad/osd_catmark_xord_boundary.obj", 3, false, false},
    {"osd/catmark/catmark_cubes_semisharp.obj", 3, false, true},
    {"osd/catmark/catmark_nonquads.obj", 2, false, false},
    {"osd/catmark/catmark_hole_test2.obj", 3, false, false},
    {"osd/catmark/catmark_pyramid_creases1.obj", 2, true, true},
    // Crease patches: inf-sharp boundary and corner patches, single-crease patches.
    {"osd/catmark/catmark_cube_creases2.obj", 4, false, true},
    {"osd/catmark/catmark_single_crease.obj", 3, false, false},
    {"osd/catmark/catmark_torus_creases0.obj", 3, false, true, "vertex"},
    {"osd/catmark/catmark_cube_creases1.obj", 3, false, true},
    // Boundary vertices of valence 2 to 7 under each boundary rule, adaptive and uniform, and the
    // boundary, corner and crease-end configurations of the catmark shapes (signed normals).
    {"quad/osd_catmark_xord_boundary.obj", 3, false, false, "compute", BoundaryRule::EdgeOnly},
    {"quad/osd_catmark_xord_boundary.obj", 3, true, false, "compute", BoundaryRule::EdgeOnly},
    {"quad/osd_catmark_xord_boundary.obj", 3, false, false, "vertex", BoundaryRule::EdgeOnly},
    {"quad/osd_catmark_fvar_bound1.obj", 3, false, false, "compute", BoundaryRule::EdgeOnly},
    {"osd/catmark/catmark_fvar_bound3.obj", 3, false, false, "compute", BoundaryRule::EdgeOnly},
    {"osd/catmark/catmark_fvar_bound3.obj", 3, false, false, "compute", BoundaryRule::EdgeAndCorner},
    {"osd/catmark/catmark_edgeonly.obj", 3, false, false},
    {"osd/catmark/catmark_edgecorner.obj", 3, false, false},
    {"osd/catmark/catmark_edgenone.obj", 2, false, false},
    {"osd/catmark/catmark_flap.obj", 3, false, false, "compute", BoundaryRule::EdgeOnly},
    {"osd/catmark/catmark_flap2.obj", 3, false, false},
    {"osd/catmark/catmark_dart_edgeonly.obj", 3, false, false},
    {"osd/catmark/catmark_dart_edgecorner.obj", 3, false, false},
    {"osd/catmark/catmark_cube_corner4.obj", 3, false, true},
    {"osd/catmark/catmark_cube_creases2.obj", 3, false, true},
    {"osd/catmark/catmark_tent_creases1.obj", 3, false, false},
    {"osd/catmark/catmark_fvar_bound4.obj", 3, false, false},
    {"osd/catmark/catmark_fvar_bound2.obj", 3, false, false, "compute", BoundaryRule::EdgeOnly},
    // Corners whose limit points were approximate at depth 3 (semi-sharp creases of
    // sharpness 6 on the car and the rook, Chaikin-free cube creases, cone points, corner
    // sectors), now compared like every other drawn vertex.
    {"osd/catmark/catmark_car.obj", 3, false, false},
    {"osd/catmark/catmark_rook.obj", 3, false, false},
    {"osd/catmark/catmark_helmet.obj", 3, false, false},
    {"osd/catmark/catmark_pyramid_creases2.obj", 3, false, true},
    {"osd/catmark/catmark_gregory_test7.obj", 3, false, false},
    {"osd/catmark/catmark_inf_crease0.obj", 3, false, false},
};

INSTANTIATE_TEST_SUITE_P(Shared, SubdivisionRender, ::testing::ValuesIn(kCases), caseName);

} // namespace
