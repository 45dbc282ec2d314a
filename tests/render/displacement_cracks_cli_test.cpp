// The seam fix closes every crack (paper 000, 4.5): with it the drawn triangles, welded
// by exact position, close up for closed inputs at depths 1-4, adaptive and uniform, with a map
// continuous across seams and one that is not; without it they open (so the check can fail).
// And as a viewer sees it: key-coloured background and back faces inside the silhouette over 16
// views. Many renders: labelled "heavy", run in the release suite only (scripts/test.sh).
#include "displacement_support.h"

#include <OpenImageIO/imageio.h>

#include <array>
#include <iostream>

using namespace limn;
using namespace limn::test;
using namespace limn::test::displacement;

namespace {

// ---------------------------------------------------------------------------------------------
// Watertight with the seam fix, cracked without it: every depth 1-4, adaptive and uniform.

struct WatertightCase {
    Model model;
    std::string kind; // limn-heightmap --kind
};
void PrintTo(const WatertightCase& c, std::ostream* os) {
    *os << c.model.name << " " << c.kind;
}

class DisplacedWatertight : public ::testing::TestWithParam<WatertightCase> {};

TEST_P(DisplacedWatertight, ClosedWithSeamFixOpenWithout) {
    const WatertightCase& c = GetParam();
    ScratchDir dir;
    const std::string obj = modelFile(c.model, dir);
    const double scale = 0.05 * diagonalOf(obj);
    std::string map;
    for (int depth = 1; depth <= 4; ++depth)
        for (bool uniform : {false, true}) {
            SCOPED_TRACE("depth " + std::to_string(depth) + (uniform ? " uniform" : " adaptive"));
            const std::string limn = prepare(obj, depth, uniform, dir, "in");
            if (map.empty()) map = heightmap(limn, c.kind, dir);
            const std::vector<std::string> displace = {"--displace",       map,
                                                       "--displace-scale", std::to_string(scale),
                                                       "--displace-mid",   "0.5"};

            WeldedEdges fixed = weldedEdges(drawn(limn, displace, dir));
            EXPECT_EQ(fixed.open, 0u) << "open edges with the seam fix";
            EXPECT_EQ(fixed.over, 0u);
            EXPECT_EQ(fixed.collapsed, 0u);

            auto noFix = displace;
            noFix.push_back("--no-seam-fix");
            WeldedEdges broken = weldedEdges(drawn(limn, noFix, dir));
            EXPECT_GT(broken.open, 0u) << "--no-seam-fix should open the UV seams";
        }
}

const WatertightCase kWatertight[] = {
    {{"spot", "quad/spot_control_mesh.obj"}, "surface"},
    {{"spot", "quad/spot_control_mesh.obj"}, "uv"},
    {{"islands", ""}, "surface"},
    {{"islands", ""}, "uv"},
    {{"lefthanded", "quad/osd_catmark_lefthanded.obj"}, "surface"},
    {{"lefthanded", "quad/osd_catmark_lefthanded.obj"}, "uv"},
};

std::string watertightName(const ::testing::TestParamInfo<WatertightCase>& p) {
    return p.param.model.name + "_" + p.param.kind;
}

INSTANTIATE_TEST_SUITE_P(Models, DisplacedWatertight, ::testing::ValuesIn(kWatertight),
                         watertightName);

// ---------------------------------------------------------------------------------------------
// Cracks as a viewer sees them: culling is off, the background is magenta and faces seen from
// behind are green, so a crack in the closed surface shows either colour inside the silhouette.

struct Pixels {
    int width = 0, height = 0;
    std::vector<std::array<uint8_t, 3>> rgb;
};

Pixels readPng(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    Pixels p;
    p.width = in->spec().width;
    p.height = in->spec().height;
    if (in->spec().nchannels != 3) throw std::runtime_error("expected RGB");
    p.rgb.resize(size_t(p.width) * p.height);
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, p.rgb.data()))
        throw std::runtime_error("cannot read " + path);
    return p;
}

