// Malformed OBJ through limn-classify: each is refused with exit code 1 and one line naming the
// file and the line or element, leaving no output or temporary file behind.
#include "hostile_obj_cases.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

using namespace limn;
using namespace limn::test::hostile_obj;

namespace {

TEST(HostileObj, RejectedByLimnClassify) {
    for (const auto& c : kCases) {
        SCOPED_TRACE(c.name);
        test::ScratchDir dir;
        std::string input = (dir / "in.obj").string(), output = (dir / "out.limn").string();
        test::writeFile(input, c.obj);
        auto r = test::run({test::tool("limn-classify").string(), input, "-o", output});
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind("limn-classify: error: " + input + ": ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        std::vector<std::string> left;
        for (const auto& e : std::filesystem::directory_iterator(dir.path()))
            left.push_back(e.path().filename().string());
        EXPECT_EQ(left, std::vector<std::string>{"in.obj"});
    }
}

} // namespace
