// limn-render's anti-aliasing (--samples, --supersample) and output formats (8/16-bit PNG, EXR)
// as users run it. Expected values come from the test's own computations: face
// colours and depths of an axis-aligned cube from its geometry and the camera, the supersample
// filter redone here in linear light from a render at twice the size, EXR read back with
// OpenImageIO directly (not through limn's plugin).
#include "image/png_decode.h"
#include "test_support.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

using namespace limn;
using namespace limn::test;

namespace {

std::string bin(const std::string& name) {
    return tool(name).string();
}

RunResult render(std::vector<std::string> args) {
    args.insert(args.begin(), bin("limn-render"));
    return run(args);
}

void renderOk(std::vector<std::string> args) {
    auto r = render(std::move(args));
    ASSERT_EQ(r.exitCode, 0) << r.err;
}

// The cube [-1, 1]^3, faces counter-clockwise seen from outside.
const char* kCubeObj = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                       "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                       "f 5 6 7 8\nf 2 1 4 3\nf 6 2 3 7\nf 1 5 8 4\nf 8 7 3 4\nf 1 2 6 5\n";

double toLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double toSrgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

struct Png {
    uint32_t width = 0, height = 0, channels = 0, bitDepth = 0;
    std::vector<float> values; // 0..1
};

Png readPng(const std::filesystem::path& path) {
    auto bytes = readBytes(path);
    Png png;
    EXPECT_GE(bytes.size(), 33u);
    if (bytes.size() < 33) return png;
    png.bitDepth = bytes[24]; // IHDR: signature 8, length 4, type 4, width 4, height 4, depth
    auto img = decodePngCommon(bytes);
    EXPECT_TRUE(img.has_value());
    if (!img) return png;
    png.width = img->width, png.height = img->height, png.channels = img->channels;
    png.values = img->values;
    return png;
}

// 8-bit levels of an image (whatever its depth), RGB only.
std::vector<std::array<int, 3>> levels(const Png& png) {
    std::vector<std::array<int, 3>> out(size_t(png.width) * png.height);
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < 3; ++c)
            out[i][c] = int(std::lround(png.values[i * png.channels + c] * 255.0));
    return out;
}

int maxDiff(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a[c] - b[c]));
    return d;
}

// --shade normal on the control mesh stores n * 0.5 + 0.5, so each face of the cube is one flat
// colour known from its normal. Returns the 8-bit sRGB values of the six faces.
std::vector<std::array<int, 3>> cubeFaceColours() {
    std::vector<std::array<int, 3>> out;
    for (int axis = 0; axis < 3; ++axis)
        for (int sign : {-1, 1}) {
            std::array<int, 3> c{};
            for (int k = 0; k < 3; ++k)
                c[k] = int(std::lround(((k == axis ? sign : 0) * 0.5 + 0.5) * 255.0));
            out.push_back(c);
        }
    return out;
}

// Whether pixel p (8-bit sRGB) is a strict mix, in linear light, of colours a and b: p = (1 - t) a
// + t b with t inside (0.04, 0.96), every channel within `tolerance` (linear).
bool isBlend(const std::array<int, 3>& p, const std::array<int, 3>& a, const std::array<int, 3>& b,
             double tolerance = 0.012) {
    double la[3], lb[3], lp[3], num = 0, den = 0;
    for (int c = 0; c < 3; ++c) {
        la[c] = toLinear(a[c] / 255.0), lb[c] = toLinear(b[c] / 255.0), lp[c] = toLinear(p[c] / 255.0);
        num += (lp[c] - la[c]) * (lb[c] - la[c]);
        den += (lb[c] - la[c]) * (lb[c] - la[c]);
    }
    if (den < 1e-6) return false;
    const double t = num / den;
    if (t < 0.04 || t > 0.96) return false;
    for (int c = 0; c < 3; ++c)
        if (std::abs(la[c] + t * (lb[c] - la[c]) - lp[c]) > tolerance) return false;
    return true;
}