// Magenta pixels that the outside background cannot reach (flood fill from the border through
// magenta): background seen through a crack; and green pixels: a back face seen through a crack.
// Green pixels touching the outside background are left out: where a front face and the back face
// behind it meet at a silhouette edge their depths are equal at grazing angles and the back one can
// win the depth test (this shows on the undisplaced surface too), which is no crack.
size_t crackPixels(const Pixels& img) {
    const std::array<uint8_t, 3> key = {255, 0, 255}, back = {0, 255, 0};
    const int W = img.width, H = img.height;
    std::vector<uint8_t> outside(img.rgb.size(), 0);
    std::vector<size_t> stack;
    auto push = [&](int x, int y) {
        size_t i = size_t(y) * W + x;
        if (img.rgb[i] == key && !outside[i]) outside[i] = 1, stack.push_back(i);
    };
    for (int x = 0; x < W; ++x) push(x, 0), push(x, H - 1);
    for (int y = 0; y < H; ++y) push(0, y), push(W - 1, y);
    while (!stack.empty()) {
        size_t i = stack.back();
        stack.pop_back();
        int x = int(i % W), y = int(i / W);
        if (x > 0) push(x - 1, y);
        if (x + 1 < W) push(x + 1, y);
        if (y > 0) push(x, y - 1);
        if (y + 1 < H) push(x, y + 1);
    }
    auto onSilhouette = [&](int x, int y) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int nx = x + dx, ny = y + dy;
                if (nx >= 0 && ny >= 0 && nx < W && ny < H && outside[size_t(ny) * W + nx])
                    return true;
            }
        return false;
    };
    size_t n = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + x;
            n += (img.rgb[i] == key && !outside[i]) || (img.rgb[i] == back && !onSilhouette(x, y));
        }
    return n;
}

TEST(Displacement, NoCrackPixelsInSixteenViews) {
    ScratchDir dir;
    const std::string obj = modelPath("quad/spot_control_mesh.obj").string();
    const std::string limn = prepare(obj, 3, false, dir, "spot");
    const std::string map = heightmap(limn, "uv", dir); // the stress case: unrelated across seams
    // 3% of the diagonal: at 4% the noise folds the surface over itself in places, and a fold
    // shows a back face without any gap (found when the framing grew to 85% of the frame: one
    // pixel at view 0,-20 whose welded --mesh-out is closed). A crack test must not count folds.
    const std::string scale = std::to_string(0.03 * diagonalOf(obj));
    size_t withFix = 0, withoutFix = 0;
    // The sixteen views as two turntables of eight (a turntable's frame k is the single render
    // of its view, Turntable.EveryFrameIsTheSingleRenderOfItsView): azimuths 0, 45, ... at
    // elevation -20 and 22.5, 67.5, ... at 35, in four processes instead of thirty-two.
    for (int ring = 0; ring < 2; ++ring) {
        const std::string view = ring ? "22.5,35" : "0,-20";
        for (bool fix : {true, false}) {
            const std::string frames = (dir / (std::string(fix ? "fix" : "nofix") + "_%d.png")).string();
            std::vector<std::string> argv = {bin("limn-render"), limn, "--validate", "-o", frames};
            for (const std::string& a : std::vector<std::string>{
                     "--size=200x150", "--view=" + view, "--turntable=8", "--displace=" + map,
                     "--displace-scale=" + scale, "--displace-mid=0.5", "--background=1,0,1",
                     "--back-faces=0,1,0",
                     // One sample per pixel: a crack pixel is exactly the key colour, not a
                     // blend of it with the surface around (MSAA, the default, would blend).
                     "--samples=1"})
                argv.push_back(a);
            if (!fix) argv.push_back("--no-seam-fix");
            runOk(argv);
            for (int k = 0; k < 8; ++k) {
                const auto png = dir / (std::string(fix ? "fix" : "nofix") + "_" + std::to_string(k) + ".png");
                size_t n = crackPixels(readPng(png.string()));
                (fix ? withFix : withoutFix) += n;
                if (fix) {
                    EXPECT_EQ(n, 0u) << "view " << view << ", turntable frame " << k;
                }
            }
        }
    }
    // The figure for the issue note; gtest keeps it in the XML report too.
    std::cout << "crack pixels over 16 views at 200x150: " << withFix << " with the seam fix, "
              << withoutFix << " without\n";
    RecordProperty("crack_pixels_without_fix", int(withoutFix));
    EXPECT_EQ(withFix, 0u);
    EXPECT_GT(withoutFix, 0u) << "the stress map should crack the surface without the fix";
}

} // namespace
