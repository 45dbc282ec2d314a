// Messages that say what to do, and no silent fallbacks: errors about an
// option's file name the option; a container without tables and a --grid without a blending
// surface warn; new tables drop the seams made for the old ones; limn-info validates and flags
// stale chunks and prints the bounding box that --displace-scale P% refers to.
#include "container/container.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <cstdio>

using namespace limn;

namespace {

std::string bin(const std::string& tool) { return test::tool(tool).string(); }

// A unit cube with a UV per corner of each face (so limn-seams has something to do).
const std::string kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 4/2 3/3 2/4\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 2/1 3/2 7/3 6/4\n"
    "f 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n";

struct Files {
    test::ScratchDir dir;
    std::string obj, limn, d2, d3;
    Files() {
        obj = (dir / "cube.obj").string();
        limn = (dir / "cube.limn").string();
        d2 = (dir / "d2.limn").string();
        d3 = (dir / "d3.limn").string();
        test::writeFile(obj, kCubeObj);
        EXPECT_EQ(test::run({bin("limn-classify"), obj, "-o", limn}).exitCode, 0);
        EXPECT_EQ(test::run({bin("limn-tables"), limn, "-d", "2", "-o", d2}).exitCode, 0);
        EXPECT_EQ(test::run({bin("limn-tables"), limn, "-d", "3", "-o", d3}).exitCode, 0);
    }
};

TEST(Messages, AMissingMapNamesItsOption) {
    Files f;
    auto r = test::run({bin("limn-render"), f.d2, "--texture", (f.dir / "nosuch.png").string(),
                        "-o", (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("nosuch.png: --texture: cannot open"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("give --texture an existing image file"), std::string::npos) << r.err;
}

TEST(Messages, SurfaceControlWithSubdivisionOptionsSaysWhy) {
    Files f;
    ASSERT_EQ(test::run({bin("limn-heightmap"), "--kind", "uv", "--size", "16", "-o",
                         (f.dir / "t.png").string()})
                  .exitCode,
              0);
    auto r = test::run({bin("limn-render"), f.d2, "--displace", (f.dir / "t.png").string(),
                        "--surface", "control", "-o", (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(r.err.find("run limn-tables first"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("leave out --surface control"), std::string::npos) << r.err;
}

TEST(Messages, NoSilentFallbacks) {
    Files f;
    auto r = test::run({bin("limn-render"), f.limn, "--size", "32x24", "-o",
                        (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("drawing the control mesh; run limn-tables"), std::string::npos) << r.err;
    r = test::run({bin("limn-render"), f.limn, "-q", "--size", "32x24", "-o",
                   (f.dir / "o.png").string()});
    EXPECT_EQ(r.err, "") << "-q silences warnings";
    r = test::run({bin("limn-render"), f.d2, "--grid", "4", "--size", "32x24", "-o",
                   (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("--grid"), std::string::npos) << r.err;
    for (std::vector<std::string> options : {std::vector<std::string>{"--displace-scale", "0.1"},
                                             {"--displace-mid", "0.5"}, {"--no-seam-fix"}}) {
        std::vector<std::string> args = {bin("limn-render"), f.d2, "--size", "32x24", "-o", (f.dir / "o.png").string()};
        args.insert(args.end(), options.begin(), options.end());
        r = test::run(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.err.find("without --displace they do nothing"), std::string::npos) << options[0] << ": " << r.err;
    }
    r = test::run({bin("limn-render"), f.d2, "--size", "32x24", "--mesh-ascii", "-o", (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--mesh-ascii applies to a .ply --mesh-out"), std::string::npos) << r.err;
    // A mesh file is drawn as the control mesh on purpose: no warning.
    r = test::run({bin("limn-render"), f.obj, "--size", "32x24", "-o", (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
}

TEST(Messages, NewTablesDropTheOldSeams) {
    Files f;
    const std::string seams = (f.dir / "s.limn").string(), again = (f.dir / "a.limn").string();
    ASSERT_EQ(test::run({bin("limn-seams"), f.d2, "-o", seams}).exitCode, 0);
    auto r = test::run({bin("limn-tables"), seams, "-d", "3", "-o", again});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("dropped the SEAM chunk"), std::string::npos) << r.err;
    const Container c = parseContainer(test::readBytes(again));
    EXPECT_EQ(c.find(FourCC{"SEAM"}), nullptr);
}

// Classifying a container again with other scheme options: its tables and seams would draw the
// old surface (they once stayed, without a word); they are dropped, saying what to run. With
// the same options they stay, byte for byte.
TEST(Messages, ClassifyingAgainWithOtherOptionsDropsTheTables) {
    Files f;
    const std::string seams = (f.dir / "s.limn").string(), same = (f.dir / "same.limn").string(),
                      other = (f.dir / "other.limn").string();
    ASSERT_EQ(test::run({bin("limn-seams"), f.d2, "-o", seams}).exitCode, 0);
    auto r = test::run({bin("limn-classify"), seams, "-o", same});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(test::readBytes(same), test::readBytes(seams));
    for (std::vector<std::string> option : {std::vector<std::string>{"--fvar", "none"}, {"--boundary", "none"}}) {
        SCOPED_TRACE(option[0]);
        std::vector<std::string> args = {bin("limn-classify"), seams, "-o", other};
        args.insert(args.end(), option.begin(), option.end());
        r = test::run(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.err.find("its tables and seams were made for other scheme options or tags; dropped: run "
                             "limn-tables and limn-seams again"),
                  std::string::npos)
            << r.err;
        const Container c = parseContainer(test::readBytes(other));
        EXPECT_EQ(c.find(FourCC{"TBLS"}), nullptr);
        EXPECT_EQ(c.find(FourCC{"SEAM"}), nullptr);
        EXPECT_NE(c.find(FourCC{"CLSF"}), nullptr);
    }
}

// limn-render samples a map with wrap-around, so UVs moved by whole tiles (a UDIM layout) must
// bake the same map: they once baked nothing (every texel the flat 0.5) without a word. UVs
// far outside float's integers (+-2e8 times the size overflowed int) bake without undefined
// behaviour (UBSan checks it in the sanitizer run).
TEST(Messages, HeightmapWrapsUVsLikeTheRenderer) {
    test::ScratchDir dir;
    std::string shifted;
    for (size_t at = 0, end; at < kCubeObj.size(); at = end + 1) {
        end = kCubeObj.find('\n', at);
        std::string line = kCubeObj.substr(at, end - at);
        if (line.rfind("vt ", 0) == 0) {
            double u = 0, v = 0;
            std::sscanf(line.c_str(), "vt %lf %lf", &u, &v);
            line = "vt " + std::to_string(u + 1) + " " + std::to_string(v - 3);
        }
        shifted += line + "\n";
    }
    test::writeFile(dir / "cube.obj", kCubeObj);
    test::writeFile(dir / "udim.obj", shifted);
    for (const char* name : {"cube", "udim"}) {
        auto r = test::run({bin("limn-heightmap"), "--size", "32", (dir / (std::string(name) + ".obj")).string(),
                            "-o", (dir / (std::string(name) + ".png")).string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_EQ(test::readBytes(dir / "udim.png"), test::readBytes(dir / "cube.png"));
    test::writeFile(dir / "far.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt -2e8 -2e8\nvt 2e8 -2e8\n"
                                     "vt 2e8 2e8\nvt -2e8 2e8\nf 1/1 2/2 3/3 4/4\n");
    auto r = test::run({bin("limn-heightmap"), "--size", "16", "--padding", "0", (dir / "far.obj").string(), "-o",
                        (dir / "far.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(Messages, InfoValidatesAndFlagsStaleChunks) {
    Files f;
    const std::string seams = (f.dir / "s.limn").string();
    ASSERT_EQ(test::run({bin("limn-seams"), f.d3, "-o", seams}).exitCode, 0);
    auto r = test::run({bin("limn-info"), "--json", seams});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(R"("type":"SEAM","version":1)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(R"("stale":false)"), std::string::npos) << r.out;

    // The depth-3 seams spliced next to depth-2 tables: stale, and for the wrong element count.
    Container withSeams = parseContainer(test::readBytes(seams));
    Container other = parseContainer(test::readBytes(f.d2));
    other.set(*withSeams.find(FourCC{"SEAM"}));
    const auto spliced = serializeContainer(other);
    const std::string bad = (f.dir / "bad.limn").string();
    test::writeFile(bad, std::string(spliced.begin(), spliced.end()));
    r = test::run({bin("limn-info"), bad});
    EXPECT_EQ(r.exitCode, 1) << "limn-info accepted seams limn-render refuses: " << r.out;
    EXPECT_NE(r.err.find("elements"), std::string::npos) << r.err;
    r = test::run({bin("limn-render"), bad, "-o", (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
}

TEST(Messages, InfoPrintsTheBoundsThatDisplaceScalePercentUses) {
    Files f;
    auto r = test::run({bin("limn-info"), "--json", f.limn});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(R"("bounds":{"min":[0,0,0],"max":[1,1,1],"diagonal":1.7320508)"),
              std::string::npos)
        << r.out;
    ASSERT_EQ(test::run({bin("limn-heightmap"), "--kind", "uv", "--size", "16", "-o",
                         (f.dir / "h.png").string()})
                  .exitCode,
              0);
    // 2% of the unit cube's diagonal, sqrt(3) / 50.
    r = test::run({bin("limn-render"), f.d2, "-v", "--size", "32x24", "--displace",
                   (f.dir / "h.png").string(), "--displace-scale", "2%", "-o",
                   (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("= 0.034641 world units"), std::string::npos) << r.err;
    r = test::run({bin("limn-render"), f.d2, "--displace", (f.dir / "h.png").string(),
                   "--displace-scale", "2x", "-o", (f.dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
}

} // namespace

namespace {

// A tool at the end of a pipe whose first command failed reads nothing: it says so, instead of
// blaming the (absent) mesh.
TEST(Messages, EmptyStandardInputBlamesTheUpstreamCommand) {
    for (const char* tool : {"limn-classify", "limn-tables", "limn-seams", "limn-render", "limn-info", "limn-loop",
                             "limn-trim", "limn-blend"}) {
        SCOPED_TRACE(tool);
        test::ScratchDir dir;
        std::vector<std::string> args = {bin(tool)};
        if (std::string(tool) == "limn-render") args.insert(args.end(), {"-o", (dir / "o.png").string()});
        const auto r = test::run(args, "");
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find("empty input on <stdin> (did the command before it in the pipe fail?)"), std::string::npos)
            << r.err;
        EXPECT_EQ(r.err.find("no vertices"), std::string::npos) << r.err;
    }
}

// 60 glTF nodes that each list the next twice (2^60 paths) once kept limn-info and
// limn-classify busy forever; a cycle too. Both are refused before any work.
TEST(Messages, GltfNodeGraphsThatAreNotTreesAreRefusedWithinASecond) {
    for (const char* tool : {"limn-info", "limn-classify"})
        for (const char* file : {"dag.gltf", "cycle.gltf"}) {
            SCOPED_TRACE(std::string(tool) + " " + file);
            test::ScratchDir dir;
            const auto start = std::chrono::steady_clock::now();
            auto r = test::run({bin(tool), test::modelPath(std::string("gltf/features/") + file).string(), "-o",
                                (dir / "o.limn").string()});
            if (std::string(tool) == "limn-info")
                r = test::run({bin(tool), test::modelPath(std::string("gltf/features/") + file).string()});
            EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2)); // both runs
            EXPECT_EQ(r.exitCode, 1) << r.err;
            EXPECT_NE(r.err.find("glTF requires the nodes to form trees"), std::string::npos) << r.err;
            EXPECT_TRUE(test::filesIn(dir.path()).empty());
        }
}

// A Möbius strip (a strip of four quads whose ends join with a half twist) is not orientable;
// a mesh with one face flipped is orientable and the message says how many faces to flip.
TEST(Messages, MoebiusStripIsNotOrientable) {
    test::ScratchDir dir;
    // Vertices 0..4 along the bottom edge, 5..9 along the top; the last quad joins column 4 to
    // column 0 upside down.
    std::string moebius;
    for (int i = 0; i < 5; ++i) moebius += "v " + std::to_string(i) + " 0 " + std::to_string(i % 2) + "\n";
    for (int i = 0; i < 5; ++i) moebius += "v " + std::to_string(i) + " 1 " + std::to_string((i + 1) % 2) + "\n";
    moebius += "f 1 2 7 6\nf 2 3 8 7\nf 3 4 9 8\nf 4 5 10 9\nf 5 6 1 10\n";
    test::writeFile(dir / "moebius.obj", moebius);
    auto c = test::run({bin("limn-classify"), "-q", (dir / "moebius.obj").string(), "-o", (dir / "m.limn").string()});
    ASSERT_EQ(c.exitCode, 0) << c.err;
    auto t = test::run({bin("limn-tables"), (dir / "m.limn").string(), "-o", (dir / "t.limn").string()});
    EXPECT_EQ(t.exitCode, 1);
    EXPECT_NE(t.err.find("the mesh is not orientable"), std::string::npos) << t.err;
    EXPECT_EQ(t.err.find("non-manifold"), std::string::npos) << t.err;
    // The cube with its top face flipped: orientable, one face to flip.
    std::string cube = kCubeObj;
    cube.replace(cube.find("f 5/1 6/2 7/3 8/4"), 17, "f 8/4 7/3 6/2 5/1");
    test::writeFile(dir / "flipped.obj", cube);
    ASSERT_EQ(test::run({bin("limn-classify"), "-q", (dir / "flipped.obj").string(), "-o", (dir / "f.limn").string()}).exitCode, 0);
    t = test::run({bin("limn-tables"), (dir / "f.limn").string(), "-o", (dir / "t.limn").string()});
    EXPECT_EQ(t.exitCode, 1);
    EXPECT_NE(t.err.find("faces of opposite orientation meet at 4 edges"), std::string::npos) << t.err;
    EXPECT_NE(t.err.find("flipping 1 faces would make the mesh consistent"), std::string::npos) << t.err;
}


// A cone of n quads whose apex has its own UV in every face (a UV seam between each two): every
// element at the apex carries all n of its UVs. Past what the displacement's seam fix averages
// (4,096 UVs at a point), or past one 128 MiB storage buffer of UVs in all, limn-seams refuses at
// once; it once worked n^3 (30 s at n = 4,000, minutes at 16,383) and wrote seams no reader took.
std::string coneWithSeamAtApex(int n) {
    std::string obj = "v 0 0 1\n";
    for (int ring = 1; ring <= 2; ++ring)
        for (int i = 0; i < n; ++i) {
            const double a = 6.283185307179586 * (i + 0.5 * (ring - 1)) / n;
            obj += "v " + std::to_string(ring * std::cos(a)) + " " + std::to_string(ring * std::sin(a)) + " 0\n";
        }
    for (int ring = 0; ring <= 2; ++ring)
        for (int i = 0; i < n; ++i) {
            const double a = 6.283185307179586 * (i + 0.5) / n, r = 0.05 + 0.15 * ring;
            obj += "vt " + std::to_string(0.5 + r * std::cos(a)) + " " + std::to_string(0.5 + r * std::sin(a)) + "\n";
        }
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        obj += "f 1/" + std::to_string(1 + i) + " " + std::to_string(2 + i) + "/" + std::to_string(1 + n + i) + " " +
               std::to_string(2 + n + i) + "/" + std::to_string(1 + 2 * n + i) + " " + std::to_string(2 + j) + "/" +
               std::to_string(1 + n + j) + "\n";
    }
    return obj;
}

TEST(Messages, SeamsOfAVertexWithThousandsOfUVsAreRefusedAtOnce) {
    struct Case {
        int n;
        const char* message;
    };
    for (Case c : {Case{4097, "a vertex has 4097 different UVs in the faces around it, more than the 4096"},
                   Case{4000, "the seams need more than 16777216 UVs (128 MiB, one GPU storage buffer)"}}) {
        SCOPED_TRACE(c.n);
        test::ScratchDir dir;
        test::writeFile(dir / "cone.obj", coneWithSeamAtApex(c.n));
        ASSERT_EQ(test::run({bin("limn-classify"), "-q", (dir / "cone.obj").string(), "-o", (dir / "c.limn").string()}).exitCode, 0);
        ASSERT_EQ(test::run({bin("limn-tables"), "-q", (dir / "c.limn").string(), "-o", (dir / "t.limn").string()}).exitCode, 0);
        const auto start = std::chrono::steady_clock::now();
        auto r = test::run({bin("limn-seams"), (dir / "t.limn").string(), "-o", (dir / "s.limn").string()});
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)); // 0.5 s here, loaded
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "s.limn"));
    }
    // Within both: 1,000 UVs at the apex, in each of its 1,000 elements' corners.
    test::ScratchDir dir;
    test::writeFile(dir / "cone.obj", coneWithSeamAtApex(1000));
    ASSERT_EQ(test::run({bin("limn-classify"), "-q", (dir / "cone.obj").string(), "-o", (dir / "c.limn").string()}).exitCode, 0);
    ASSERT_EQ(test::run({bin("limn-tables"), "-q", (dir / "c.limn").string(), "-o", (dir / "t.limn").string()}).exitCode, 0);
    auto r = test::run({bin("limn-seams"), (dir / "t.limn").string(), "-o", (dir / "s.limn").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = test::run({bin("limn-info"), "--json", (dir / "s.limn").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err; // limn-info decodes and checks the SEAM chunk
    EXPECT_NE(r.out.find("\"SEAM\""), std::string::npos) << r.out;
}

} // namespace
