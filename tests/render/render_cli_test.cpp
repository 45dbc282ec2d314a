// limn-render as users run it (a subprocess, on lavapipe). Most runs use --sync-validation,
// which makes any validation error fail the run: exit code 0 means the layer reported none.
#include "drawn_ply.h"
#include "image/srgb_image.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <thread>

using namespace limn;
using namespace limn::test;

namespace {

std::string bin(const std::string& name) {
    return tool(name).string();
}

// Classifies a model into a .limn in `dir` and returns its path.
std::string classify(const ScratchDir& dir, const std::string& model, const std::string& name) {
    std::string out = (dir / (name + ".limn")).string();
    auto r = run({bin("limn-classify"), model, "-o", out});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return out;
}

RunResult render(std::vector<std::string> args, const std::string& input = {}) {
    args.insert(args.begin(), bin("limn-render"));
    return run(args, input);
}

Image readPng(const std::filesystem::path& path) {
    auto bytes = readBytes(path);
    return decodePng(bytes);
}

bool samePixel(const uint8_t* a, std::initializer_list<int> b, int tolerance) {
    int i = 0;
    for (int v : b)
        if (std::abs(int(a[i++]) - v) > tolerance) return false;
    return true;
}

// A 3x3 grid of unit quads in the XY plane with the centre face a hole, plus a pentagon fan
// beside it; coordinates that float cannot hold exactly (0.1 steps) to exercise the conversion.
const char* kGridObj = "v 0 0 0\nv 1.1 0 0\nv 2.2 0 0\nv 3.3 0 0\n"
                       "v 0 1.1 0\nv 1.1 1.1 0.1\nv 2.2 1.1 0.1\nv 3.3 1.1 0\n"
                       "v 0 2.2 0\nv 1.1 2.2 0.1\nv 2.2 2.2 0.1\nv 3.3 2.2 0\n"
                       "v 0 3.3 0\nv 1.1 3.3 0\nv 2.2 3.3 0\nv 3.3 3.3 0\n"
                       "v 4.4 0 0\nv 5.5 1.1 0.3\nv 4.95 2.7 0\nv 3.9 2.7 -0.2\n"
                       "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                       "f 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\n"
                       "f 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\n"
                       "f 4 17 18 19 20\n"
                       "t hole 1/0/0 4\n";

// ----------------------------------------------------------------------------------------------

TEST(RenderCli, SameCommandSameBytes) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/spot_control_mesh.obj").string(), "spot");
    auto a = dir / "a.png", b = dir / "b.png";
    for (const auto& out : {a, b}) {
        auto r =
            render({limn, "--size", "160x120", "--wire", "--view", "120,10", "-o", out.string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_EQ(readFile(a), readFile(b));
    // Standard output carries the same bytes when piped.
    auto piped = render({limn, "--size", "160x120", "--wire", "--view", "120,10", "-o", "-"});
    ASSERT_EQ(piped.exitCode, 0) << piped.err;
    EXPECT_EQ(piped.out, readFile(a));
}

TEST(RenderCli, ValidationLayerReportsNothing) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_fvar_bound1.obj").string(), "fvar");
    for (std::vector<std::string> options : {std::vector<std::string>{"--shade", "lit", "--wire"},
                                             {"--shade", "normal", "--alpha"},
                                             {"--shade", "uv"},
                                             {"--bench", "2", "--wire"}}) {
        std::vector<std::string> args = {
            limn, "--size", "64x48", "--sync-validation", "-v", "-o", (dir / "out.png").string()};
        args.insert(args.end(), options.begin(), options.end());
        auto r = render(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.err.find("validation: 0 errors, 0 warnings"), std::string::npos) << r.err;
    }
}

TEST(RenderCli, UnknownDeviceIsExitCode3) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    auto r = render({limn, "--device", "no-such-device", "-o", (dir / "x.png").string()});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("limn-render: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no-such-device"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("devices found"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(RenderCli, NoVulkanDriverIsExitCode3) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    // The loader finds no driver at all.
    auto r = run({"/usr/bin/env", "VK_ICD_FILENAMES=/nonexistent.json",
                  "VK_DRIVER_FILES=/nonexistent.json", bin("limn-render"), limn, "-o",
                  (dir / "x.png").string()});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("Vulkan"), std::string::npos) << r.err;
}

TEST(RenderCli, BackgroundAtTheCornersObjectInTheMiddle) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/spot_control_mesh.obj").string(), "spot");
    auto out = dir / "bg.png";
    auto r = render({limn, "--size", "96x64", "--background", "0.1,0.5,0.9", "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readPng(out);
    ASSERT_EQ(img.width, 96u);
    ASSERT_EQ(img.height, 64u);
    ASSERT_EQ(img.channels, 3u);
    // 0.1, 0.5, 0.9 * 255 = 25.5, 127.5, 229.5: the GPU's sRGB encode may land either side.
    for (auto [x, y] : {std::pair{0u, 0u}, {95u, 0u}, {0u, 63u}, {95u, 63u}})
        EXPECT_TRUE(samePixel(img.at(x, y), {26, 128, 230}, 1)) << x << "," << y;
    // Grey lit surface in the middle: R = G = B, unlike the background.
    const uint8_t* c = img.at(48, 32);
    EXPECT_EQ(c[0], c[1]);
    EXPECT_EQ(c[1], c[2]);
    EXPECT_GT(c[0], 30);
}

TEST(RenderCli, AlphaMakesTheBackgroundTransparent) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    auto out = dir / "a.png";
    auto r =
        render({limn, "--size", "64x48", "--alpha", "--background", "1,0,0", "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readPng(out);
    ASSERT_EQ(img.channels, 4u);
    EXPECT_TRUE(samePixel(img.at(0, 0), {255, 0, 0, 0}, 0));
    EXPECT_EQ(img.at(32, 24)[3], 255);
}

// Looking straight at the grid, the hole in its middle shows the background.
TEST(RenderCli, HolesAreNotDrawn) {
    ScratchDir dir;
    writeFile(dir / "grid.obj", kGridObj);
    auto limn = classify(dir, (dir / "grid.obj").string(), "grid");
    auto out = dir / "grid.png";
    // Eye on the +Z axis above the grid's centre (1.65, 1.65), looking down -Z.
    auto r = render({limn, "--size", "101x101", "--eye", "1.65,1.65,12", "--target", "1.65,1.65,0",
                     "--background", "0,0,1", "--sync-validation", "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readPng(out);
    EXPECT_TRUE(samePixel(img.at(50, 50), {0, 0, 255}, 0)) << int(img.at(50, 50)[0]);
    // A drawn face next to the hole (one cell to the left, x = 0.55 in world).
    const uint8_t* side = img.at(50 - 14, 50);
    EXPECT_FALSE(samePixel(side, {0, 0, 255}, 0));
}

TEST(RenderCli, MeshOutHoldsTheControlMeshAsDrawn) {
    ScratchDir dir;
    writeFile(dir / "grid.obj", kGridObj);
    auto limn = classify(dir, (dir / "grid.obj").string(), "grid");
    auto plyPath = dir / "grid.ply";
    auto r = render({limn, "--size", "32x32", "--sync-validation", "--mesh-out", plyPath.string(),
                     "-o", (dir / "grid.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Drawn ply = parsePly(readFile(plyPath)); // throws unless the size fits the header
    EXPECT_FALSE(ply.hasST);          // no UVs, so no texture UVs: 36 bytes a vertex
    EXPECT_FALSE(ply.hasApproximate); // a control mesh is exact

    // Independent expectation from the OBJ text: 8 quads (hole left out) and one pentagon.
    std::vector<std::array<double, 3>> positions;
    std::vector<std::vector<int>> faces;
    std::istringstream obj(kGridObj);
    std::string tag;
    for (std::string line; std::getline(obj, line);) {
        std::istringstream ls(line);
        ls >> tag;
        if (tag == "v") {
            std::array<double, 3> p;
            ls >> p[0] >> p[1] >> p[2];
            positions.push_back(p);
        } else if (tag == "f") {
            std::vector<int> f;
            for (int i; ls >> i;) f.push_back(i - 1);
            faces.push_back(f);
        }
    }
    std::vector<int> ptex(faces.size());
    for (size_t f = 1; f < faces.size(); ++f)
        ptex[f] = ptex[f - 1] + (faces[f - 1].size() == 4 ? 1 : int(faces[f - 1].size()));

    size_t corner = 0, triangle = 0;
    for (size_t f = 0; f < faces.size(); ++f) {
        if (f == 4) continue; // the hole
        const auto& face = faces[f];
        // Newell normal in double, from the double positions.
        double n[3] = {0, 0, 0};
        for (size_t i = 0; i < face.size(); ++i) {
            const auto& a = positions[face[(i + face.size() - 1) % face.size()]];
            const auto& b = positions[face[i]];
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
        }
        double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (size_t i = 0; i < face.size(); ++i, ++corner) {
            ASSERT_LT(corner, ply.vertices.size());
            const auto& v = ply.vertices[corner];
            for (int k = 0; k < 3; ++k) {
                EXPECT_EQ(v.p[k], static_cast<float>(positions[face[i]][k])) << "corner " << corner;
                EXPECT_NEAR(v.n[k], n[k] / len, 1e-6) << "face " << f;
            }
            EXPECT_EQ(v.ptex, ptex[f]);
            EXPECT_EQ(v.uv[0], 0.0f);
        }
        const int first = int(corner - face.size());
        for (size_t i = 1; i + 1 < face.size(); ++i, ++triangle) {
            ASSERT_LT(triangle, ply.triangles.size());
            EXPECT_EQ(ply.triangles[triangle],
                      (std::array<int32_t, 3>{first, first + int(i), first + int(i) + 1}));
        }
    }
    EXPECT_EQ(corner, ply.vertices.size());
    EXPECT_EQ(triangle, ply.triangles.size());

    // The ASCII form carries the same numbers.
    auto asciiPath = dir / "grid_ascii.ply";
    r = render({limn, "--size", "32x32", "--mesh-out", asciiPath.string(), "--mesh-ascii", "-o",
                (dir / "grid.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string ascii = readFile(asciiPath);
    auto body = ascii.substr(ascii.find("end_header\n") + 11);
    std::istringstream values(body);
    for (const auto& v : ply.vertices) {
        float x, y, z, nx, ny, nz, u, w;
        int pt;
        values >> x >> y >> z >> nx >> ny >> nz >> pt >> u >> w;
        EXPECT_EQ(x, v.p[0]);
        EXPECT_EQ(y, v.p[1]);
        EXPECT_EQ(z, v.p[2]);
        EXPECT_EQ(nz, v.n[2]);
        EXPECT_EQ(pt, v.ptex);
    }
}

TEST(RenderCli, FailuresLeaveNoOutput) {
    ScratchDir dir;
    writeFile(dir / "grid.obj", kGridObj);
    auto limn = classify(dir, (dir / "grid.obj").string(), "grid");
    auto out = dir / "old.png";
    writeFile(out, "previous contents");
    auto r = render({limn, "--shade", "uv", "-o", out.string()}); // the grid has no UVs
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("no texture coordinates"), std::string::npos) << r.err;
    EXPECT_EQ(readFile(out), "previous contents");
    r = render({limn, "--shade", "levels", "-o", out.string()}); // no subdivision tables
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("limn-tables"), std::string::npos) << r.err;
    EXPECT_EQ(readFile(out), "previous contents");
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().filename().string().rfind(".limn-tmp", 0), std::string::npos);
    r = render({(dir / "missing.limn").string(), "-o", (dir / "m.png").string()});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("missing.limn"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "m.png"));
}

// Devices and pipes are written in place: an atomic rename would replace them with a plain file
// (as root, `-o /dev/null` replaced /dev/null itself). Tested on a FIFO in a scratch directory,
// so that a regression cannot damage the machine's /dev/null.
TEST(RenderCli, WritesIntoDevicesAndPipesInPlace) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    auto fifo = dir / "png.fifo";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    std::string received;
    std::thread reader([&] { received = readFile(fifo); });
    auto r = render({limn, "--size", "16x16", "-o", fifo.string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    if (!std::filesystem::is_fifo(fifo)) {
        reader.detach(); // blocked for good on the FIFO that was renamed over; never join it
        FAIL() << "the FIFO was replaced by a regular file";
    }
    // If the tool never opened the FIFO, open it for writing once so the reader sees EOF.
    int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    reader.join();
    EXPECT_EQ(received.substr(0, 4), "\x89PNG");
}

TEST(RenderCli, UsageErrorsAreExitCode2) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    std::string out = (dir / "x.png").string();
    for (std::vector<std::string> bad : {std::vector<std::string>{"--size", "0x10"},
                                         {"--size", "100"},
                                         {"--view", "10"},
                                         {"--view", "0,0", "--eye", "1,2,3"},
                                         {"--target", "0,0,0"},
                                         {"--fov", "200"},
                                         {"--background", "2,0,0"},
                                         {"--shade", "sparkles"},
                                         {"--bench", "5", "-o", "-"},
                                         {"--mesh-out", "-", "-o", "-"}}) {
        std::vector<std::string> args = {limn, "-o", out};
        args.insert(args.end(), bad.begin(), bad.end());
        auto r = render(args);
        EXPECT_EQ(r.exitCode, 2) << bad[0] << ": " << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
}

// An explicit camera is checked like a --cameras line (sequence_test.cpp): no zero or parallel
// up, no coordinate the GPU's float cannot carry; --bench-orbit means nothing without --bench.
TEST(RenderCli, CameraAndBenchOptionsAreCheckedWithTheReason) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    std::string out = (dir / "x.png").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--eye", "0,0,5", "--up", "0,0,0"}, "--up: the up vector is zero"},
        {{"--eye", "0,0,5", "--target", "0,0,0", "--up", "0,0,-2"}, "--up is parallel to the view direction"},
        {{"--eye", "0,0,5", "--target", "-1e300,0,0"}, "--target: each coordinate must be within +-1e18"},
        {{"--eye", "1e19,0,5"}, "--eye: each coordinate must be within +-1e18"},
        {{"--bench-orbit", "10"}, "give --bench FRAMES too"},
        {{"--view", "1e308,0"}, "--view: azimuth must be -360 to 360"},
    };
    for (const auto& [bad, message] : cases) {
        std::vector<std::string> args = {limn, "--size", "32x32", "-o", out};
        args.insert(args.end(), bad.begin(), bad.end());
        auto r = render(args);
        EXPECT_EQ(r.exitCode, 2) << bad[0] << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
    // A non-parallel up renders.
    auto r = render({limn, "--size", "32x32", "-o", out, "--eye", "0,0,5", "--target", "0,0,0", "--up", "1,0,0"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(RenderCli, HelpListsDefaultsAndExitCodes) {
    auto r = render({"--help"});
    EXPECT_EQ(r.exitCode, 0);
    for (const char* needle :
         {"--size WxH", "[default: 1024x768]", "[default: -30,20]", "--light AZ,EL", "[default: -40,35]", "--color R,G,B", "--up-axis", "--mesh-out", "--bench FRAMES",
          "--device NAME", "Exit codes", "3  missing capability"})
        EXPECT_NE(r.out.find(needle), std::string::npos) << needle;
}

// /dev/stdout is a link to a link to the pipe (/proc/self/fd/1 -> "pipe:[N]"): written through,
// as the help promises for a device or FIFO (it failed: "cannot create output").
TEST(RenderCli, DevStdoutIsStandardOutput) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    auto r = render({limn, "--size", "32x24", "-o", "/dev/stdout"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.substr(0, 4), "\x89PNG");
}

TEST(RenderCli, DepfileAndBench) {
    ScratchDir dir;
    auto limn = classify(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube");
    auto out = (dir / "c.png").string(), dep = (dir / "c.d").string();
    auto r = render({limn, "--size", "32x32", "-o", out, "--depfile", dep});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readFile(dep), out + ": " + limn + "\n");

    r = render({limn, "--size", "32x32", "--bench", "3"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* key : {"{\"frames\":3,", "\"gpu_ms\":{\"compute\":", "\"draw\":", "\"total\":",
                            "\"cpu_ms\":", "\"triangles\":12,", "\"vertices_evaluated\":8,",
                            "\"buffer_bytes\":", "\"peak_rss_mb\":", "\"device\":\""})
        EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
    EXPECT_EQ(r.out.back(), '\n');
    EXPECT_EQ(r.out.find('\n'), r.out.size() - 1); // one line
}

// ----------------------------------------------------------------------------------------------
// Reference images (tests/render/ref/, made by make_refs.sh from ref/cases.txt, checked in).
// A pixel differs when any channel is off by more than kTolerance; at most kMaxDiffering of them
// may differ (rasterisation and sRGB rounding may shift edges between Mesa versions).

constexpr int kTolerance = 8;
constexpr double kMaxDifferingFraction = 0.01;

struct RefCase {
    std::string name, model;
    // Tools run before rendering, in order: {"limn-tables" | "limn-blend" | "limn-trim", args}.
    std::vector<std::pair<std::string, std::vector<std::string>>> steps;
    std::vector<std::string> options;
};

// gtest prints parameters in test listings; the name says it all.
void PrintTo(const RefCase& c, std::ostream* os) {
    *os << c.name;
}

std::vector<RefCase> referenceCases() {
    std::vector<RefCase> cases;
    std::ifstream in(std::string(LIMN_SOURCE_DIR) + "/tests/render/ref/cases.txt");
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        RefCase c;
        ls >> c.name >> c.model;
        for (std::string o; ls >> o;) {
            // Leading --tables=, --blend=, --trim=: comma-separated arguments of that tool.
            auto eq = o.find('=');
            if (c.options.empty() && eq != std::string::npos &&
                (o.rfind("--tables=", 0) == 0 || o.rfind("--blend=", 0) == 0 || o.rfind("--trim=", 0) == 0)) {
                std::vector<std::string> args;
                std::istringstream ts(o.substr(eq + 1));
                for (std::string t; std::getline(ts, t, ',');) args.push_back(t);
                c.steps.emplace_back("limn-" + o.substr(2, eq - 2), args);
                continue;
            }
            c.options.push_back(o);
        }
        cases.push_back(c);
    }
    return cases;
}

class RenderReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(RenderReference, MatchesWithinTolerance) {
    const RefCase& c = GetParam();
    ScratchDir dir;
    auto limn = classify(dir, modelPath(c.model).string(), c.name);
    std::vector<std::string> trim;
    for (const auto& [step, stepArgs] : c.steps) {
        const bool mask = step == "limn-trim";
        const std::string target = mask ? (dir / "mask.png").string() : limn;
        std::vector<std::string> args = {bin(step), limn, "-q", "-o", target};
        args.insert(args.end(), stepArgs.begin(), stepArgs.end());
        auto t = run(args);
        ASSERT_EQ(t.exitCode, 0) << step << ": " << t.err;
        if (mask) trim = {"--trim", target};
    }
    auto out = dir / (c.name + ".png");
    std::vector<std::string> args = {limn, "--size",    "128x96", "--sync-validation",
                                     "-o", out.string()};
    args.insert(args.end(), trim.begin(), trim.end());
    args.insert(args.end(), c.options.begin(), c.options.end());
    auto r = render(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto got = readPng(out);
    auto want =
        readPng(std::filesystem::path(LIMN_SOURCE_DIR) / "tests/render/ref" / (c.name + ".png"));
    ASSERT_EQ(got.width, want.width);
    ASSERT_EQ(got.height, want.height);
    ASSERT_EQ(got.channels, want.channels);
    size_t differing = 0;
    int worst = 0;
    for (size_t p = 0; p < size_t(got.width) * got.height; ++p) {
        int diff = 0;
        for (uint32_t k = 0; k < got.channels; ++k)
            diff = std::max(diff, std::abs(int(got.pixels[p * got.channels + k]) -
                                           int(want.pixels[p * got.channels + k])));
        worst = std::max(worst, diff);
        differing += diff > kTolerance;
    }
    const size_t allowed = size_t(kMaxDifferingFraction * got.width * got.height);
    EXPECT_LE(differing, allowed) << c.name << ": " << differing << " pixels differ by more than "
                                  << kTolerance << " (worst " << worst << ")";
    // The picture is not blank: some pixels differ from the top-left (background) one.
    size_t notBackground = 0;
    for (size_t p = 0; p < size_t(got.width) * got.height; ++p)
        notBackground +=
            std::memcmp(&got.pixels[p * got.channels], got.pixels.data(), got.channels) != 0;
    EXPECT_GT(notBackground, size_t(got.width) * got.height / 50) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Cases, RenderReference, ::testing::ValuesIn(referenceCases()),
                         [](const ::testing::TestParamInfo<RefCase>& param) {
                             return param.param.name;
                         });

} // namespace
