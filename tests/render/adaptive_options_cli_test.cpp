// View-adaptive tessellation through limn-render's options: displacement along the normal,
// --tess and --edge-pixels at their extremes, buffers too small for a view, tables too deep,
// --wire-triangles. Expected values come from OpenSubdiv and from the mesh file.
#include "drawn_ply.h"
#include "mesh/import.h"
#include "model_tables.h"
#include "osd_oracle.h"
#include "image/srgb_image.h"
#include "subdiv/tables.h"
#include "adaptive_cli_support.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace limn;
using namespace limn::test;

// Displacement (paper 000, 4.5) on the view-adaptive tessellation, close up: every drawn vertex
// of a regular patch moved from OpenSubdiv's limit point along OpenSubdiv's limit normal (the
// offset's component across the normal within 1e-5 of the diagonal, its length within the map's
// range); welded closed with the seam fix, and open without it (the UV-noise map differs across
// UV seams, so each side's own samples crack the surface: the check can fail).
TEST(AdaptiveDisplacement, AlongTheNormalClosedWithSeamFixOpenWithout) {
    ScratchDir dir;
    const std::string obj = modelPath("quad/spot_control_mesh.obj").string();
    const std::string limn = prepare(obj, 3, dir), map = (dir / "h.png").string();
    auto r = run({tool("limn-seams").string(), limn, "-o", limn});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run({tool("limn-heightmap").string(), limn, "--kind", "uv", "-o", map});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Warnings w;
    Mesh mesh = importMeshFile(obj, w);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo), scale = 0.03 * diag;
    const glm::dvec3 target = mesh.positions[0];
    const glm::dvec3 eye = target + glm::normalize(target - 0.5 * (lo + hi)) * (0.4 * diag);
    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    TablesOptions to;
    to.depth = 3;
    Tables t = buildTables(mesh, so, to, w);
    std::map<uint32_t, std::vector<std::array<double, 3>>> patches; // ptex -> u0, v0, size
    std::map<uint32_t, int> irregular;
    for (const Patch& p : t.patches) patches[p.ptex].push_back({p.u0, p.v0, p.size});
    for (const IrregularFace& q : t.irregular) ++irregular[q.ptex];
    OsdLimitSurface osd(mesh, so, 5);
    for (bool fix : {true, false}) {
        SCOPED_TRACE(fix ? "seam fix" : "no seam fix");
        const std::string ply = (dir / "d.ply").string();
        std::vector<std::string> args = {tool("limn-render").string(), limn, "--size", "320x240", "--validate",
                                         "--eye", triple(eye), "--target", triple(target), "--displace", map,
                                         "--displace-scale", std::to_string(scale), "--displace-mid", "0.5",
                                         "--mesh-out", ply, "-o", (dir / "d.png").string()};
        if (!fix) args.push_back("--no-seam-fix");
        r = run(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Drawn drawn = parsePly(readFile(ply));
        double across = 0, longest = 0;
        size_t compared = 0;
        for (const PlyVertex& v : drawn.vertices) {
            if (irregular.count(uint32_t(v.ptex))) continue; // only ptex faces of regular patches
            glm::dvec3 ref, refN;
            ASSERT_TRUE(osd.evaluate(v.ptex, v.uv[0], v.uv[1], ref, refN));
            const glm::dvec3 d = glm::dvec3(v.p[0], v.p[1], v.p[2]) - ref;
            across = std::max(across, glm::length(d - glm::dot(d, refN) * refN) / diag);
            longest = std::max(longest, glm::length(d));
            ++compared;
        }
        EXPECT_GT(compared, drawn.vertices.size() / 10);
        EXPECT_LE(across, 1e-5) << "displaced off the limit normal";
        EXPECT_LE(longest, 0.5 * scale * 1.0001) << "more than scale * |sample - mid|";
        EXPECT_GT(longest, 0.05 * scale) << "not displaced";
        const WeldedEdges welded = weldedEdges(drawn);
        EXPECT_EQ(welded.over, 0u);
        if (fix) {
            EXPECT_EQ(welded.open, 0u) << "open edges with the seam fix";
        } else {
            EXPECT_GT(welded.open, 0u) << "no cracks without the seam fix: the test shows nothing";
        }
        std::printf("%s: %zu vertices, %zu triangles, open edges %zu, across %.2e diag, longest %.3f of scale\n",
                    fix ? "fix" : "nofix", drawn.vertices.size(), drawn.triangles.size(), welded.open, across,
                    longest / scale);
    }
}

