// limn-render's look: framing measured in the image, --up-axis against a mesh turned by hand,
// and the lit rig's options (glTF materials: gltf_material_cli_test.cpp). Every render runs
// with --validate, so exit code 0 also means no validation errors.
#include "look_cli_support.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

using namespace limn;
using namespace limn::test;
using namespace limn::look_test;

namespace {

// The object's extent in the image: the box of the pixels that are not the key background.
struct Silhouette {
    uint32_t x0 = ~0u, y0 = ~0u, x1 = 0, y1 = 0;
    size_t pixels = 0;
    uint32_t width() const { return pixels ? x1 - x0 + 1 : 0; }
    uint32_t height() const { return pixels ? y1 - y0 + 1 : 0; }
};

Silhouette silhouette(const Image& img) {
    Silhouette s;
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            if (p[0] == 255 && p[1] == 0 && p[2] == 255) continue;
            ++s.pixels;
            s.x0 = std::min(s.x0, x), s.x1 = std::max(s.x1, x);
            s.y0 = std::min(s.y0, y), s.y1 = std::max(s.y1, y);
        }
    return s;
}

// The larger silhouette extent over the frame's smaller side.
double fill(const Image& img, const Silhouette& s) {
    return double(std::max(s.width(), s.height())) / double(std::min(img.width, img.height));
}

// Pixels whose channels differ by more than `tolerance` anywhere, as a fraction of all pixels.
double differing(const Image& a, const Image& b, int tolerance) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.pixels.size() != b.pixels.size()) return 1.0;
    size_t n = 0;
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i)
        for (uint32_t c = 0; c < a.channels; ++c)
            if (std::abs(int(a.pixels[i * a.channels + c]) - int(b.pixels[i * b.channels + c])) >
                tolerance) {
                ++n;
                break;
            }
    return double(n) / (double(a.width) * a.height);
}

} // namespace

// ---- framing ------------------------------------------------------------------------------

