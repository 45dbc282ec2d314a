// Makefile.examples: builds every example through limn-classify and limn-info, prints the
// summaries, and a second run does nothing until an input changes.
#include "test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <sstream>

using namespace limn;

namespace {

test::RunResult make(const std::filesystem::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {"/usr/bin/make",
                                     "-s",
                                     "-f",
                                     std::string(LIMN_SOURCE_DIR) + "/Makefile.examples",
                                     "BIN=" + test::binDir().string(),
                                     "OUT=" + out.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return test::run(argv);
}

TEST(MakefileExamples, BuildsOnceThenNothing) {
    test::ScratchDir dir;
    const auto out = dir / "out";
    auto first = make(out, {"-j2"});
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_TRUE(first.err.empty()) << first.err;

    auto list = test::run({test::tool("limn-examples").string(), "--list"});
    std::istringstream names(list.out);
    int count = 0;
    for (std::string name; std::getline(names, name); ++count) {
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
    EXPECT_EQ(count, 6);

    // Up to date: make -q agrees and a second run prints and rebuilds nothing.
    EXPECT_EQ(make(out, {"-q"}).exitCode, 0);
    auto second = make(out, {"-j2"});
    EXPECT_EQ(second.exitCode, 0);
    EXPECT_EQ(second.out, "");

    // A changed input rebuilds just what depends on it.
    auto obj = out / "meshes" / "torus.obj";
    std::filesystem::last_write_time(obj, std::filesystem::last_write_time(obj) +
                                              std::chrono::seconds(10));
    EXPECT_EQ(make(out, {"-q"}).exitCode, 1);
    auto third = make(out);
    EXPECT_EQ(third.exitCode, 0) << third.err;
    EXPECT_EQ(third.out.rfind((out / "torus.limn").string() + "\n", 0), 0u) << third.out;
    EXPECT_EQ(third.out.find("cube.limn"), std::string::npos) << third.out;
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