// --mesh-out flags the vertices drawn where the surface is approximate (bilinear within 2^-K of
// an extraordinary corner, docs/irregular.md): with K = 2 tables (the default --tess 64 lands
// vertices there) every vertex off OpenSubdiv's limit by more than 1e-5 of the diagonal is
// flagged and every unflagged one is on it; with the default K = 6 nothing is, and the PLY keeps
// its layout without the property.
TEST(AdaptiveCli, MeshOutFlagsTheApproximateVertices) {
    ScratchDir dir;
    const std::string obj = modelPath("osd/catmark/catmark_smoothtris0.obj").string(), limn = (dir / "c.limn").string();
    ASSERT_EQ(run({tool("limn-classify").string(), obj, "-o", limn}).exitCode, 0);
    Warnings w;
    const Mesh mesh = importMeshFile(obj, w);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    OsdLimitSurface osd(mesh, resolveSchemeOptions(mesh.tags, {}), 10);
    for (const char* K : {"2", "6"}) {
        SCOPED_TRACE(std::string("--irregular-levels ") + K);
        const std::string tables = (dir / "t.limn").string(), ply = (dir / "m.ply").string();
        auto r = run({tool("limn-tables").string(), limn, "-q", "--depth", "2", "--irregular-levels", K, "-o", tables});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = run({tool("limn-render").string(), tables, "-q", "--size", "160x120", "--mesh-out", ply, "-o",
                 (dir / "i.png").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Drawn drawn = parsePly(readFile(ply));
        size_t flagged = 0, off = 0, offUnflagged = 0;
        for (const PlyVertex& v : drawn.vertices) {
            glm::dvec3 ref, refN;
            ASSERT_TRUE(osd.evaluate(v.ptex, v.uv[0], v.uv[1], ref, refN));
            const bool isOff = glm::length(glm::dvec3(v.p[0], v.p[1], v.p[2]) - ref) / diag > 1e-5;
            flagged += v.approximate, off += isOff, offUnflagged += isOff && !v.approximate;
        }
        EXPECT_EQ(offUnflagged, 0u);
        if (std::string(K) == "2") {
            EXPECT_TRUE(drawn.hasApproximate);
            EXPECT_GT(off, 20u);
            EXPECT_GE(flagged, off);
            EXPECT_LE(flagged, off + off / 10) << "flagged vertices that are on the limit";
        } else {
            EXPECT_FALSE(drawn.hasApproximate);
            EXPECT_EQ(off, 0u);
        }
        std::printf("K %s: %zu vertices, %zu off the limit, %zu flagged approximate\n", K,
                    drawn.vertices.size(), off, flagged);
    }
}

// --tess that is not a power of two used to crash the fixed grids ("vector::_M_range_insert");
// both modes now render and stay welded closed.
TEST(AdaptiveCli, TessNotAPowerOfTwoInBothModes) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/spot_control_mesh.obj").string(), 3, dir);
    for (const char* tess : {"3", "5", "6", "7", "12"})
        for (const char* ep : {"4", "0"}) {
            SCOPED_TRACE(std::string("--tess ") + tess + " --edge-pixels " + ep);
            const std::string ply = (dir / "t.ply").string();
            auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--tess", tess,
                          "--edge-pixels", ep, "--mesh-out", ply, "-o", (dir / "t.png").string()});
            ASSERT_EQ(r.exitCode, 0) << r.err;
            const WeldedEdges welded = weldedEdges(parsePly(readFile(ply)));
            EXPECT_EQ(welded.open, 0u);
            EXPECT_EQ(welded.over, 0u);
        }
}