struct Silhouette {
    size_t pure = 0;     // within 1 level of the background, a face colour or the wire colour
    size_t blends = 0;   // strict mixes of two of those
    size_t wireMix = 0;  // of them, mixes of the wire colour and a face
    size_t other = 0;    // neither
};

Silhouette classifyPixels(const Png& png, const std::array<int, 3>& background, bool wire) {
    std::vector<std::array<int, 3>> palette = cubeFaceColours();
    palette.push_back(background);
    // --wire draws in linear 0.006 (renderer.cpp): sRGB level 18.
    const int w8 = int(std::lround(toSrgb(0.006) * 255.0));
    const std::array<int, 3> wireColour{w8, w8, w8};
    if (wire) palette.push_back(wireColour);
    Silhouette s;
    for (const auto& p : levels(png)) {
        bool pure = false;
        for (const auto& c : palette) pure = pure || maxDiff(p, c) <= 1;
        if (pure) {
            ++s.pure;
            continue;
        }
        bool blend = false, wireBlend = false;
        for (size_t i = 0; i < palette.size(); ++i)
            for (size_t j = i + 1; j < palette.size(); ++j)
                if (isBlend(p, palette[i], palette[j])) {
                    blend = true;
                    wireBlend = wireBlend || (wire && palette[j] == wireColour && i < 6);
                }
        if (blend) ++s.blends;
        else ++s.other;
        if (wireBlend) ++s.wireMix;
    }
    return s;
}

