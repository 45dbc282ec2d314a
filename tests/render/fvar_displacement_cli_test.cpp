// Smooth face-varying UVs through the tools: limn-classify --fvar MODE | limn-tables |
// limn-seams | limn-render --displace --mesh-out. In every mode the displaced closed meshes stay
// welded-closed with the seam fix, in the fixed grids and the view-adaptive tessellation (its samples are the smooth UVs of every face around a point,
// in increasing face order, so every copy of a point displaces by the same bits), and the PLY's
// s, t are the smooth UVs: they differ from the linear ones of mode "all" where the rule smooths
// (and equal them on one-face islands whose corners the rule keeps sharp).
#include "displacement_support.h"
#include "mesh/import.h"
#include "osd_fvar_oracle.h"
#include "subdiv/fvar_surface.h"
#include "subdiv/tables.h"

#include <map>

using namespace limn;
using namespace limn::test;
using namespace limn::test::displacement;

namespace {

const char* const kModes[] = {"none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"};

std::string prepareFVar(const std::string& obj, const std::string& mode, int depth, const ScratchDir& dir) {
    const std::string limn = (dir / "fvar.limn").string();
    runOk({bin("limn-classify"), "-q", obj, "--fvar", mode, "-o", limn});
    runOk({bin("limn-tables"), "-q", limn, "-o", limn, "--depth", std::to_string(depth)});
    runOk({bin("limn-seams"), "-q", limn, "-o", limn});
    return limn;
}

// The drawn texture coordinates by (ptex, u, v) of each vertex (its first copy's).
std::map<std::array<float, 3>, std::array<float, 2>> uvByPoint(const Drawn& d) {
    std::map<std::array<float, 3>, std::array<float, 2>> out;
    for (const auto& v : d.vertices) out.try_emplace({float(v.ptex), v.uv[0], v.uv[1]}, std::array<float, 2>{v.st[0], v.st[1]});
    return out;
}

struct FVarCase {
    Model model;
    int depth;
};

class FVarDisplaced : public ::testing::TestWithParam<FVarCase> {};

TEST_P(FVarDisplaced, WeldedClosedInEveryMode) {
    const FVarCase& c = GetParam();
    ScratchDir dir;
    const std::string obj = modelFile(c.model, dir);
    const double scale = 0.05 * diagonalOf(obj);
    std::string map;
    std::map<std::array<float, 3>, std::array<float, 2>> linear;
    size_t smoothed = 0;
    for (int m = 5; m >= 0; --m) { // "all" first: the linear UVs to compare with
        SCOPED_TRACE(std::string("--fvar ") + kModes[m]);
        const std::string limn = prepareFVar(obj, kModes[m], c.depth, dir);
        if (map.empty()) map = heightmap(limn, "uv", dir); // unrelated across seams: the stress case
        const Drawn d = drawn(limn, {"--displace", map, "--displace-scale", std::to_string(scale),
                                     "--displace-mid", "0.5"},
                              dir);
        ASSERT_TRUE(d.hasST);
        WeldedEdges w = weldedEdges(d);
        EXPECT_EQ(w.open, 0u) << "open edges with the seam fix";
        EXPECT_EQ(w.over, 0u);
        EXPECT_EQ(w.collapsed, 0u);
        // The view-adaptive tessellation: the seam records of the smooth UVs (corners exact,
        // edges interpolated per side), interiors at the emitted smooth UV; welded closed too.
        const std::string ply = (dir / "adaptive.ply").string();
        runOk({bin("limn-render"), limn, "--size", "64x48", "--validate", "--mesh-out", ply, "-o",
               (dir / "adaptive.png").string(), "--displace", map, "--displace-scale", std::to_string(scale),
               "--displace-mid", "0.5"});
        WeldedEdges a = weldedEdges(parsePly(readFile(ply)));
        EXPECT_EQ(a.open, 0u) << "view-adaptive: open edges with the seam fix";
        EXPECT_EQ(a.over, 0u);
        EXPECT_EQ(a.collapsed, 0u);
        if (m == 0) { // the check can fail: each side's own samples open the UV seams
            runOk({bin("limn-render"), limn, "--size", "64x48", "--mesh-out", ply, "-o",
                   (dir / "adaptive.png").string(), "--displace", map, "--displace-scale",
                   std::to_string(scale), "--displace-mid", "0.5", "--no-seam-fix"});
            EXPECT_GT(weldedEdges(parsePly(readFile(ply))).open, 0u) << "--no-seam-fix should crack";
        }
        auto uvs = uvByPoint(d);
        if (m == 5) {
            linear = uvs;
            continue;
        }
        size_t differ = 0;
        for (const auto& [k, st] : uvs) {
            auto it = linear.find(k);
            ASSERT_NE(it, linear.end());
            differ += std::abs(it->second[0] - st[0]) + std::abs(it->second[1] - st[1]) > 1e-4f;
        }
        // An island of one quad whose corners the mode keeps sharp is its bilinear chart.
        if (c.model.name == "islands" && m != 0)
            EXPECT_EQ(differ, 0u) << "a one-face island with sharp corners is bilinear";
        else
            EXPECT_GT(differ, 0u) << "the smooth UVs should differ from the linear ones somewhere";
        smoothed += differ;
    }
    RecordProperty("smoothed_vertices", int(smoothed));
}

const FVarCase kCases[] = {
    {{"spot", "quad/spot_control_mesh.obj"}, 1}, {{"spot", "quad/spot_control_mesh.obj"}, 2},
    {{"spot", "quad/spot_control_mesh.obj"}, 3}, {{"spot", "quad/spot_control_mesh.obj"}, 4},
    {{"blub", "quad/blub_control_mesh.obj"}, 2}, {{"islands", ""}, 2},
};

std::string caseName(const ::testing::TestParamInfo<FVarCase>& p) {
    return p.param.model.name + "_d" + std::to_string(p.param.depth);
}

INSTANTIATE_TEST_SUITE_P(Models, FVarDisplaced, ::testing::ValuesIn(kCases), caseName);

// A hole (and a face without a limit surface) has no UV surface: the seam fix samples the faces
// around a point that are drawn. It asked the hole's own chart instead, and limn-render failed
// ("no face-varying element contains ptex face 6") on a valid mesh with holes and smooth UVs.
TEST(FVarDisplacedHoles, HoleFacesAreNotSampled) {
    ScratchDir dir;
    const std::string limn = prepareFVar(modelPath("osd/catmark/catmark_hole_test2.obj").string(), "boundaries", 2, dir);
    const std::string map = heightmap(limn, "uv", dir);
    const std::vector<std::string> displace = {"--displace", map, "--displace-scale", "0.05"};
    const Drawn fixed = drawn(limn, displace, dir);
    EXPECT_GT(fixed.triangles.size(), 0u);
    std::vector<std::string> adaptive = {bin("limn-render"), limn, "--size", "64x48", "-o", (dir / "a.png").string()};
    adaptive.insert(adaptive.end(), displace.begin(), displace.end());
    runOk(adaptive);
}

// The view-adaptive tessellation evaluates the smooth UVs on the GPU (shaders/fvar_eval.glsl) at
// the (ptex, u, v) of each vertex it emits: equal to the CPU's FaceVaryingSurface (in double)
// to 1e-5 at every emitted vertex inside a ptex face (where the vertex's chart is that face's),
// in every smoothing rule, on spot seen close up (rates well above the fixed grids').
TEST(FVarAdaptive, GpuUVsMatchTheCpuSurface) {
    ScratchDir dir;
    const std::string obj = modelPath("quad/spot_control_mesh.obj").string();
    Warnings w;
    const Mesh mesh = importMeshFile(obj, w);
    for (int m = 0; m < 5; ++m) {
        SCOPED_TRACE(std::string("--fvar ") + kModes[m]);
        const int depth = 3;
        const std::string limn = prepareFVar(obj, kModes[m], depth, dir);
        const std::string ply = (dir / "adaptive.ply").string();
        runOk({bin("limn-render"), limn, "--size", "320x240", "--view", "30,20", "--validate", "--mesh-out", ply,
               "-o", (dir / "adaptive.png").string()});
        const Drawn d = parsePly(readFile(ply));
        ASSERT_TRUE(d.hasST);
        SchemeOptions o = resolveSchemeOptions(mesh.tags, {});
        o.fvar = static_cast<FVarRule>(m);
        FaceVaryingSurface surface(mesh, o, depth, TablesOptions{}.irregularLevels, w);
        double worst = 0;
        size_t inside = 0;
        for (const auto& v : d.vertices) {
            if (!(v.uv[0] > 0 && v.uv[0] < 1 && v.uv[1] > 0 && v.uv[1] < 1)) continue;
            // A vertex on an edge between UV elements takes the UV of the element it was drawn
            // for (fvar_eval.glsl probes toward that element's inside); where an irregular UV
            // face (bilinear in its corner limits) meets a patch the two sides differ by up to
            // about 1e-3 on spot. The PLY does not say which element drew the vertex: the
            // reference is the nearest of the elements around the point (probes toward each
            // corner of the ptex face), each evaluated exactly on the CPU.
            double best = 1e9;
            for (const auto& [tu, tv] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}}) {
                const glm::dvec2 ref = surface.uvAt(uint32_t(v.ptex), v.uv[0], v.uv[1], tu, tv);
                best = std::min(best, glm::length(ref - glm::dvec2(v.st[0], v.st[1])));
            }
            worst = std::max(worst, best);
            ++inside;
        }
        std::printf("fvar adaptive %s: %zu vertices inside ptex faces, max |GPU - CPU| UV %.3g\n", kModes[m],
                    inside, worst);
        EXPECT_GT(inside, 1000u);
        EXPECT_LE(worst, 1e-5);
    }
}