// Rates far above the default in a close view (--tess 1024, half-pixel segments): every element
// writes all its triangles (lavapipe ends a shader invocation's loops after 65,535 iterations in
// all, which once left most of a big element unwritten: holes, and --mesh-out triangles of one
// repeated vertex), so the surface is welded closed with no triangle collapsed; or, where one
// element's sides alone need more, the render is refused (exit 1, nothing written). cube_creases1 has single-crease patches (graded segments).
TEST(AdaptiveCli, HighRatesWriteEveryTriangle) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("osd/catmark/catmark_cube_creases1.obj").string(), 3, dir);
    const std::string ply = (dir / "t.ply").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "400x300", "--view", "30,40", "--tess", "1024",
                  "--edge-pixels", "0.25", "--mesh-out", ply});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Drawn d = parsePly(readFile(ply));
    EXPECT_GT(d.triangles.size(), 1000000u) << "not a high-rate view";
    const WeldedEdges welded = weldedEdges(d);
    EXPECT_EQ(welded.collapsed, 0u);
    EXPECT_EQ(welded.open, 0u);
    EXPECT_EQ(welded.over, 0u);
    // The same view with smooth UVs spends more loop iterations per vertex (fvar_eval.glsl).
    const std::string spot = prepare(modelPath("quad/spot_control_mesh.obj").string(), 4, dir, {"--fvar", "none"});
    r = run({tool("limn-render").string(), spot, "--size", "400x300", "--eye", "0.3,0.4,0.9", "--target", "0,0.2,0",
             "--tess", "128", "--edge-pixels", "0.25", "--shade", "uv", "--mesh-out", ply});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const WeldedEdges smooth = weldedEdges(parsePly(readFile(ply)));
    EXPECT_EQ(smooth.collapsed, 0u);
    EXPECT_EQ(smooth.open, 0u);
    EXPECT_EQ(smooth.over, 0u);
}

// The same promise where the elements are few and large: a flat 3x3 grid at depth 1 seen from
// above with every side at --tess segments (--edge-pixels 0.001). Up to --tess 1536 every
// element is written whole; past that, on lavapipe, its loop limit ends an element's emit early
// (the emit pass's budget in adaptive_counts.comp is an estimate; at 2048 and 4096 it once left
// 15-50% of the triangles unwritten, as (0, 0, 0), with exit 0). Whatever the device, each
// render is whole (no collapsed triangle) or refused with what to do and nothing written.
TEST(AdaptiveCli, LargeElementsAtHighRatesAreWholeOrRefused) {
    ScratchDir dir;
    std::string obj;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            const int a = y * 4 + x + 1;
            obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 5) + " " +
                   std::to_string(a + 4) + "\n";
        }
    writeFile(dir / "grid.obj", obj);
    const std::string limn = prepare((dir / "grid.obj").string(), 1, dir);
    const std::string ply = (dir / "g.ply").string();
    for (const char* tess : {"1536", "2048", "4096"}) {
        SCOPED_TRACE(tess);
        auto r = run({tool("limn-render").string(), limn, "--eye", "1.5,1.5,3", "--target", "1.5,1.5,0", "--size",
                      "320x240", "--edge-pixels", "0.001", "--tess", tess, "--mesh-out", ply});
        if (r.exitCode == 0) {
            const Drawn d = parsePly(readFile(ply));
            EXPECT_GT(d.triangles.size(), 100000u) << "not a high-rate view";
            EXPECT_EQ(weldedEdges(d).collapsed, 0u) << "triangles left unwritten";
            std::filesystem::remove(ply);
        } else {
            EXPECT_EQ(r.exitCode, 1) << r.err;
            EXPECT_NE(r.err.find("lower --tess"), std::string::npos) << r.err;
            // (--tess above 2^6 is also told that it can draw irregular faces' corners bilinear.)
            std::string other;
            for (size_t at = 0, end; at < r.err.size(); at = end + 1) {
                end = std::min(r.err.find('\n', at), r.err.size());
                const std::string line = r.err.substr(at, end - at);
                if (line.find("--irregular-levels") == std::string::npos) other += line + "\n";
            }
            EXPECT_EQ(other.find("warning"), std::string::npos) << "the error alone, not a warning too: " << r.err;
            EXPECT_FALSE(std::filesystem::exists(ply));
        }
        if (std::string(tess) == "1536") {
            EXPECT_EQ(r.exitCode, 0) << r.err;
        }
    }
}