class Output : public ::testing::Test {
  protected:
    void SetUp() override {
        writeFile(dir / "cube.obj", kCubeObj);
        auto r = run({bin("limn-classify"), (dir / "cube.obj").string(), "-o", cube});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = run({bin("limn-classify"), modelPath("quad/spot_control_mesh.obj").string(), "-o", spot});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = run({bin("limn-tables"), spot, "--depth", "2", "-q", "-o", spot});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    std::string out(const std::string& name) const { return (dir / name).string(); }
    ScratchDir dir;
    std::string cube = (dir / "cube.limn").string(), spot = (dir / "spot.limn").string();
};

// ----------------------------------------------------------------------------------------------

TEST_F(Output, SameCommandSameBytesForEverySamplingAndFormat) {
    const std::vector<std::vector<std::string>> variants = {
        {"--samples", "1"}, {"--samples", "4"}, {"--supersample", "2"},
        {"--supersample", "2", "--samples", "1"}, {"--bit-depth", "16"}, {"--alpha"},
        {"--sample-shading"}};
    for (const auto& v : variants) {
        std::string first;
        for (int k = 0; k < 2; ++k) {
            std::vector<std::string> args = {spot, "--size", "96x72", "--wire", "--validate", "-o",
                                             out("same.png")};
            args.insert(args.end(), v.begin(), v.end());
            renderOk(args);
            if (k == 0) first = readFile(out("same.png"));
            else EXPECT_TRUE(readFile(out("same.png")) == first) << v[0] << " " << v.back();
        }
    }
    std::string first;
    for (int k = 0; k < 2; ++k) {
        renderOk({spot, "--size", "96x72", "--supersample", "2", "-o", out("same.exr")});
        if (k == 0) first = readFile(out("same.exr"));
        else EXPECT_TRUE(readFile(out("same.exr")) == first) << "EXR bytes differ (a time stamp?)";
    }
}

// With one sample every pixel is exactly the background or one face's colour; with four, the
// silhouette and the edges between faces hold strict linear-light blends of the two sides, and
// lines drawn with --wire blend with the faces under them.
TEST_F(Output, FourSamplesBlendSilhouettesOneSampleDoesNot) {
    const std::array<int, 3> black{0, 0, 0};
    for (bool wire : {false, true}) {
        std::vector<std::string> base = {cube,          "--surface", "control", "--shade",
                                         "normal",      "--view",    "30,25",   "--background",
                                         "0,0,0",       "--size",    "160x120", "--sync-validation"};
        if (wire) base.push_back("--wire");
        auto one = base, four = base;
        one.insert(one.end(), {"--samples", "1", "-o", out("one.png")});
        four.insert(four.end(), {"-o", out("four.png")}); // 4 is the default
        renderOk(one);
        renderOk(four);
        const Silhouette s1 = classifyPixels(readPng(out("one.png")), black, wire);
        const Silhouette s4 = classifyPixels(readPng(out("four.png")), black, wire);
        // The cube covers a good part of the image (pure pixels of three faces at least).
        EXPECT_GT(s1.pure, 160u * 120u / 8) << "wire " << wire;
        EXPECT_EQ(s1.blends + s1.other, 0u) << "wire " << wire;
        // The silhouette of a cube this size is ~300 pixels long; most edge pixels are mixed.
        EXPECT_GT(s4.blends, 150u) << "wire " << wire;
        // Mixes are of two neighbours, not arbitrary colours (a few pixels where three meet).
        EXPECT_LT(s4.other, s4.blends / 10 + 5) << "wire " << wire;
        if (wire) {
            EXPECT_EQ(s1.wireMix, 0u);
            EXPECT_GT(s4.wireMix, 50u) << "wire lines are not anti-aliased";
        }
    }
}

// Away from edges MSAA changes nothing: the fragment shader runs once per pixel, at its centre.
TEST_F(Output, FourSamplesKeepInteriorPixelsExact) {
    for (const char* shade : {"normal", "uv", "levels"}) {
        for (const char* samples : {"1", "4"})
            renderOk({spot, "--shade", shade, "--size", "128x96", "--view", "200,15", "--samples",
                      samples, "-o", out(std::string("s") + samples + ".png")});
        const auto a = levels(readPng(out("s1.png"))), b = levels(readPng(out("s4.png")));
        ASSERT_EQ(a.size(), b.size());
        const uint32_t w = 128, h = 96;
        size_t interior = 0, equal = 0;
        for (uint32_t y = 1; y + 1 < h; ++y)
            for (uint32_t x = 1; x + 1 < w; ++x) {
                // Interior: the 3x3 neighbourhood in the one-sample image varies smoothly.
                bool flat = true;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        flat = flat && maxDiff(a[y * w + x], a[(y + dy) * w + (x + dx)]) <= 6;
                if (!flat) continue;
                ++interior;
                equal += maxDiff(a[y * w + x], b[y * w + x]) == 0;
            }
        EXPECT_GT(interior, w * h / 4) << shade;
        // A few interior pixels hold a triangle edge inside the surface, where the centre is
        // covered by another triangle than some samples; those may round differently. Their
        // share follows the triangles per pixel: here about 6,200 triangles on 10,800 interior
        // pixels (depth 2, view-adaptive with its chord criterion), 0.57% of them differ.
        EXPECT_GE(double(equal), 0.99 * double(interior)) << shade;
    }
}

// --supersample 2 is a render at twice the size, each 2x2 block averaged in linear light: redone
// here from an 8-bit --samples 1 render at 2x. The 8-bit source rounds each sample by half a
// level, the float path does not: allow 1 level, and 2 on a handful of pixels.
TEST_F(Output, SupersampleMatchesBoxFilteredDoubleSizeRender) {
    renderOk({spot, "--samples", "1", "--supersample", "2", "--size", "80x60", "--view", "200,15",
              "--validate", "-o", out("ss.png")});
    renderOk({spot, "--samples", "1", "--size", "160x120", "--view", "200,15", "-o", out("big.png")});
    renderOk({spot, "--samples", "1", "--size", "80x60", "--view", "200,15", "-o", out("small.png")});
    const Png ss = readPng(out("ss.png")), big = readPng(out("big.png")),
              small = readPng(out("small.png"));
    ASSERT_EQ(ss.width, 80u);
    ASSERT_EQ(ss.height, 60u);
    ASSERT_EQ(big.width, 160u);
    size_t within1 = 0, over2 = 0, differsFromSmall = 0;
    const auto ssLevels = levels(ss), smallLevels = levels(small);
    for (uint32_t y = 0; y < 60; ++y)
        for (uint32_t x = 0; x < 80; ++x) {
            std::array<int, 3> expected{};
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int j = 0; j < 2; ++j)
                    for (int i = 0; i < 2; ++i)
                        sum += toLinear(big.values[((2 * y + j) * 160 + 2 * x + i) * 3 + c]);
                expected[c] = int(std::lround(toSrgb(sum / 4) * 255.0));
            }
            const int d = maxDiff(ssLevels[y * 80 + x], expected);
            within1 += d <= 1;
            over2 += d > 2;
            differsFromSmall += maxDiff(ssLevels[y * 80 + x], smallLevels[y * 80 + x]) > 8;
        }
    EXPECT_EQ(over2, 0u);
    EXPECT_GE(within1, size_t(0.99 * 80 * 60));
    // And it did filter: the silhouette differs from a plain one-sample render.
    EXPECT_GT(differsFromSmall, 40u);
}

