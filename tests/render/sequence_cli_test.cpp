// Sequences in one run: limn-render --turntable, --cameras and --frames as users run
// them. Every frame must be the same bytes as a single render with that frame's camera and mesh
// (the renderer keeps its tables and buffers; only the camera or the control points change), and
// bad sequences fail before writing, or leave nothing behind.
#include "test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>

using namespace limn::test;

namespace {

std::string bin(const std::string& name) { return tool(name).string(); }

// The built-in twisting torus, its frames in dir/twist/, and tables of depth 2 made from frame 0.
struct Twist {
    ScratchDir dir;
    std::string limn;
    Twist() {
        auto r = run({bin("limn-examples"), "-o", dir.path().string(), "--only", "twist"});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        limn = (dir / "twist.limn").string();
        r = run({bin("limn-tables"), (dir / "twist" / "twist_0000.obj").string(), "--depth", "2", "-q", "-o", limn});
        EXPECT_EQ(r.exitCode, 0) << r.err;
    }
    std::string frame(int k) const {
        char name[32];
        std::snprintf(name, sizeof name, "twist_%04d.obj", k);
        return (dir / "twist" / name).string();
    }
};

std::vector<std::string> files(const std::filesystem::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

const std::vector<std::string> kSmall = {"--size", "96x72", "--validate"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

} // namespace

TEST(Turntable, EveryFrameIsTheSingleRenderOfItsView) {
    Twist t;
    ScratchDir out;
    auto r = run(with({bin("limn-render"), t.limn, "--turntable", "4", "--view", "10,25", "-o",
                       (out / "spin_%02d.png").string()}, kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(files(out.path()), (std::vector<std::string>{"spin_00.png", "spin_01.png", "spin_02.png", "spin_03.png"}));
    const char* azimuths[] = {"10", "100", "190", "280"};
    for (int k = 0; k < 4; ++k) {
        const auto single = out / ("single_" + std::to_string(k) + ".png");
        r = run(with({bin("limn-render"), t.limn, "--view", std::string(azimuths[k]) + ",25", "-o", single.string()},
                     kSmall));
        ASSERT_EQ(r.exitCode, 0) << r.err;
        char name[32];
        std::snprintf(name, sizeof name, "spin_%02d.png", k);
        EXPECT_EQ(readBytes(single), readBytes(out / name)) << "frame " << k;
    }
    // The views differ (the object turns), and the same command gives the same bytes.
    EXPECT_NE(readBytes(out / "spin_00.png"), readBytes(out / "spin_01.png"));
    ScratchDir again;
    r = run(with({bin("limn-render"), t.limn, "--turntable", "4", "--view", "10,25", "-o",
                  (again / "spin_%02d.png").string()}, kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const auto& name : files(again.path())) EXPECT_EQ(readBytes(again / name), readBytes(out / name)) << name;
}

TEST(Frames, EveryFrameIsTheSingleRenderOfItsMeshWithTheSameTables) {
    Twist t;
    ScratchDir out;
    const std::vector<std::string> camera = {"--eye", "2,3,4", "--target", "0,0,0"};
    for (const char* edgePixels : {"4", "0"}) {
        const std::string tag = std::string("ep") + edgePixels + "_";
        auto r = run(with(with({bin("limn-render"), t.limn, "--frames", (t.dir / "twist" / "twist_%04d.obj").string(),
                                "--edge-pixels", edgePixels, "-o", (out / (tag + "%04d.png")).string(),
                                "--depfile", (out / (tag + "frames.d")).string()},
                               kSmall),
                          camera));
        ASSERT_EQ(r.exitCode, 0) << r.err;
        // Frames 0, 7 and 23 against a single render of that frame's mesh through the whole
        // pipeline (its own classification and tables: the same, since they are topology only).
        for (int k : {0, 7, 23}) {
            const std::string limn = (out / ("single" + std::to_string(k) + ".limn")).string();
            r = run({bin("limn-tables"), t.frame(k), "--depth", "2", "-q", "-o", limn});
            ASSERT_EQ(r.exitCode, 0) << r.err;
            const auto single = out / (tag + "single" + std::to_string(k) + ".png");
            r = run(with(with({bin("limn-render"), limn, "--edge-pixels", edgePixels, "-o", single.string()}, kSmall),
                         camera));
            ASSERT_EQ(r.exitCode, 0) << r.err;
            char name[32];
            std::snprintf(name, sizeof name, "%04d.png", k);
            EXPECT_EQ(readBytes(single), readBytes(out / (tag + name))) << "frame " << k << ", --edge-pixels " << edgePixels;
        }
        // The depfile names every frame and every frame mesh.
        const std::string dep = readFile(out / (tag + "frames.d"));
        EXPECT_NE(dep.find(tag + "0023.png"), std::string::npos) << dep;
        EXPECT_NE(dep.find("twist_0023.obj"), std::string::npos) << dep;
        EXPECT_EQ(dep.find("twist_0023.obj"), dep.rfind("twist_0023.obj")) << "named twice: " << dep;
    }
}

// The GPU surface (tables, tessellation buffers, pipelines) is set up once for the whole run;
// each frame only brings its control points (limn-render -v says when it does either).
TEST(Frames, SetUpOnceNewControlPointsPerFrame) {
    Twist t;
    ScratchDir out;
    auto r = run(with({bin("limn-render"), t.limn, "-v", "--frames", (t.dir / "twist" / "twist_%04d.obj").string(),
                       "-o", (out / "f%d.png").string()},
                      kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto count = [&](const std::string& words) {
        size_t n = 0;
        for (size_t at = r.err.find(words); at != std::string::npos; at = r.err.find(words, at + 1)) ++n;
        return n;
    };
    EXPECT_EQ(count("set up the GPU surface"), 1u) << r.err;
    EXPECT_EQ(count("new control points from"), 24u) << r.err;
    EXPECT_EQ(count("twist_0013.obj"), 1u) << r.err;
}

TEST(Frames, DefaultFramingHoldsEveryFrame) {
    Twist t;
    ScratchDir out;
    auto r = run(with({bin("limn-render"), t.limn, "--frames", (t.dir / "twist" / "twist_%04d.obj").string(), "-o",
                       (out / "f%d.png").string(), "--background", "0,0,0"},
                      kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(files(out.path()).size(), 24u);
}

TEST(Cameras, EveryLineIsTheSingleRenderOfThatCamera) {
    Twist t;
    ScratchDir out;
    const auto cams = out / "cams.txt";
    std::ofstream(cams) << "# eye target up fov\n0 0 4  0 0 0  0 1 0\n3,1,2, 0,0.2,0, 0,0,1, 50\n";
    auto r = run(with({bin("limn-render"), t.limn, "--cameras", cams.string(), "-o", (out / "cam_%d.png").string()},
                      kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<std::vector<std::string>> singles = {
        {"--eye", "0,0,4", "--target", "0,0,0", "--up", "0,1,0"},
        {"--eye", "3,1,2", "--target", "0,0.2,0", "--up", "0,0,1", "--fov", "50"}};
    for (size_t k = 0; k < singles.size(); ++k) {
        const auto single = out / ("single" + std::to_string(k) + ".png");
        r = run(with(with({bin("limn-render"), t.limn, "-o", single.string()}, kSmall), singles[k]));
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(readBytes(single), readBytes(out / ("cam_" + std::to_string(k) + ".png"))) << k;
    }
}

TEST(SequenceErrors, RefusedBeforeAnyFileIsWritten) {
    Twist t;
    ScratchDir out;
    const std::string o = (out / "x_%04d.png").string(), frames = (t.dir / "twist" / "twist_%04d.obj").string();
    const auto cams = out / "bad.txt";
    std::ofstream(cams) << "0 0 4 0 0 0 0 1 0\n0 0 4 0 0 0 0 1\n";
    const struct {
        std::vector<std::string> args;
        int exit;
        const char* words;
    } cases[] = {
        {{"--turntable", "4", "-o", (out / "plain.png").string()}, 2, "needs one frame number"},
        {{"--turntable", "4", "-o", "-"}, 2, "one image per frame"},
        {{"--turntable", "0", "-o", o}, 2, "--turntable"},
        {{"--turntable", "4x", "-o", o}, 2, "--turntable"},
        {{"-o", o}, 2, "numbers frames"},
        {{"--turntable", "4", "--frames", frames, "-o", o}, 2, "exclude each other"},
        {{"--turntable", "4", "--eye", "1,2,3", "-o", o}, 2, "leave out --eye"},
        {{"--cameras", cams.string(), "--view", "10,10", "-o", o}, 2, "leave out --view"},
        {{"--turntable", "4", "--bench", "3", "-o", o}, 2, "--bench"},
        {{"--turntable", "4", "-o", (out / "x_%04d.jpg").string()}, 2, "unknown image extension"},
        {{"--turntable", "4", "-o", (out / "no" / "x_%d.png").string()}, 1, "no folder"},
        {{"--cameras", cams.string(), "-o", o}, 1, "line 2"},
        {{"--frames", (t.dir / "none_%04d.obj").string(), "-o", o}, 1, "no file matches"},
    };
    for (const auto& c : cases) {
        auto r = run(with(with({bin("limn-render"), t.limn}, c.args), kSmall));
        EXPECT_EQ(r.exitCode, c.exit) << r.err;
        EXPECT_NE(r.err.find(c.words), std::string::npos) << r.err;
        EXPECT_EQ(files(out.path()), (std::vector<std::string>{"bad.txt"})) << r.err;
    }
}

// A sequence is estimated before any work (images uncompressed, meshes at the least) and refused
// when it would write more than --max-output, or by default the free space where it goes.
TEST(SequenceErrors, AnOversizedSequenceIsRefusedAtOnce) {
    ScratchDir out;
    const std::string cube = modelPath("gltf/features/cube.gltf").string(), o = (out / "f_%06d.png").string();
    const struct {
        std::vector<std::string> args;
        const char* words;
        bool beforeInput; // refused before the input is read: at once
    } cases[] = {
        // 100000 x 96 x 72 x 3 bytes: 2.07 GB.
        {{"--turntable", "100000", "--size", "96x72", "--max-output", "1G"}, "more than --max-output", true},
        // 100000 x 16384^2 x 4 bytes: 107 TB, more than any disk this runs on.
        {{"--turntable", "100000", "--size", "16384x16384", "--alpha"}, "more than the free space in", true},
        // 1000 frames of 8 x 8 x 3 bytes (192 KB) fit in 300K (307,200 bytes); with the cube's 12
        // triangles at 24 bytes each per frame (480 KB) they do not.
        {{"--turntable", "1000", "--size", "8x8", "--max-output", "300K", "--mesh-out", (out / "m_%06d.ply").string()},
         "and meshes at least", false},
    };
    for (const auto& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        auto r = run(with({bin("limn-render"), cube, "-o", o}, c.args));
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find(c.words), std::string::npos) << r.err;
        EXPECT_TRUE(files(out.path()).empty()) << r.err;
        if (c.beforeInput) {
            EXPECT_LT(seconds, 1.0) << r.err;
        }
    }
    // A sequence whose estimate is exactly --max-output is rendered (2 x 96 x 72 x 3 bytes).
    auto r = run(with({bin("limn-render"), cube, "-o", o},
                      {"--turntable", "2", "--size", "96x72", "--max-output", "41472"}));
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(SequenceErrors, AFrameWithOtherFacesFailsAndLeavesNoFrames) {
    Twist t;
    ScratchDir out;
    // Frame 5 replaced by a cube: other faces, so the input's tables do not apply.
    auto r = run({bin("limn-examples"), "-o", out.path().string(), "--only", "cube"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::filesystem::copy_file(out / "cube.obj", t.frame(5), std::filesystem::copy_options::overwrite_existing);
    std::filesystem::remove(out / "cube.obj");
    r = run(with({bin("limn-render"), t.limn, "--frames", (t.dir / "twist" / "twist_%04d.obj").string(), "-o",
                  (out / "f_%04d.png").string()},
                 kSmall));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("twist_0005.obj"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("faces differ"), std::string::npos) << r.err;
    EXPECT_TRUE(files(out.path()).empty());
}

// --shard I/N and --frame-range: each part frames and views its frames as the whole sequence
// does, so the parts together write the one-process frames, byte for byte; a part's depfile
// names only the frames it wrote.
TEST(Shards, PartsWriteTheWholeRunsFramesAndTheirDepfilesNameThem) {
    Twist t;
    ScratchDir whole, parts;
    const std::string frames = (t.dir / "twist" / "twist_%04d.obj").string();
    struct Sequence {
        std::vector<std::string> args;
        int count;
    };
    // The default camera: --frames' framing is the box of every frame's control points, which a
    // part must take from the frames it does not render too.
    for (const Sequence& s : {Sequence{{"--turntable", "5", "--view", "10,25"}, 5}, Sequence{{"--frames", frames}, 24}}) {
        const std::string tag = s.args[0].substr(2) + "_";
        auto r = run(with(with({bin("limn-render"), t.limn, "-o", (whole / (tag + "%04d.png")).string()}, s.args),
                          kSmall));
        ASSERT_EQ(r.exitCode, 0) << r.err;
        for (int i = 0; i < 3; ++i) {
            const std::string shard = std::to_string(i) + "/3", dep = (parts / (tag + std::to_string(i) + ".d")).string();
            r = run(with(with({bin("limn-render"), t.limn, "--shard", shard, "-o", (parts / (tag + "%04d.png")).string(),
                               "--depfile", dep},
                              s.args),
                         kSmall));
            ASSERT_EQ(r.exitCode, 0) << shard << ": " << r.err;
            // Part i of 3 owns frames floor(i n / 3) .. floor((i + 1) n / 3) - 1.
            const std::string rule = readFile(dep);
            for (int k = 0; k < s.count; ++k) {
                char name[32];
                std::snprintf(name, sizeof name, "%04d.png", k);
                const bool mine = k >= i * s.count / 3 && k < (i + 1) * s.count / 3;
                EXPECT_EQ(rule.find(tag + name) != std::string::npos, mine) << shard << " frame " << k << ": " << rule;
            }
            if (s.args[0] == "--frames") {
                EXPECT_NE(rule.find("twist_0023.obj"), std::string::npos) << rule;
            }
        }
        for (int k = 0; k < s.count; ++k) {
            char name[32];
            std::snprintf(name, sizeof name, "%04d.png", k);
            ASSERT_TRUE(std::filesystem::exists(parts / (tag + name))) << tag << name;
            EXPECT_EQ(readBytes(parts / (tag + name)), readBytes(whole / (tag + name))) << tag << name;
        }
    }
    // --frame-range re-renders a few frames as the whole run did.
    ScratchDir range;
    auto r = run(with({bin("limn-render"), t.limn, "--frames", frames, "--frame-range", "7-9", "-o",
                       (range / "%04d.png").string()},
                      kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(files(range.path()), (std::vector<std::string>{"0007.png", "0008.png", "0009.png"}));
    for (const char* name : {"0007.png", "0008.png", "0009.png"})
        EXPECT_EQ(readBytes(range / name), readBytes(whole / (std::string("frames_") + name))) << name;
    // What the checks above rely on: a sequence of only the first frames is framed differently,
    // so a part framed by its own frames would not have matched.
    ScratchDir first;
    std::filesystem::create_directory(first / "in");
    for (int k = 0; k < 4; ++k)
        std::filesystem::copy_file(t.frame(k), first / "in" / std::filesystem::path(t.frame(k)).filename());
    r = run(with({bin("limn-render"), t.limn, "--frames", (first / "in" / "twist_%04d.obj").string(), "-o",
                  (first / "%04d.png").string()},
                 kSmall));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(readBytes(first / "0000.png"), readBytes(whole / "frames_0000.png"));
}

// Bad shards are usage errors before any work: the input (missing here) is not even read.
TEST(Shards, BadShardsAreUsageErrorsBeforeAnyWork) {
    Twist t;
    ScratchDir out;
    const std::string o = (out / "x_%04d.png").string(), missing = (out / "missing.limn").string();
    for (const char* bad : {"0/0", "5/4", "-1/2", "one/2", "1/two", "1/2/3", "1.5/2", ""}) {
        auto r = run(with({bin("limn-render"), missing, "--turntable", "4", "--shard", bad, "-o", o}, kSmall));
        EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
        EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
    }
    const struct {
        std::vector<std::string> args;
        const char* words;
    } cases[] = {
        {{"--shard", "0/2", "-o", (out / "x.png").string()}, "part of a sequence"},
        {{"--frame-range", "0-2", "-o", (out / "x.png").string()}, "part of a sequence"},
        {{"--turntable", "4", "--shard", "4/8", "-o", o}, "at most 4 parts"},
        {{"--turntable", "4", "--frame-range", "4-9", "-o", o}, "no frame of the sequence"},
        {{"--turntable", "4", "--frame-range", "3-1", "-o", o}, "--frame-range"},
    };
    for (const auto& c : cases) {
        auto r = run(with(with({bin("limn-render"), t.limn}, c.args), kSmall));
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find(c.words), std::string::npos) << r.err;
    }
    EXPECT_TRUE(files(out.path()).empty());
}
