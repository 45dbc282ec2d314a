// Messages that say what to do, and no silent fallbacks (issue 15, section 4): errors about an
// option's file name the option; a container without tables and a --grid without a blending
// surface warn; new tables drop the seams made for the old ones; limn-info validates and flags
// stale chunks and prints the bounding box that --displace-scale P% refers to.
#include "container/container.h"
#include "test_support.h"

#include <gtest/gtest.h>

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
    auto r = test::run({bin("limn-render"), f.d2, "--texture", (f.dir / "t.png").string(),
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
