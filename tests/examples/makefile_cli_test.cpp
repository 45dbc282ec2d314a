// Makefile.examples: which images it promises for which examples, that a build makes every one of
// them as a PNG of the requested size, that a second run does nothing, and that a changed input
// rebuilds exactly what depends on it. The build runs on a subset of the examples at a tiny image
// size (every tool start costs more than the pixels; under ASan about three times more).
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

using namespace limn;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kExamples = {"cube",           "quad_sphere",  "torus",
                                            "pentagon_tower", "creased_cube", "grid_with_hole"};

// The images the Makefile promises for an example, by its properties (the header of
// Makefile.examples): every example gets the subdivision and blending images; the closed meshes
// with UVs get displacement; those whose UV seams do not wrap get the crack demo; all but the one
// with semi-sharp creases (which limn-loop refuses) get the Loop runs.
std::vector<std::string> expectedImages(const std::string& name) {
    std::vector<std::string> images = {"adaptive", "uniform", "levels", "wire", "blend",
                                       "blend-trim"};
    const std::set<std::string> closedWithUvs = {"cube", "quad_sphere", "torus"};
    if (closedWithUvs.count(name)) images.insert(images.end(), {"displaced", "displaced-nofix"});
    if (name == "cube" || name == "quad_sphere")
        images.insert(images.end(), {"cracks-nofix", "cracks-fixed"});
    if (name != "creased_cube")
        images.insert(images.end(), {"loop-uniform", "loop-3e-3", "loop-1e-3"});
    return images;
}

// The animation stage: every frame of the twist animation, and 8 turntable views of the torus.
std::set<std::string> animationPaths(const fs::path& out, bool torus) {
    std::set<std::string> paths;
    char name[64];
    for (int k = 0; k < 24; ++k) {
        std::snprintf(name, sizeof name, "twist/twist_%04d.png", k);
        paths.insert((out / name).string());
    }
    for (int k = 0; torus && k < 8; ++k) {
        std::snprintf(name, sizeof name, "torus.turntable/%02d.png", k);
        paths.insert((out / name).string());
    }
    return paths;
}

std::set<std::string> expectedPaths(const fs::path& out, const std::vector<std::string>& names) {
    std::set<std::string> paths;
    for (const auto& name : names)
        for (const auto& image : expectedImages(name))
            paths.insert((out / (name + "." + image + ".png")).string());
    const auto animation = animationPaths(out, std::find(names.begin(), names.end(), "torus") != names.end());
    paths.insert(animation.begin(), animation.end());
    return paths;
}

std::set<std::string> lines(const std::string& text) {
    std::set<std::string> result;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) result.insert(line);
    return result;
}

test::RunResult make(const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {"/usr/bin/make",
                                     "-s",
                                     "-f",
                                     std::string(LIMN_SOURCE_DIR) + "/Makefile.examples",
                                     "BIN=" + test::binDir().string(),
                                     "OUT=" + out.string(),
                                     "SIZE=64x48",
                                     "MAP_SIZE=64",
                                     "TRIM_TILE=16"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return test::run(argv);
}

// Width and height from a PNG's signature and IHDR chunk (PNG spec, 5.2 and 11.2.2); {0, 0} when
// the file is not a PNG.
std::pair<uint32_t, uint32_t> pngSize(const fs::path& path) {
    const auto bytes = test::readBytes(path);
    static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 24 || !std::equal(kSignature, kSignature + 8, bytes.begin()) ||
        std::string(bytes.begin() + 12, bytes.begin() + 16) != "IHDR")
        return {0, 0};
    auto be32 = [&](size_t at) {
        return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
               uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
    };
    return {be32(16), be32(20)};
}

using Times = std::map<std::string, fs::file_time_type>;

Times writeTimes(const fs::path& dir) {
    Times times;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) times[entry.path().string()] = entry.last_write_time();
    return times;
}

// Marks `file` as changed: newer than every file under `dir`, yet not in the future, so the
// outputs remade from it are newer still.
void touchAfterEverything(const fs::path& dir, const fs::path& file) {
    auto newest = fs::file_time_type::min();
    for (const auto& [path, time] : writeTimes(dir)) newest = std::max(newest, time);
    fs::last_write_time(file, newest + std::chrono::milliseconds(1));
}

// The files under `dir` written since `before` (new or with another write time), as names
// relative to `dir`.
std::set<std::string> rewritten(const fs::path& dir, const Times& before) {
    std::set<std::string> result;
    for (const auto& [path, time] : writeTimes(dir)) {
        auto it = before.find(path);
        if (it == before.end() || it->second != time)
            result.insert(fs::relative(path, dir).string());
    }
    return result;
}