TEST_F(Output, SixteenBitPngRoundsToTheEightBitOne) {
    for (bool alpha : {false, true}) {
        std::vector<std::string> base = {spot, "--size", "96x72", "--view", "200,15", "--validate"};
        if (alpha) base.push_back("--alpha");
        auto a = base, b = base;
        a.insert(a.end(), {"-o", out("8.png")});
        b.insert(b.end(), {"--bit-depth", "16", "-o", out("16.png")});
        renderOk(a);
        renderOk(b);
        const Png p8 = readPng(out("8.png")), p16 = readPng(out("16.png"));
        EXPECT_EQ(p8.bitDepth, 8u);
        EXPECT_EQ(p16.bitDepth, 16u);
        ASSERT_EQ(p16.channels, alpha ? 4u : 3u);
        ASSERT_EQ(p8.values.size(), p16.values.size());
        size_t fine = 0, worst = 0, notEightBit = 0;
        size_t covered = 0;
        const uint32_t ch = p16.channels;
        for (size_t i = 0; i < p16.values.size(); ++i) {
            const size_t pixel = i / ch;
            // Straight alpha: where a pixel is transparent its colour carries no information.
            if (alpha && p8.values[pixel * ch + 3] == 0.0f) continue;
            // The surface (not the 0.2 background), colour channels: 16-bit values proper.
            if (i % ch < 3 && std::lround(p8.values[pixel * ch] * 255.0) != 51) {
                const double v16 = p16.values[i] * 65535.0;
                notEightBit += std::abs(v16 / 257.0 - std::round(v16 / 257.0)) > 1e-6;
                ++covered;
            }
            const long d = std::abs(std::lround(p16.values[i] * 255.0) - std::lround(p8.values[i] * 255.0));
            worst = std::max<size_t>(worst, size_t(d));
            fine += d <= 1;
        }
        EXPECT_LE(worst, 1u) << "alpha " << alpha;
        // Really 16 bits: most samples are not 8-bit values widened (k * 257).
        EXPECT_GT(covered, 1000u);
        EXPECT_GT(notEightBit, covered * 3 / 4) << "alpha " << alpha;
    }
}

