// formats/limn.md section 6 through the tool: limn-classify writes exactly the pinned 256 bytes
// for the single triangle, from a file and from standard input, to stdout and to a file.
#include "test_support.h"
#include "worked_example.h"

#include <gtest/gtest.h>

using namespace limn;
using namespace limn::test::worked_example;

namespace {

TEST(WorkedExample, LimnClassifyWritesExactlyThem) {
    auto bytes = pinned();
    std::string expected(bytes.begin(), bytes.end());
    // From a file and from standard input (format sniffed), to stdout and to a file.
    test::ScratchDir dir;
    test::writeFile(dir / "triangle.obj", kTriangleObj);
    auto r = test::run({test::tool("limn-classify").string(), (dir / "triangle.obj").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out, expected);
    auto piped = test::run({test::tool("limn-classify").string()}, kTriangleObj);
    ASSERT_EQ(piped.exitCode, 0) << piped.err;
    EXPECT_EQ(piped.out, expected);
    auto toFile = test::run({test::tool("limn-classify").string(), (dir / "triangle.obj").string(),
                             "-o", (dir / "triangle.limn").string()});
    ASSERT_EQ(toFile.exitCode, 0) << toFile.err;
    EXPECT_EQ(toFile.out, "");
    EXPECT_EQ(test::readFile(dir / "triangle.limn"), expected);
    // Re-classifying the container reproduces it.
    auto again = test::run({test::tool("limn-classify").string(), "-"}, expected);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(again.out, expected);
}

} // namespace