// The view-adaptive tessellation draws points inside irregular faces (around extraordinary
// vertices, n-gons and triangles, and where UV seams make the UV mesh irregular); their UVs are
// the UV surface's there, evaluated as the geometry is (docs/irregular.md): every drawn vertex
// inside a ptex face within 1e-6 (UVs span [0, 1]) of OpenSubdiv's face-varying limit at its
// (ptex, u, v): the emit pass evaluates the UV at the point it draws (its parameter rounded to
// 1/32768 of the element, as the position and the PLY's u, v are). With `limn-tables --irregular-levels 0` the UV surface's irregular faces are the
// bilinear blend of their corners' limit UVs (as before they had a surface), and the same check
// fails: the test can tell.
TEST(FVarAdaptive, DrawnUVsOnIrregularFacesMatchOpenSubdiv) {
    ScratchDir dir;
    struct Shape {
        const char* model;
        const char* rule;
        int depth;
        bool bilinearToo; // also draw the tables without the irregular surface
    };
    const Shape shapes[] = {{"quad/spot_control_mesh.obj", "corners-only", 2, true},
                            {"tri/cube_no_bottom.obj", "corners-plus1", 2, true},
                            {"quad/osd_catmark_pyramid.obj", "none", 1, false},
                            {"quad/blub_control_mesh.obj", "boundaries", 3, false}};
    for (const Shape& sh : shapes) {
        SCOPED_TRACE(sh.model);
        const std::string obj = modelPath(sh.model).string();
        Warnings w;
        const Mesh mesh = importMeshFile(obj, w);
        SchemeOptions o = resolveSchemeOptions(mesh.tags, {});
        int rule = 0;
        while (std::string(kModes[rule]) != sh.rule) ++rule;
        o.fvar = static_cast<FVarRule>(rule);
        const test::OsdFaceVarying osd(mesh, o, 8); // isolated deeper than limn's depth + K is exact
        const std::string limn = (dir / "irregular.limn").string(), ply = (dir / "irregular.ply").string();
        runOk({bin("limn-classify"), "-q", obj, "--fvar", sh.rule, "-o", limn});
        auto worst = [&](const std::string& levels, size_t& inside) {
            runOk({bin("limn-tables"), "-q", limn, "-o", (dir / "t.limn").string(), "--depth",
                   std::to_string(sh.depth), "--irregular-levels", levels});
            runOk({bin("limn-render"), (dir / "t.limn").string(), "--size", "160x120", "--view", "30,20",
                   "--mesh-out", ply, "-o", (dir / "irregular.png").string()});
            const Drawn d = parsePly(readFile(ply));
            EXPECT_TRUE(d.hasST);
            double most = 0;
            inside = 0;
            for (const auto& v : d.vertices) {
                if (!(v.uv[0] > 0 && v.uv[0] < 1 && v.uv[1] > 0 && v.uv[1] < 1)) continue;
                // The element that drew the vertex is not in the PLY: the nearest of OpenSubdiv's
                // patches around the point (probes toward each corner of the ptex face). Inside
                // a ptex face the limit surface is continuous, so they differ by rounding only.
                double best = 1e9;
                const double u = v.uv[0], vv = v.uv[1];
                for (const auto& [tu, tv] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}}) {
                    glm::dvec2 ref;
                    if (!osd.evaluate(int(v.ptex), u, vv, u + 1e-7 * (tu - u), vv + 1e-7 * (tv - vv), ref)) continue;
                    best = std::min(best, glm::length(ref - glm::dvec2(v.st[0], v.st[1])));
                }
                if (best >= 1e9) continue;
                most = std::max(most, best);
                ++inside;
            }
            return most;
        };
        size_t inside = 0, bilinearInside = 0;
        const double exact = worst("6", inside);
        std::printf("fvar adaptive %s --fvar %s depth %d: %zu vertices inside ptex faces, max |UV - OpenSubdiv| %.3g\n",
                    sh.model, sh.rule, sh.depth, inside, exact);
        EXPECT_GT(inside, 200u);
        EXPECT_LE(exact, 1e-6); // measured at most 2.7e-7 (float records and arithmetic)
        if (sh.bilinearToo) {
            const double bilinear = worst("0", bilinearInside);
            std::printf("  with --irregular-levels 0 (bilinear irregular faces): max %.3g\n", bilinear);
            EXPECT_GT(bilinear, 1e-4) << "the check should see the bilinear irregular faces";
        }
    }
}

} // namespace