// The EXR holds R, G, B, A, Z in linear light: the background colour decoded from sRGB, the +Z
// face of a cube seen head-on at its colour, depth the distance along the view axis.
TEST_F(Output, ExrHoldsLinearColourAlphaAndDepth) {
    // Eye on +Z at distance 5 from the centre: the face z = 1 is 4 away along the view direction,
    // at every pixel it covers (a plane perpendicular to the view axis).
    const double bg[3] = {0.2, 0.4, 0.6};
    for (bool alpha : {false, true}) {
        std::vector<std::string> args = {cube, "--surface", "control", "--shade", "normal",
                                         "--eye", "0,0,5", "--target", "0,0,0", "--size", "64x48",
                                         "--background", "0.2,0.4,0.6", "--sync-validation",
                                         "-o", out("c.exr")};
        if (alpha) args.push_back("--alpha");
        renderOk(args);
        auto in = OIIO::ImageInput::open(out("c.exr"));
        ASSERT_TRUE(in) << OIIO::geterror();
        const OIIO::ImageSpec& spec = in->spec();
        ASSERT_EQ(spec.width, 64);
        ASSERT_EQ(spec.height, 48);
        ASSERT_EQ(spec.nchannels, 5);
        std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
        // OpenEXR stores channels sorted by name; OpenImageIO gives RGBA first, then the rest.
        EXPECT_EQ(names, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
        EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
        std::vector<float> px(64 * 48 * 5);
        ASSERT_TRUE(in->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, px.data())) << in->geterror();
        in->close();
        auto at = [&](int x, int y, int c) { return px[(size_t(y) * 64 + x) * 5 + c]; };
        // A corner: background. Half-float precision: 1e-3 relative.
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(at(0, 0, c), alpha ? 0.0 : toLinear(bg[c]), 1e-3 * (1 + toLinear(bg[c])));
        EXPECT_EQ(at(0, 0, 3), alpha ? 0.0f : 1.0f);
        EXPECT_TRUE(std::isinf(at(0, 0, 4)) && at(0, 0, 4) > 0) << at(0, 0, 4);
        // The centre: the +Z face, normal (0, 0, 1), stored as sRGB (0.5, 0.5, 1).
        const double face[3] = {toLinear(0.5), toLinear(0.5), 1.0};
        for (int y : {20, 24, 27})
            for (int x : {28, 32, 35}) {
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(at(x, y, c), face[c], 2e-3) << x << "," << y;
                EXPECT_EQ(at(x, y, 3), 1.0f);
                EXPECT_NEAR(at(x, y, 4), 4.0, 4e-4) << x << "," << y;
            }
    }
}

TEST_F(Output, UnsupportedExtensionsAreUsageErrorsAndWriteNothing) {
    for (const char* name : {"x.jpg", "x.tif", "x", "x.png.bak", "dir.png/x"}) {
        auto r = render({cube, "--size", "16x16", "-o", out(name)});
        EXPECT_EQ(r.exitCode, 2) << name << ": " << r.err;
        EXPECT_NE(r.err.find(".png"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(".exr"), std::string::npos) << r.err;
    }
    auto r = render({cube, "--size", "16x16", "--bit-depth", "16", "-o", out("x.exr")});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--bit-depth"), std::string::npos) << r.err;
    r = render({cube, "--size", "16x16", "--bit-depth", "12", "-o", out("x.png")});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    r = render({cube, "--size", "16x16", "--samples", "2", "-o", out("x.png")});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("1 or 4"), std::string::npos) << r.err;
    // Upper-case extensions are the same formats; a device is a stream, like standard output.
    renderOk({cube, "--size", "16x16", "-o", out("upper.PNG")});
    renderOk({cube, "--size", "16x16", "-o", "/dev/null"});
    // Nothing else was left behind: no output, no temporary file.
    auto files = filesIn(dir.path());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"cube.limn", "cube.obj", "spot.limn", "upper.PNG"}));
}

TEST_F(Output, MissingImagePluginIsExitCode3ForExrOnly) {
    auto r = run({"/usr/bin/env", "LIMN_IMAGE_PLUGIN=/nonexistent/limn_image_oiio.so",
                  bin("limn-render"), cube, "--size", "16x16", "-o", out("x.exr"), "--depfile",
                  out("x.d")});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("limn_image_oiio"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out("x.exr")));
    EXPECT_FALSE(std::filesystem::exists(out("x.d")));
    // PNGs never need it.
    r = run({"/usr/bin/env", "LIMN_IMAGE_PLUGIN=/nonexistent/limn_image_oiio.so",
             bin("limn-render"), cube, "--size", "16x16", "--bit-depth", "16", "--supersample",
             "2", "-o", out("x.png")});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST_F(Output, ExrAndSixteenBitKeepDepfileAndAtomicOutput) {
    renderOk({cube, "--size", "16x16", "-o", out("d.exr"), "--depfile", out("d.d")});
    EXPECT_EQ(readFile(out("d.d")), out("d.exr") + ": " + cube + "\n");
    // A failed run (no UVs for --shade uv) keeps the previous file and leaves no temporary one.
    writeFile(out("keep.exr"), "previous");
    auto r = render({cube, "--size", "16x16", "--shade", "uv", "-o", out("keep.exr")});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(readFile(out("keep.exr")), "previous");
    for (const auto& f : filesIn(dir.path())) EXPECT_EQ(f.find("tmp"), std::string::npos) << f;
}