// The object's larger extent spans 80-90% of the frame's smaller side (the camera fits 85%),
// whatever the model, the view and the frame's orientation, and the image is centred.
TEST(Framing, FillsAboutEightyFivePercentOfTheSmallerSide) {
    ScratchDir dir;
    const std::string spot = prepare(dir, modelPath("quad/spot_control_mesh.obj").string(), "spot", 2);
    const std::string cube = prepare(dir, modelPath("quad/osd_catmark_cube.obj").string(), "cube", 3);
    const std::string car = prepare(dir, modelPath("osd/catmark/catmark_car.obj").string(), "car", -1);
    const std::string torus = prepare(dir, modelPath("quad/osd_catmark_torus.obj").string(), "torus", -1);
    struct Case {
        std::string input;
        std::vector<std::string> options;
    };
    const std::vector<Case> cases = {
        {spot, {}},
        {spot, {"--view", "150,20"}},
        {spot, {"--view", "90,0", "--size", "120x160"}},
        {cube, {"--view", "0,0"}},
        {cube, {"--view", "35,30", "--size", "200x100"}},
        {car, {"--up-axis", "z"}},
        {car, {"--up-axis", "z", "--view", "90,10"}},
        {torus, {"--view", "10,70"}}, // the control mesh
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {c.input, "--background", kKey, "-o", (dir / "f.png").string()};
        if (std::find(c.options.begin(), c.options.end(), "--size") == c.options.end())
            args.insert(args.end(), {"--size", "160x120"});
        args.insert(args.end(), c.options.begin(), c.options.end());
        auto r = limnRender(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Image img = readPng(dir / "f.png");
        const Silhouette s = silhouette(img);
        std::string what = c.input;
        for (const auto& o : c.options) what += " " + o;
        EXPECT_GE(fill(img, s), 0.80) << what;
        EXPECT_LE(fill(img, s), 0.90) << what;
        // Centred: the margins left and right (and above and below) differ by a few pixels.
        const double side = std::min(img.width, img.height);
        EXPECT_LE(std::abs(double(s.x0) - double(img.width - 1 - s.x1)), 0.04 * side) << what;
        EXPECT_LE(std::abs(double(s.y0) - double(img.height - 1 - s.y1)), 0.04 * side) << what;
    }
}

// A round object is framed alike from every azimuth: same fill within 2% of the side.
TEST(Framing, SameAcrossAzimuthsForARoundModel) {
    ScratchDir dir;
    auto r = run({bin("limn-examples"), "--only", "quad_sphere", "-o", dir.path().string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string sphere = prepare(dir, (dir / "quad_sphere.obj").string(), "sphere", 3);
    double lo = 1, hi = 0;
    for (const char* view : {"0,20", "45,20", "90,20", "135,20", "200,20", "290,-10"}) {
        r = limnRender({sphere, "--view", view, "--size", "160x120", "--background", kKey, "-o",
                    (dir / "s.png").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Image img = readPng(dir / "s.png");
        const double f = fill(img, silhouette(img));
        lo = std::min(lo, f), hi = std::max(hi, f);
        EXPECT_GE(f, 0.80) << view;
        EXPECT_LE(f, 0.90) << view;
    }
    EXPECT_LE(hi - lo, 0.02);
}

// ---- up axis ------------------------------------------------------------------------------

namespace {

// The OBJ with every vertex turned from Z up to Y up: (x, y, z) -> (x, z, -y), done on the text
// (reordering and negating decimal strings is exact).
std::string turnedToYUp(const std::string& obj) {
    std::istringstream in(obj);
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) {
            std::istringstream v(line.substr(2));
            std::string x, y, z;
            v >> x >> y >> z;
            const std::string minusY = y[0] == '-' ? y.substr(1) : "-" + y;
            out << "v " << x << " " << z << " " << minusY << "\n";
        } else {
            out << line << "\n";
        }
    }
    return out.str();
}

} // namespace

// The Z-up car seen with --up-axis z is the car turned to Y up seen with --up-axis y: the same
// view, framing and sky light. Not bit-identical (the turned coordinates are summed in another
// order in the projection), so: at most 0.5% of the pixels off by more than 8.
TEST(UpAxis, ZUpCarMatchesTheCarTurnedToYUp) {
    ScratchDir dir;
    const std::string obj = readFile(modelPath("osd/catmark/catmark_car.obj"));
    writeFile(dir / "car_y.obj", turnedToYUp(obj));
    const std::string carZ = prepare(dir, modelPath("osd/catmark/catmark_car.obj").string(), "car_z", 1);
    const std::string carY = prepare(dir, (dir / "car_y.obj").string(), "car_y", 1);
    for (const char* view : {"-30,20", "120,35"}) {
        auto r = limnRender({carZ, "--up-axis", "z", "--view", view, "--size", "160x120", "-o",
                         (dir / "z.png").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = limnRender({carY, "--up-axis", "y", "--view", view, "--size", "160x120", "-o",
                    (dir / "y.png").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = limnRender({carZ, "--up-axis", "y", "--view", view, "--size", "160x120", "-o",
                    (dir / "wrong.png").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto z = readPng(dir / "z.png"), y = readPng(dir / "y.png");
        EXPECT_LE(differing(z, y, 8), 0.005) << view;
        // And the axis matters: the Z-up car taken as Y-up is another picture.
        EXPECT_GT(differing(z, readPng(dir / "wrong.png"), 8), 0.05) << view;
    }
}

// ---- the lit rig's options ------------------------------------------------------------------

TEST(LitRig, OptionErrorsAreUsageErrors) {
    ScratchDir dir;
    const std::string cube = prepare(dir, modelPath("quad/osd_catmark_cube.obj").string(), "c", -1);
    for (std::vector<std::string> bad : {std::vector<std::string>{"--light", "30"},
                                         {"--light", "a,b"},
                                         {"--light", "30,91"},
                                         {"--light", "400,10"},
                                         {"--light", "30,10,5"},
                                         {"--color", "0.5,0.5"},
                                         {"--color", "1,2,0"},
                                         {"--color", "-0.1,0,0"},
                                         {"--color", "nan,0,0"},
                                         {"--up-axis", "x"}}) {
        bad.insert(bad.begin(), cube);
        bad.insert(bad.end(), {"-o", (dir / "x.png").string()});
        auto r = limnRender(bad);
        EXPECT_EQ(r.exitCode, 2) << bad[1] << " " << bad[2] << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    }
}

// Same bytes twice; --light moves the shading, --color tints it.
TEST(LitRig, DeterministicAndControlledByTheOptions) {
    ScratchDir dir;
    const std::string spot = prepare(dir, modelPath("quad/spot_control_mesh.obj").string(), "spot", 2);
    auto png = [&](const std::string& name, std::vector<std::string> options) {
        options.insert(options.begin(), spot);
        options.insert(options.end(), {"--size", "128x96", "-o", (dir / name).string()});
        auto r = limnRender(options);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readBytes(dir / name);
    };
    const auto a = png("a.png", {"--light", "30,10", "--color", "0.9,0.5,0.2"});
    const auto b = png("b.png", {"--light", "30,10", "--color", "0.9,0.5,0.2"});
    EXPECT_EQ(a, b);
    const auto plain = png("p.png", {});
    const auto lit = png("l.png", {"--light", "60,-20"});
    EXPECT_NE(plain, lit);
    // --color 0.9,0.5,0.2: every covered pixel reddish (R > G > B); the default is grey.
    const Image tinted = decodePng(a), grey = decodePng(plain);
    const uint8_t* bg = grey.at(0, 0);
    size_t covered = 0, ordered = 0, neutral = 0;
    for (uint32_t y = 0; y < grey.height; ++y)
        for (uint32_t x = 0; x < grey.width; ++x) {
            const uint8_t* g = grey.at(x, y);
            if (std::memcmp(g, bg, 3) == 0) continue;
            ++covered;
            const uint8_t* t = tinted.at(x, y);
            ordered += t[0] > t[1] && t[1] > t[2];
            neutral += std::abs(g[0] - g[1]) <= 3 && std::abs(g[1] - g[2]) <= 6;
        }
    ASSERT_GT(covered, 1000u);
    EXPECT_GE(ordered, covered * 95 / 100);
    EXPECT_GE(neutral, covered * 95 / 100);
}

// ---- glTF materials -------------------------------------------------------------------------
