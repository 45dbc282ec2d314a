// Smooth face-varying UVs against OpenSubdiv's face-varying patches: the UV limn
// draws at every tessellation vertex (each seam copy in its own chart) equals OpenSubdiv's
// EvaluateBasisFaceVarying at the same (ptex, u, v) to 1e-5, for every face-varying rule, at
// depths 1-4, on OpenSubdiv's fvar_bound/fvar_project shapes, spot and blub. The rule "all"
// keeps limn's linear charts (no FaceVaryingSurface), checked the same way.
#include "mesh/import.h"
#include "osd_fvar_oracle.h"
#include "subdiv/fvar_surface.h"
#include "tess/chart_uvs.h"
#include "tess/tessellation.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

using namespace limn;

namespace {

struct Case {
    std::string model;
    FVarRule rule;
    int depth;
};

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model;
    s = s.substr(s.rfind('/') + 1);
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s + "_fvar" + std::to_string(int(info.param.rule)) + "_d" + std::to_string(info.param.depth);
}

struct Errors {
    double max = 0;
    size_t vertices = 0;
};

// The largest distance between the drawn UVs and OpenSubdiv's at every drawn vertex.
Errors compare(const Tables& t, const Tessellation& tess, const test::OsdFaceVarying& osd) {
    Errors e;
    const uint32_t P = static_cast<uint32_t>(t.patches.size());
    for (size_t i = 0; i < tess.vertices.size(); ++i) {
        const TessVertex& src = tess.uvSources[i];
        const PtexPoint p = ptexOf(t, src);
        // Pick OpenSubdiv's patch from just inside the element the UV was evaluated for.
        float u0, v0, size;
        if (src.element < P) u0 = t.patches[src.element].u0, v0 = t.patches[src.element].v0, size = t.patches[src.element].size;
        else u0 = t.irregular[src.element - P].u0, v0 = t.irregular[src.element - P].v0, size = t.irregular[src.element - P].size;
        const double cu = u0 + 0.5 * size, cv = v0 + 0.5 * size;
        glm::dvec2 ref;
        if (!osd.evaluate(int(p.ptex), p.u, p.v, p.u + 1e-7 * (cu - p.u), p.v + 1e-7 * (cv - p.v), ref)) continue;
        e.max = std::max(e.max, glm::length(ref - glm::dvec2(tess.uvs[i])));
        ++e.vertices;
    }
    return e;
}

class FVarUV : public ::testing::TestWithParam<Case> {};

TEST_P(FVarUV, MatchesOpenSubdivAtEveryDrawnVertex) {
    const Case& c = GetParam();
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath(c.model).string(), w);
    ASSERT_TRUE(mesh.hasUVs());
    SchemeOptions o = resolveSchemeOptions(mesh.tags, {});
    o.fvar = c.rule;
    TablesOptions to;
    to.depth = c.depth;
    Tables t = buildTables(mesh, o, to, w);
    // Isolated to level 8, so that OpenSubdiv's patches are exact at limn's lattice points even
    // where semi-sharp features have not decayed by limn's depth (limn's limit points are exact
    // there: subdiv/exact_limits.h; OpenSubdiv's end caps at level N would not be).
    test::OsdFaceVarying osd(mesh, o, 8);
    Tessellation linear = buildTessellation(mesh, t, 1u << 16, true);
    const Errors before = compare(t, linear, osd);
    Errors after = before;
    if (c.rule != FVarRule::All) {
        FaceVaryingSurface surface(mesh, o, t.depth, t.irregularLevels, w);
        ChartUVs charts(mesh, surface, 1u << t.depth);
        Tessellation smooth = buildTessellation(mesh, t, 1u << 16, true, &charts);
        after = compare(t, smooth, osd);
        // The same points and triangles: only UVs (and seam copies) may differ.
        EXPECT_EQ(smooth.indices.size(), linear.indices.size());
    }
    std::printf("fvar-uv %s rule %d depth %d: %zu vertices, max |UV - OpenSubdiv| linear %.3g, drawn %.3g\n",
                c.model.c_str(), int(c.rule), c.depth, after.vertices, before.max, after.max);
    EXPECT_GT(after.vertices, 0u);
    EXPECT_LE(after.max, 1e-5);
}

std::vector<Case> cases() {
    std::vector<Case> out;
    for (const char* m : {"osd/catmark/catmark_fvar_bound0.obj", "osd/catmark/catmark_fvar_bound1.obj",
                          "osd/catmark/catmark_fvar_bound2.obj", "osd/catmark/catmark_fvar_bound3.obj",
                          "osd/catmark/catmark_fvar_bound4.obj", "osd/catmark/catmark_fvar_project0.obj",
                          "quad/spot_control_mesh.obj", "quad/blub_control_mesh.obj"})
        for (int rule = 0; rule <= 5; ++rule)
            for (int depth = 1; depth <= 4; ++depth) out.push_back({m, static_cast<FVarRule>(rule), depth});
    return out;
}

INSTANTIATE_TEST_SUITE_P(Shapes, FVarUV, ::testing::ValuesIn(cases()), caseName);

// Under "none" only OpenSubdiv's disjoint values are sharpened: a UV index used by two spans of
// faces around a vertex (spot has 8 such, where its UV islands touch at a point), none else.
// Pins the sharpening too (an out-of-bounds read once added corners of garbage sharpness that
// changed from run to run).
TEST(FVarMesh, SpotUnderNoneSharpensOnlyItsDisjointValues) {
    Warnings w;
    Mesh mesh = importMeshFile(test::modelPath("quad/spot_control_mesh.obj").string(), w);
    SchemeOptions o = resolveSchemeOptions(mesh.tags, {});
    o.fvar = FVarRule::LinearNone;
    const Mesh uv = faceVaryingMesh(mesh, o);
    EXPECT_EQ(uv.faceVertices.size(), mesh.faceVertices.size());
    ASSERT_EQ(uv.tags.corners.size(), 8u);
    for (const auto& c : uv.tags.corners) EXPECT_EQ(c.sharpness, kInfiniteSharpness);
    EXPECT_GT(uv.positions.size(), mesh.uvs.size()); // the disjoint values are split per span
}

} // namespace
