// limn-render on blending surfaces as users run it: which surface a container gives, trimming
// (paper 001, 4.3) checked pixel by pixel, determinism, the two evaluation paths, errors, and
// limn-trim. Every render runs with --sync-validation, so exit code 0 means no validation error.
#include "mesh/obj.h"
#include "image/srgb_image.h"
#include "blend/trim.h"
#include "test_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

using namespace limn;
using namespace limn::test;

namespace {

std::string bin(const std::string& name) {
    return tool(name).string();
}

// OBJ text or a shared model -> classify -> blend (ARGS) -> NAME.limn in dir.
std::string blendContainer(const ScratchDir& dir, const std::string& name, const std::string& obj,
                           std::vector<std::string> blendArgs = {}) {
    const std::string limn = (dir / (name + ".limn")).string();
    auto r = run({bin("limn-classify"), obj, "-o", limn});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    blendArgs.insert(blendArgs.begin(), {bin("limn-blend"), limn, "-q", "-o", limn});
    r = run(blendArgs);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return limn;
}

std::string writeMesh(const ScratchDir& dir, const std::string& name, const Mesh& m) {
    auto path = dir / (name + ".obj");
    writeFile(path, writeObj(m));
    return path.string();
}

RunResult render(std::vector<std::string> args) {
    args.insert(args.begin(), {bin("limn-render"), "--sync-validation"});
    return run(args);
}

Image readPng(const std::filesystem::path& p) {
    return decodePng(readBytes(p));
}

bool isBackground(const Image& img, uint32_t x, uint32_t y, std::array<int, 3> bg) {
    const uint8_t* p = img.at(x, y);
    return p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2];
}

// A gently bent 4×4 grid of quads seen from above: an open height field, so nothing lies behind
// any face and removing a face can only reveal the background.
Mesh bentGrid() {
    return blendtest::grid(
        4, [](double x, double y) { return 0.15 * std::sin(x) * std::cos(0.7 * y); });
}
const std::vector<std::string> kTopView = {"--eye",  "2,2,9",  "--target",     "2,2,0",
                                           "--fov",  "40",     "--background", "1,0,1",
                                           "--size", "160x160",
                                           // One sample per pixel: the exact-pixel checks rely
                                           // on the rasterizer's top-left rule, not on coverage.
                                           "--samples", "1"};
constexpr std::array<int, 3> kMagenta = {255, 0, 255};

// ----------------------------------------------------------------------------------------------

