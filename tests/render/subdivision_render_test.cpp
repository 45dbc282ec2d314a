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
};
// gtest prints parameters in failure messages; without this it dumps the struct's bytes.
void PrintTo(const Case& c, std::ostream* os) {
    *os << c.model << " depth " << c.depth << (c.uniform ? " uniform" : " adaptive") << " eval "
        << c.eval;
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model.substr(info.param.model.find_last_of('/') + 1);
    s = s.substr(0, s.find('.'));
    return s + "_d" + std::to_string(info.param.depth) + (info.param.uniform ? "_uniform" : "") +
           "_" + info.param.eval;
}

class SubdivisionRender : public ::testing::TestWithParam<Case> {};

TEST_P(SubdivisionRender, DrawnSurfaceIsTheLimitSurfaceAndWatertight) {
    const Case& c = GetParam();
    ScratchDir dir;
    const std::string limn = (dir / "in.limn").string(), ply = (dir / "drawn.ply").string();
    auto r = run({tool("limn-classify").string(), modelPath(c.model).string(), "-o", limn});
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
    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    TablesOptions to;
    to.depth = c.depth;
    to.uniform = c.uniform;
    Tables t = buildTables(mesh, so, to, w);
    Tessellation tess = buildTessellation(mesh, t, 64, /*splitUVSeams=*/mesh.hasUVs());
    ASSERT_EQ(drawn.vertices.size(), tess.vertices.size());

    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    OsdLimitSurface osd(mesh, so, std::max(c.depth + 2, 4));
    double worstP = 0, worstN = 0;
    size_t compared = 0;
    const uint32_t P = static_cast<uint32_t>(t.patches.size());
    for (size_t i = 0; i < drawn.vertices.size(); ++i) {
        const TessVertex& tv = tess.vertices[i];
        const PlyVertex& v = drawn.vertices[i];
        PtexPoint pp = ptexOf(t, tv);
        EXPECT_EQ(uint32_t(v.ptex), pp.ptex);
        EXPECT_NEAR(v.uv[0], pp.u, 1e-6);
        EXPECT_NEAR(v.uv[1], pp.v, 1e-6);
        // Exact by construction: points of regular patches, and corners of irregular faces whose
        // limit point is exact (not a smooth corner, see tests/subdiv SmoothCorner).
        bool exact = tv.element < P;
        if (!exact) {
            bool corner =
                (tv.s == 0 || tv.s == kTessParamOne) && (tv.t == 0 || tv.t == kTessParamOne);
            if (!corner) continue;
            const IrregularFace& q = t.irregular[tv.element - P];
            int k = tv.s == 0 ? (tv.t == 0 ? 0 : 3) : (tv.t == 0 ? 1 : 2);
            if (!t.limitExact[q.corner[k]]) continue;
        }
        glm::dvec3 ref, refN;
        ASSERT_TRUE(osd.evaluate(int(pp.ptex), pp.u, pp.v, ref, refN));
        glm::dvec3 got(v.p[0], v.p[1], v.p[2]), gotN(v.n[0], v.n[1], v.n[2]);
        worstP = std::max(worstP, glm::length(got - ref) / diag);
        if (exact || tv.element < P) // irregular corners: normals are covered by tests/subdiv
            worstN =
                std::max(worstN, std::acos(std::min(1.0, glm::dot(glm::normalize(gotN), refN))) *
                                     180 / M_PI);
        ++compared;
    }
    EXPECT_GT(compared, drawn.vertices.size() / 4);
    EXPECT_LE(worstP, 1e-5) << compared << " vertices compared";
    EXPECT_LE(worstN, 0.5);

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
};

INSTANTIATE_TEST_SUITE_P(Shared, SubdivisionRender, ::testing::ValuesIn(kCases), caseName);

} // namespace