// A view whose tessellation needs more than the per-frame buffers hold (a sub-pixel
// --edge-pixels) once wrote an image with holes and exit 0, with only a warning: it is refused
// like --mesh-out, and a sequence removes the frames it wrote.
TEST(AdaptiveCli, AViewOverItsBuffersWritesNothing) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/spot_control_mesh.obj").string(), 3, dir);
    const std::string png = (dir / "s.png").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--view", "150,20", "--edge-pixels", "0.001",
                  "-q", "-o", png});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("more than its buffers hold"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing written: raise --max-error or --edge-pixels, or lower --tess"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--edge-pixels", "0.001", "--turntable", "2",
             "-o", (dir / "t_%d.png").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "t_0.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "t_1.png"));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--view", "150,20", "--edge-pixels", "0.001",
             "--bench", "1"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(r.out, "") << "no benchmark JSON for a frame with parts left out";
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--view", "150,20", "-o", png});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// limn-tables accepts --depth 16; the view-adaptive pieces pack depth 15 at most (edge_pieces.cpp),
// so the default mode refuses such tables saying what to do, and the fixed grids render them.
TEST(AdaptiveCli, DepthSixteenTablesRefusedWithWhatToDo) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/osd_catmark_cube.obj").string(), 16, dir);
    const std::string png = (dir / "c.png").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "-o", png});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("these have depth 16"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--depth 15 or less"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--edge-pixels 0"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--edge-pixels", "0", "-o", png});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// catmark_car at depth 6: its fixed grids (64 segments per side of its level-0 patches: about
// 12.9 M triangles, 147.7 MiB of indices)
// are refused before any work with what to do; the view-adaptive default renders it.
TEST(AdaptiveCli, CarAtDepthSixFixedRefusedAdaptiveRenders) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("osd/catmark/catmark_car.obj").string(), 6, dir);
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--edge-pixels", "0", "-o",
                  (dir / "fixed.png").string()});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("128 MiB"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--edge-pixels"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "fixed.png"));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--validate", "-o", (dir / "va.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// --wire-triangles draws the edges of the triangles drawn: with view-adaptive tessellation its
// line pixels follow the rates the view chose (a close-up of spot's flank: a quarter of the
// segment length gives over twice the line pixels, lines being 1 px wide and merging where
// dense), with the fixed grids it draws their triangles. Normal shading: no surface pixel has
// the wire's grey (18, 18, 18: an encoded normal is never (-0.86, -0.86, -0.86)). One sample per
// pixel, so a line pixel is exactly the wire colour.
TEST(AdaptiveCli, WireTrianglesFollowTheRates) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/spot_control_mesh.obj").string(), 3, dir);
    auto wirePixels = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args = {tool("limn-render").string(), limn, "--validate", "--samples", "1",
                                         "--shade", "normal", "--size", "320x240", "--eye", "0.2,0.4,-1.3",
                                         "--target", "0,0.2,-0.3", "--max-error", "0", "-o", (dir / name).string()};
        args.insert(args.end(), extra.begin(), extra.end());
        auto r = run(args);
        if (r.exitCode != 0) throw std::runtime_error(r.err);
        const auto img = decodePng(readBytes(dir / name));
        size_t n = 0;
        for (size_t i = 0; i + 2 < img.pixels.size(); i += img.channels)
            n += img.pixels[i] == 18 && img.pixels[i + 1] == 18 && img.pixels[i + 2] == 18;
        return n;
    };
    const size_t none = wirePixels("none.png", {});
    const size_t fine = wirePixels("p8.png", {"--wire-triangles", "--edge-pixels", "8"});
    const size_t coarse = wirePixels("p32.png", {"--wire-triangles", "--edge-pixels", "32"});
    const size_t fixed = wirePixels("fixed.png", {"--wire-triangles", "--edge-pixels", "0"});
    std::printf("wire pixels: none %zu, P=8 %zu, P=32 %zu, fixed %zu\n", none, fine, coarse, fixed);
    EXPECT_EQ(none, 0u);
    EXPECT_GT(coarse, 3000u);
    EXPECT_GT(double(fine), 1.8 * double(coarse));
    EXPECT_GT(fixed, 3000u);
    EXPECT_EQ(readBytes(dir / "p8.png"), (wirePixels("again.png", {"--wire-triangles", "--edge-pixels", "8"}),
                                          readBytes(dir / "again.png")));

    auto r = run({tool("limn-render").string(), limn, "--wire", "--wire-triangles", "-o", (dir / "x.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("choose one"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    const std::string control = (dir / "control.limn").string();
    r = run({tool("limn-classify").string(), modelPath("quad/spot_control_mesh.obj").string(), "-o", control});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run({tool("limn-render").string(), control, "--wire-triangles", "-o", (dir / "x.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("limn-tables"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}
