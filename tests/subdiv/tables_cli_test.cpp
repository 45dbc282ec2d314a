// limn-tables on the command line: a mesh file or a classified container in, the same bytes as
// limn-classify | limn-tables, every run alike; bad input and a bad depth refused.
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace limn;

namespace {

// A closed surface of quads (a capped cylinder) whose two poles have `valence` faces; vertex 0
// (the top pole) tagged an infinitely sharp corner: a cone point, whose limit normals are
// iterated per face on its dense (2k + 1)^2 local subdivision matrix.
std::string coneObj(uint32_t valence) {
    const uint32_t m = 2 * valence;
    std::string s = "v 0 0 1.5\n";
    for (int z : {1, -1})
        for (uint32_t j = 0; j < m; ++j)
            s += "v " + std::to_string(std::cos(2 * M_PI * j / m)) + " " +
                 std::to_string(std::sin(2 * M_PI * j / m)) + " " + std::to_string(0.5 * z) + "\n";
    s += "v 0 0 -1.5\n";
    auto A = [&](uint32_t j) { return std::to_string(2 + j % m); };
    auto B = [&](uint32_t j) { return std::to_string(2 + m + j % m); };
    const std::string Q = std::to_string(2 + 2 * m);
    for (uint32_t i = 0; i < valence; ++i) s += "f 1 " + A(2 * i) + " " + A(2 * i + 1) + " " + A(2 * i + 2) + "\n";
    for (uint32_t j = 0; j < m; ++j) s += "f " + A(j) + " " + B(j) + " " + B(j + 1) + " " + A(j + 1) + "\n";
    for (uint32_t i = 0; i < valence; ++i) s += "f " + Q + " " + B(2 * i + 2) + " " + B(2 * i + 1) + " " + B(2 * i) + "\n";
    return s + "t corner 1/1/0 0 10\n";
}

// A cone point of 300 faces took over a minute (and a dart of 16,383 asked for 8.6 GB): past
// 64 faces its limit points keep their closed-form masks, counted approximate, in well under a
// second. `timeout` bounds the run if that regresses.
TEST(TablesTool, CrowdedConePointsFinish) {
    test::ScratchDir dir;
    test::writeFile(dir / "cone.obj", coneObj(300));
    auto r = test::run({"/usr/bin/timeout", "30", test::tool("limn-tables").string(), "--depth", "1",
                        (dir / "cone.obj").string(), "-o", (dir / "cone.limn").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find(": 1 limit points have an approximate normal"), std::string::npos) << r.err;
}

// A mesh file is classified with the defaults first, exactly as limn-classify | limn-tables.
TEST(TablesTool, TakesAMeshOrAClassifiedContainer) {
    test::ScratchDir dir;
    auto r = test::run({test::tool("limn-tables").string(), "--depth", "2",
                        test::modelPath("quad/spot_control_mesh.obj").string(), "-o",
                        (dir / "out.limn").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    auto classified = test::run({test::tool("limn-classify").string(),
                                 test::modelPath("quad/spot_control_mesh.obj").string()});
    ASSERT_EQ(classified.exitCode, 0);
    auto tables = test::run({test::tool("limn-tables").string(), "--depth", "2"}, classified.out);
    ASSERT_EQ(tables.exitCode, 0) << tables.err;
    EXPECT_EQ(test::readFile(dir / "out.limn"), tables.out)
        << "a mesh input differs from limn-classify | limn-tables";
    auto garbage = test::run({test::tool("limn-tables").string(), "-"}, "not a mesh at all");
    EXPECT_EQ(garbage.exitCode, 1);
    EXPECT_NE(garbage.err.find("limn-tables: error: "), std::string::npos) << garbage.err;
    auto again = test::run({test::tool("limn-tables").string(), "--depth", "2"}, classified.out);
    EXPECT_EQ(tables.out, again.out) << "not deterministic";
    auto bad = test::run({test::tool("limn-tables").string(), "--depth", "99"}, classified.out);
    EXPECT_EQ(bad.exitCode, 2);
}

} // namespace
