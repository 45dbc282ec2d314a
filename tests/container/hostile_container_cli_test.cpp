// Hostile .limn input through the tools (formats/limn.md section 4): limn-info and limn-classify
// refuse every damaged container of hostile_containers.h with exit code 1 and one line naming the
// file, without a crash or a partial output file; unknown chunks pass through limn-classify.
#include "container/container.h"
#include "hostile_containers.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

using namespace limn;
using namespace limn::test::hostile;

namespace {

// Lists the directory's entries other than `keep`: no output, no temporary file left behind.
std::vector<std::string> leftovers(const std::filesystem::path& dir, const std::string& keep) {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().filename() != keep) out.push_back(e.path().filename().string());
    return out;
}

TEST(HostileContainer, RejectedByTheTools) {
    for (const auto& c : cases()) {
        SCOPED_TRACE(c.name);
        test::ScratchDir dir;
        std::string input = (dir / "in.limn").string();
        test::writeFile(input, std::string(c.bytes.begin(), c.bytes.end()));

        auto info = test::run({test::tool("limn-info").string(), "--json", input});
        EXPECT_EQ(info.exitCode, 1);
        EXPECT_EQ(info.out, "");
        EXPECT_EQ(info.err.rfind("limn-info: error: " + input + ": ", 0), 0u) << info.err;
        EXPECT_NE(info.err.find(c.message), std::string::npos) << info.err;
        EXPECT_EQ(std::count(info.err.begin(), info.err.end(), '\n'), 1) << info.err;

        if (!c.classifyReads) continue;
        std::string output = (dir / "out.limn").string();
        auto classify = test::run({test::tool("limn-classify").string(), input, "-o", output});
        EXPECT_EQ(classify.exitCode, 1);
        EXPECT_EQ(classify.err.rfind("limn-classify: error: " + input + ": ", 0), 0u)
            << classify.err;
        EXPECT_EQ(leftovers(dir.path(), "in.limn"), std::vector<std::string>{});
    }
}

TEST(HostileContainer, TruncatedFilesThroughLimnInfo) {
    auto bytes = validContainers()[1];
    test::ScratchDir dir;
    std::string path = (dir / "cut.limn").string();
    for (size_t n = 0; n < bytes.size(); n += n < 64 ? 13 : 397) {
        SCOPED_TRACE(n);
        test::writeFile(path, std::string(bytes.begin(), bytes.begin() + n));
        auto r = test::run({test::tool("limn-info").string(), path});
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err.rfind("limn-info: error: " + path + ": ", 0), 0u) << r.err;
        // The same bytes on standard input are refused too (sniffed as .limn or as OBJ).
        auto piped = test::run({test::tool("limn-info").string()},
                               std::string(bytes.begin(), bytes.begin() + n));
        EXPECT_EQ(piped.exitCode, 1) << piped.err;
        EXPECT_EQ(piped.out, "");
    }
}

// Readers skip unknown chunks and tools pass them through unchanged (section 3).
TEST(HostileContainer, UnknownChunksPassThroughLimnClassify) {
    auto bytes = frame({{"XTRA", {9, 8, 7}}, {"MESH", triangleMesh()}, {"ZZ_9", {}}});
    auto r = test::run({test::tool("limn-classify").string(), "-"},
                       std::string(bytes.begin(), bytes.end()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Container out =
        parseContainer(std::span(reinterpret_cast<const uint8_t*>(r.out.data()), r.out.size()));
    std::vector<std::string> order;
    for (const auto& c : out.chunks) order.push_back(c.type.str());
    EXPECT_EQ(order, (std::vector<std::string>{"XTRA", "MESH", "ZZ_9", "TAGS", "CLSF"}));
    EXPECT_EQ(out.find(FourCC("XTRA"))->payload, (std::vector<uint8_t>{9, 8, 7}));
    EXPECT_EQ(out.find(FourCC("XTRA"))->version, 1u);
    EXPECT_TRUE(out.find(FourCC("ZZ_9"))->payload.empty());
}

} // namespace