TEST_F(Output, ImageMemoryIsCheckedBeforeDrawing) {
    // The device's largest image is 16384 on lavapipe (and at most that on the --size range):
    // twice 16384 cannot be drawn.
    auto r = render({cube, "--size", "16384x64", "--supersample", "2", "-o", out("big.png")});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("largest image"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out("big.png")));
    // 1024x768 with 4 samples takes ~28 MiB on the device alone: over a 4 MiB budget.
    r = render({cube, "--size", "1024x768", "--max-memory", "4M", "-o", out("m.png")});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out("m.png")));
    renderOk({cube, "--size", "1024x768", "--samples", "1", "--max-memory", "16M", "-o", out("m.png")});
}

// --sample-shading: nothing changes with one sample (the pixel centre is the sample), the
// shading of a curved surface does with four (each sample is shaded where it lies, not all four at
// the pixel centre), and the bench JSON says which it was. (Its point, highlights on surfaces that
// bend within a pixel, is checked on catmark_car in adaptive_image_cli_test.cpp.)
TEST_F(Output, SampleShadingShadesEachSample) {
    renderOk({spot, "--size", "128x96", "--samples", "1", "--validate", "-o", out("one.png")});
    renderOk({spot, "--size", "128x96", "--samples", "1", "--sample-shading", "--validate", "-o", out("one_ss.png")});
    EXPECT_TRUE(readFile(out("one.png")) == readFile(out("one_ss.png")));
    renderOk({spot, "--size", "128x96", "--validate", "-o", out("four.png")});
    renderOk({spot, "--size", "128x96", "--sample-shading", "--validate", "-o", out("four_ss.png")});
    const auto a = readPng(out("four.png")), b = readPng(out("four_ss.png"));
    ASSERT_EQ(a.values.size(), b.values.size());
    size_t differ = 0;
    for (size_t i = 0; i < a.values.size(); ++i) differ += a.values[i] != b.values[i];
    EXPECT_GT(differ, 100u);
    for (bool on : {false, true}) {
        std::vector<std::string> args = {cube, "--size", "32x32", "--bench", "2"};
        if (on) args.push_back("--sample-shading");
        auto r = render(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.out.find(on ? "\"sample_shading\":true" : "\"sample_shading\":false"), std::string::npos) << r.out;
    }
}

TEST(OutputHelp, DocumentsSamplingFormatsAndDepth) {
    auto r = render({"--help"});
    EXPECT_EQ(r.exitCode, 0);
    for (const char* needle : {"--samples 1|4", "[default: 4]", "--supersample K", "[default: 1]",
                               "--bit-depth 8|16", "--max-memory SIZE", ".exr", "box filter", "--sample-shading",
                               "linear light", "Z is the camera-space depth", "+Inf"})
        EXPECT_NE(r.out.find(needle), std::string::npos) << needle;
}

TEST_F(Output, BenchReportsSamples) {
    for (const char* samples : {"1", "4"}) {
        auto r = render({cube, "--size", "32x32", "--bench", "2", "--samples", samples});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(jsonInt(r.out, "samples"), std::stoll(samples)) << r.out;
        EXPECT_EQ(jsonInt(r.out, "supersample"), 1) << r.out;
    }
}

} // namespace