TEST(BlendTrim, RemovedFaceShowsBackgroundExactlyWhereItProjects) {
    ScratchDir dir;
    auto limn = blendContainer(dir, "grid", writeMesh(dir, "grid", bentGrid()));
    const uint32_t F = 16, removed = 5;
    std::string allButRemoved;
    for (uint32_t f = 0; f < F; ++f)
        if (f != removed) allButRemoved += (allButRemoved.empty() ? "" : ",") + std::to_string(f);
    struct Variant {
        std::string name;
        std::vector<std::string> trim; // limn-trim arguments; empty: no --trim
    };
    for (const Variant& v :
         {Variant{"full", {}}, Variant{"keep_all", {"--hole", "0"}},
          Variant{"without", {"--hole", "0", "--remove", std::to_string(removed)}},
          Variant{"only", {"--hole", "0", "--remove", allButRemoved}}}) {
        std::vector<std::string> args = {limn, "--grid", "6", "-o",
                                         (dir / (v.name + ".png")).string()};
        if (!v.trim.empty()) {
            std::vector<std::string> t = {bin("limn-trim"),
                                          limn,
                                          "--tile",
                                          "8",
                                          "-o",
                                          (dir / (v.name + "_mask.png")).string()};
            t.insert(t.end(), v.trim.begin(), v.trim.end());
            auto r = run(t);
            ASSERT_EQ(r.exitCode, 0) << r.err;
            args.insert(args.end(), {"--trim", (dir / (v.name + "_mask.png")).string()});
        }
        args.insert(args.end(), kTopView.begin(), kTopView.end());
        auto r = render(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    auto full = readPng(dir / "full.png"), keepAll = readPng(dir / "keep_all.png");
    auto without = readPng(dir / "without.png"), only = readPng(dir / "only.png");
    EXPECT_EQ(full.pixels, keepAll.pixels) << "an all-white trim map must change nothing";
    // Face 5's pixels: what the "only" render draws. The shared edges are bit-identical, so the
    // rasterizer's top-left rule gives every boundary pixel to exactly one face: "without" must be
    // background exactly there and equal to the full render everywhere else.
    size_t faceArea = 0, mismatches = 0;
    for (uint32_t y = 0; y < full.height; ++y)
        for (uint32_t x = 0; x < full.width; ++x) {
            const bool inFace = !isBackground(only, x, y, kMagenta);
            faceArea += inFace;
            if (inFace) {
                mismatches += !isBackground(without, x, y, kMagenta);
                mismatches += std::memcmp(only.at(x, y), full.at(x, y), 3) != 0;
            } else {
                mismatches += std::memcmp(without.at(x, y), full.at(x, y), 3) != 0;
            }
        }
    EXPECT_GT(faceArea, 300u) << "face 5 covers a good part of the picture";
    EXPECT_EQ(mismatches, 0u);
}

// A unit square seen from +z: u runs right and v up on screen, as they do in the trim tile.
TEST(BlendTrim, TileAddressingUIsRightVIsUp) {
    ScratchDir dir;
    writeFile(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    auto limn = blendContainer(dir, "quad", (dir / "quad.obj").string());
    // Masks written here, not by limn-trim: one 8×8 tile (one face); PGM, a format OpenImageIO
    // reads that limn never writes. Texel rows run top to bottom, so v < 0.5 is rows 4..7.
    auto pgm = [&](const std::string& name, auto keep) {
        std::string s = "P5\n8 8\n255\n";
        for (int row = 0; row < 8; ++row)
            for (int col = 0; col < 8; ++col) s += char(keep(col, row) ? 255 : 0);
        writeFile(dir / name, s);
        return (dir / name).string();
    };
    auto cutLeft = pgm("left.pgm", [](int col, int) { return col >= 4; });    // u < 0.5 cut
    auto cutBottom = pgm("bottom.pgm", [](int, int row) { return row < 4; }); // v < 0.5 cut
    for (const auto& [mask, name] : {std::pair{cutLeft, "left"}, {cutBottom, "bottom"}}) {
        auto out = dir / (std::string(name) + ".png");
        auto r = render({limn, "--trim", mask, "--grid", "4", "--eye", "0.5,0.5,3", "--target",
                         "0.5,0.5,0", "--fov", "30", "--background", "1,0,1", "--size", "64x64",
                         "-o", out.string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        auto img = readPng(out);
        size_t surface[2][2] = {}; // [bottom?][right?]
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                surface[y >= 32][x >= 32] += !isBackground(img, x, y, kMagenta);
        if (std::string(name) == "left") {
            EXPECT_EQ(surface[0][0] + surface[1][0], 0u);
            EXPECT_GT(surface[0][1], 100u);
            EXPECT_GT(surface[1][1], 100u);
        } else {
            EXPECT_EQ(surface[1][0] + surface[1][1], 0u);
            EXPECT_GT(surface[0][0], 100u);
            EXPECT_GT(surface[0][1], 100u);
        }
    }
}

TEST(BlendRenderCli, SameBytesTwiceAndBothEvaluationPathsDrawTheSamePicture) {
    ScratchDir dir;
    auto limn = blendContainer(dir, "spot", modelPath("quad/spot_control_mesh.obj").string(),
                               {"--quadrangulate"});
    auto mask = (dir / "holes.png").string();
    ASSERT_EQ(run({bin("limn-trim"), limn, "-o", mask}).exitCode, 0);
    std::vector<std::string> common = {limn,     "--trim", mask,     "--size",
                                       "128x96", "--view", "200,15", "--wire"};
    auto draw = [&](const std::string& name, std::vector<std::string> extra) {
        auto args = common;
        args.insert(args.end(), extra.begin(), extra.end());
        args.insert(args.end(), {"-o", (dir / name).string()});
        auto r = render(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readFile(dir / name);
    };
    auto a = draw("a.png", {}), b = draw("b.png", {}), v = draw("v.png", {"--eval", "vertex"});
    EXPECT_EQ(a, b) << "same command, same bytes";
    // The vertex stage evaluates with the same code (blend_eval.glsl) at the same points.
    auto ia = readPng(dir / "a.png"), iv = readPng(dir / "v.png");
    size_t differing = 0;
    for (size_t i = 0; i < ia.pixels.size(); ++i)
        differing += std::abs(ia.pixels[i] - iv.pixels[i]) > 2;
    EXPECT_LE(differing, ia.pixels.size() / 1000) << "vertex-stage and compute evaluation differ";
}

TEST(BlendRenderCli, SurfaceChoice) {
    ScratchDir dir;
    auto limn = blendContainer(dir, "torus", modelPath("quad/osd_catmark_torus.obj").string());
    auto r = run({bin("limn-tables"), limn, "-q", "--depth", "2", "-o", limn});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto draw = [&](const std::string& surface) {
        auto out = dir / (surface + ".png");
        std::vector<std::string> args = {limn, "--size", "64x48", "-o", out.string()};
        if (!surface.empty()) args.insert(args.end(), {"--surface", surface});
        auto rr = render(args);
        EXPECT_EQ(rr.exitCode, 0) << surface << ": " << rr.err;
        return readFile(out);
    };
    const auto automatic = draw(""), blendSurface = draw("blend"),
               subdivision = draw("subdivision"), control = draw("control");
    EXPECT_EQ(automatic, blendSurface) << "BLND wins over TBLS";
    EXPECT_NE(blendSurface, subdivision);
    EXPECT_NE(blendSurface, control);
    EXPECT_NE(subdivision, control);
}

TEST(BlendRenderCli, ErrorsAndNoPartialOutput) {
    ScratchDir dir;
    const auto obj = writeMesh(dir, "grid", bentGrid()); // 16 faces, no UVs
    auto limn = blendContainer(dir, "grid", obj);
    auto plain = (dir / "plain.limn").string();
    ASSERT_EQ(run({bin("limn-classify"), obj, "-o", plain}).exitCode, 0);
    auto mask = (dir / "mask.png").string();
    ASSERT_EQ(run({bin("limn-trim"), limn, "--tile", "4", "-o", mask}).exitCode, 0);
    Image wrong{6, 4, 1, std::vector<uint8_t>(24, 255)}; // 16 faces need 4x4 tiles
    auto wrongMask = (dir / "wrong.png").string();
    writeFile(wrongMask, std::string(reinterpret_cast<const char*>(encodePng(wrong).data()),
                                     encodePng(wrong).size()));
    const std::string out = (dir / "out.png").string();
    struct Bad {
        std::vector<std::string> args;
        int exitCode;
        std::string message;
    };
    for (const Bad& b : std::vector<Bad>{
             {{limn, "--surface", "control", "--trim", mask}, 2, "--trim"},
             {{limn, "--grid", "0"}, 2, "--grid"},
             {{limn, "--grid", "5000"}, 2, "--grid"},
             {{plain, "--trim", mask}, 1, "limn-blend"},
             {{plain, "--surface", "blend"}, 1, "limn-blend"},
             {{limn, "--surface", "subdivision"}, 1, "limn-tables"},
             {{limn, "--trim", wrongMask}, 1, "4x4"},
             {{limn, "--trim", (dir / "missing.png").string()}, 1, "missing.png"},
             {{limn, "--shade", "uv"}, 1, "texture coordinates"},
         }) {
        auto args = b.args;
        args.insert(args.end(), {"-o", out});
        auto r = render(args);
        EXPECT_EQ(r.exitCode, b.exitCode) << b.args[1] << ": " << r.err;
        EXPECT_NE(r.err.find(b.message), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << b.args[1];
    }
}

TEST(BlendRenderCli, LevelsColourQuarterFacesByValence) {
    ScratchDir dir;
    // Quadrangulated bipyramid: apexes of valence 5 (yellow), face centres of valence 3 (blue).
    auto limn = blendContainer(dir, "bipyramid", writeMesh(dir, "b", blendtest::bipyramid(5)),
                               {"--quadrangulate"});
    auto out = dir / "levels.png";
    auto r = render(
        {limn, "--shade", "levels", "--view", "20,50", "--size", "96x96", "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readPng(out);
    size_t blue = 0, yellow = 0;
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            blue += p[2] > p[0] + 60 && p[2] > p[1] + 30;
            yellow += p[0] > p[2] + 60 && p[1] > p[2] + 60;
        }
    EXPECT_GT(blue, 50u);
    EXPECT_GT(yellow, 50u);
}

TEST(BlendRenderCli, BenchReportsTheEvaluationPassAndDepfileNamesTheTrimMap) {
    ScratchDir dir;
    auto limn = blendContainer(dir, "torus", modelPath("quad/osd_catmark_torus.obj").string());
    auto mask = (dir / "mask.png").string();
    ASSERT_EQ(run({bin("limn-trim"), limn, "-o", mask}).exitCode, 0);
    // osd_catmark_torus: 32 vertices, 64 edges, 32 faces; --grid 4: 32 + 64·3 + 32·9 points.
    auto r = render({limn, "--bench", "2", "--grid", "4", "--size", "32x32", "--trim", mask});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* key :
         {"\"evaluate blend surface\":", "\"triangles\":1024,", "\"vertices_evaluated\":512,"})
        EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
    auto out = (dir / "t.png").string(), dep = (dir / "t.d").string();
    r = render({limn, "--trim", mask, "--size", "32x32", "-o", out, "--depfile", dep});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readFile(dep), out + ": " + limn + " " + mask + "\n");
}

// --sample-shading trims each sample on its own, so a hole's rim is anti-aliased like a
// silhouette; without it a pixel is kept or discarded whole (one fragment per pixel and triangle),
// and only the grid's outline blends with the background. Counted: pixels that are neither the
// magenta background nor the grey surface (lit neutral grey: channels within 12 levels).
TEST(BlendTrim, SampleShadingAntiAliasesTheTrimEdge) {
    ScratchDir dir;
    auto limn = blendContainer(dir, "grid", writeMesh(dir, "grid", bentGrid()));
    const auto mask = (dir / "holes.png").string();
    auto r = run({bin("limn-trim"), limn, "--tile", "64", "--hole", "0.3", "-o", mask});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto mixed = [&](const std::vector<std::string>& extra, const std::string& name) {
        std::vector<std::string> args = {limn, "--grid", "6", "--trim", mask, "--eye", "2,2,9",
                                         "--target", "2,2,0", "--fov", "40", "--background", "1,0,1",
                                         "--size", "160x160", "-o", (dir / name).string()};
        args.insert(args.end(), extra.begin(), extra.end());
        auto res = render(args);
        EXPECT_EQ(res.exitCode, 0) << res.err;
        const auto img = readPng(dir / name);
        size_t n = 0, holes = 0;
        for (uint32_t y = 0; y < img.height; ++y)
            for (uint32_t x = 0; x < img.width; ++x) {
                const uint8_t* p = img.at(x, y);
                if (isBackground(img, x, y, kMagenta)) {
                    ++holes;
                    continue;
                }
                n += std::abs(int(p[0]) - int(p[1])) > 12 || std::abs(int(p[2]) - int(p[1])) > 12;
            }
        EXPECT_GT(holes, 160u * 160u / 2) << name; // the background and 16 holes show
        return n;
    };
    const size_t perPixel = mixed({}, "pixel.png"), perSample = mixed({"--sample-shading"}, "sample.png");
    // 16 holes of about 7 pixels' radius: some 700 pixels of rim.
    EXPECT_GT(perSample, perPixel + 300) << perPixel << " " << perSample;
    EXPECT_EQ(mixed({"--samples", "1"}, "one.png"), 0u);
}

TEST(TrimCli, WritesTheAtlasForTheContainersFaces) {
    ScratchDir dir;
    auto limn = blendContainer(dir, "spot", modelPath("quad/spot_control_mesh.obj").string(),
                               {"--quadrangulate"}); // 732 quads: 28 × 27 tiles
    auto out = dir / "m.png";
    auto r = run({bin("limn-trim"), limn, "--tile", "6", "--remove", "0,731", "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readPng(out);
    EXPECT_EQ(img.width, 28u * 6);
    EXPECT_EQ(img.height, 27u * 6);
    EXPECT_EQ(img.channels, 1u);
    blend::TrimLayout l = blend::trimAtlasLayout(732, 6);
    auto at = [&](uint32_t f, double u, double v) {
        auto t = blend::trimTexel(l, f, u, v);
        return img.pixels[size_t(t.y) * img.width + t.x];
    };
    EXPECT_EQ(at(0, 0.9, 0.9), 0);   // removed
    EXPECT_EQ(at(731, 0.1, 0.1), 0); // removed
    EXPECT_EQ(at(1, 0.5, 0.5), 0);   // the default hole
    EXPECT_EQ(at(1, 0.05, 0.05), 255);
    for (const auto& [args, code] :
         std::vector<std::pair<std::vector<std::string>, int>>{{{"--remove", "732"}, 1},
                                                               {{"--remove", "x"}, 2},
                                                               {{"--tile", "0"}, 2},
                                                               {{"--hole", "2"}, 2}}) {
        std::vector<std::string> a = {bin("limn-trim"), limn, "-o", (dir / "bad.png").string()};
        a.insert(a.end(), args.begin(), args.end());
        EXPECT_EQ(run(a).exitCode, code) << args[0] << " " << args[1];
        EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
    }
    r = run({bin("limn-trim"), "--help"});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("[default: 32]"), std::string::npos) << r.out;
}

} // namespace