TEST(MakefileExamples, ListsTheImagesOfEveryStage) {
    test::ScratchDir dir;
    const auto out = dir / "out";
    auto list = make(out, {"list"});
    ASSERT_EQ(list.exitCode, 0) << list.err;
    EXPECT_EQ(lines(list.out), expectedPaths(out, kExamples));
    EXPECT_EQ(list.out.size(), [&] {
        size_t n = 0;
        for (const auto& p : expectedPaths(out, kExamples)) n += p.size() + 1;
        return n;
    }()) << "an image listed twice";
    EXPECT_FALSE(fs::exists(out)) << "list builds nothing";

    // Stages and examples select subsets; unknown ones are refused by name.
    auto loop = make(out, {"list", "STAGES=loop", "EXAMPLES=torus creased_cube"});
    ASSERT_EQ(loop.exitCode, 0) << loop.err;
    EXPECT_EQ(lines(loop.out), (std::set<std::string>{(out / "torus.loop-uniform.png").string(),
                                                      (out / "torus.loop-3e-3.png").string(),
                                                      (out / "torus.loop-1e-3.png").string()}));
    auto badStage = make(out, {"list", "STAGES=info loops"});
    EXPECT_NE(badStage.exitCode, 0);
    EXPECT_NE(badStage.err.find("unknown STAGES: loops"), std::string::npos) << badStage.err;
    auto badExample = make(out, {"list", "EXAMPLES=cube sphere"});
    EXPECT_NE(badExample.exitCode, 0);
    EXPECT_NE(badExample.err.find("unknown EXAMPLES: sphere"), std::string::npos)
        << badExample.err;
}

TEST(MakefileExamples, BuildsOnceThenNothing) {
    test::ScratchDir dir;
    const auto out = dir / "out";
    // Two examples cover every rule: the cube every stage including the crack demo, the torus
    // (all regular, UVs that wrap) displacement without it.
    const std::vector<std::string> names = {"cube", "torus"};
    const std::string subset = "EXAMPLES=cube torus";
    auto first = make(out, {subset, "-j2"});
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_TRUE(first.err.empty()) << first.err;

    for (const auto& name : names) {
        SCOPED_TRACE(name);
        const auto limn = out / (name + ".limn"), obj = out / "meshes" / (name + ".obj");
        // The summary is printed, and the container is what limn-classify makes of the mesh.
        EXPECT_NE(first.out.find(limn.string() + "\n  vertices"), std::string::npos);
        auto direct = test::run({test::tool("limn-classify").string(), "-q", obj.string()});
        ASSERT_EQ(direct.exitCode, 0) << direct.err;
        EXPECT_EQ(test::readFile(limn), direct.out);
        EXPECT_EQ(test::readFile(out / (name + ".limn.d")),
                  limn.string() + ": " + obj.string() + "\n");
    }
    // Every promised image is there, a PNG of the requested size; the maps have theirs.
    for (const auto& path : expectedPaths(out, names)) {
        SCOPED_TRACE(path);
        EXPECT_EQ(pngSize(path), std::make_pair(64u, 48u));
    }
    EXPECT_EQ(pngSize(out / "uv-noise.png"), std::make_pair(64u, 64u));
    EXPECT_EQ(pngSize(out / "torus.height.png"), std::make_pair(64u, 64u));
    // The cube's atlas: 6 faces, 3 tiles to a row, 16 texels a tile.
    EXPECT_EQ(pngSize(out / "cube.trim.png"), std::make_pair(48u, 32u));
    // The web stage: the viewer, the runtime and a container per example, linked from the index.
    for (const auto* file : {"index.html", "viewer/index.html", "viewer/viewer.mjs", "src/index.mjs",
                             "shaders/surface_vert.wgsl"})
        EXPECT_TRUE(fs::is_regular_file(out / "web" / file)) << file;
    for (const auto& name : names) {
        EXPECT_EQ(test::readFile(out / "web" / "models" / (name + ".limn")),
                  test::readFile(out / (name + ".d3.limn")));
        EXPECT_NE(test::readFile(out / "web" / "index.html")
                      .find("viewer/?model=../models/" + name + ".limn&amp;view=-30,20"),
                  std::string::npos);
        // Displaced: the container with seams and the height map, linked with the scale and mid.
        for (const auto* suffix : {".seams.limn", ".height.png"})
            EXPECT_EQ(test::readFile(out / "web" / "models" / (name + suffix)), test::readFile(out / (name + suffix)));
        EXPECT_NE(test::readFile(out / "web" / "index.html")
                      .find("viewer/?model=../models/" + name + ".seams.limn&amp;view=-30,20&amp;displace=../models/" +
                            name + ".height.png&amp;displaceScale=0.2&amp;displaceMid=0.5\""),
                  std::string::npos);
    }
    EXPECT_EQ(test::readFile(out / "web" / "models" / "uv-noise.png"), test::readFile(out / "uv-noise.png"));
    // A depfile names the inputs a render read, the height map included.
    EXPECT_EQ(test::readFile(out / "torus.displaced.png.d"),
              (out / "torus.displaced.png").string() + ": " + (out / "torus.seams.limn").string() +
                  " " + (out / "torus.height.png").string() + "\n");

    // Up to date: make -q agrees and a second run prints and rebuilds nothing.
    EXPECT_EQ(make(out, {subset, "-q"}).exitCode, 0);
    auto before = writeTimes(out);
    auto second = make(out, {subset, "-j2"});
    EXPECT_EQ(second.exitCode, 0) << second.err;
    EXPECT_EQ(second.out, "");
    EXPECT_EQ(second.err, "");
    EXPECT_EQ(rewritten(out, before), std::set<std::string>{});

    // A changed map re-renders just the images displaced by it (and the viewer's copy).
    touchAfterEverything(out, out / "uv-noise.png");
    EXPECT_EQ(make(out, {subset, "-q"}).exitCode, 1);
    before = writeTimes(out);
    auto third = make(out, {subset, "-j2"});
    ASSERT_EQ(third.exitCode, 0) << third.err;
    EXPECT_EQ(third.out, "");
    EXPECT_EQ(rewritten(out, before),
              (std::set<std::string>{"cube.cracks-nofix.png", "cube.cracks-nofix.png.d",
                                     "cube.cracks-fixed.png", "cube.cracks-fixed.png.d",
                                     "web/models/uv-noise.png"}));

    // A changed mesh rebuilds everything made from it, and nothing else.
    touchAfterEverything(out, out / "meshes" / "torus.obj");
    EXPECT_EQ(make(out, {subset, "-q"}).exitCode, 1);
    before = writeTimes(out);
    auto fourth = make(out, {subset, "-j2"});
    ASSERT_EQ(fourth.exitCode, 0) << fourth.err;
    EXPECT_EQ(fourth.out.rfind((out / "torus.limn").string() + "\n", 0), 0u) << fourth.out;
    std::set<std::string> torusFiles;
    for (const auto& [path, time] : before) {
        auto rel = fs::relative(path, out).string();
        if (rel.rfind("torus.", 0) == 0) torusFiles.insert(rel);
    }
    EXPECT_GT(torusFiles.size(), 30u);
    // The web stage's copies for the viewer.
    for (const auto* copy : {"web/models/torus.limn", "web/models/torus.seams.limn", "web/models/torus.height.png"})
        torusFiles.insert(copy);
    EXPECT_EQ(rewritten(out, before), torusFiles);
    EXPECT_EQ(make(out, {subset, "-q"}).exitCode, 0);
}

TEST(MakefileExamples, MissingToolsSayWhatToDo) {
    test::ScratchDir dir;
    auto r =
        test::run({"/usr/bin/make", "-s", "-f", std::string(LIMN_SOURCE_DIR) + "/Makefile.examples",
                   "BIN=" + (dir / "nowhere").string(), "OUT=" + (dir / "out").string()});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("build limn first"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

} // namespace

// The animation stage renders every frame in one limn-render run and the turntable in another,
// and is incremental like the rest: a changed frame mesh re-renders the frames, not the turntable.
TEST(MakefileExamples, AnimationFramesInOneRunAndIncremental) {
    test::ScratchDir dir;
    const auto out = dir / "out";
    const std::vector<std::string> subset = {"STAGES=animation", "EXAMPLES=torus"};
    auto first = make(out, {subset[0], subset[1], "-j2"});
    ASSERT_EQ(first.exitCode, 0) << first.err;
    for (const auto& p : animationPaths(out, true)) EXPECT_EQ(pngSize(p), (std::pair<uint32_t, uint32_t>{64, 48})) << p;
    EXPECT_EQ(make(out, {subset[0], subset[1], "-q"}).exitCode, 0) << "up to date";
    const Times before = writeTimes(out);
    touchAfterEverything(out, out / "meshes" / "twist" / "twist_0005.obj");
    auto second = make(out, {subset[0], subset[1], "-j2"});
    ASSERT_EQ(second.exitCode, 0) << second.err;
    const auto changed = rewritten(out, before);
    EXPECT_TRUE(changed.count("twist/twist_0000.png")) << "the frames are one run";
    EXPECT_TRUE(changed.count("twist/twist_0023.png"));
    EXPECT_FALSE(changed.count("torus.turntable/00.png"));
}
