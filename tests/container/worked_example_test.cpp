// formats/limn.md section 6: the 256 bytes limn-classify writes for a single triangle. The bytes
// are pinned in worked_example.h, and the spec's hex dump is read back to make sure the two never
// drift apart; limn-classify's side is in worked_example_cli_test.cpp.
#include "container/container.h"
#include "mesh/mesh_chunks.h"
#include "test_support.h"
#include "topology/classification.h"
#include "worked_example.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

using namespace limn;
using namespace limn::test::worked_example;

namespace {

// Reads the hex dump in section 6: "OFFSET: bytes...  comment", where a line that starts
// mid-row leaves the columns before it blank, as xxd does.
std::vector<uint8_t> bytesInSpec() {
    std::string spec = test::readFile(std::string(LIMN_SOURCE_DIR) + "/formats/limn.md");
    size_t section = spec.find("## 6. Worked example");
    size_t begin = spec.find("```\n", section) + 4;
    size_t end = spec.find("```", begin);
    std::istringstream lines(spec.substr(begin, end - begin));
    std::map<size_t, uint8_t> bytes;
    for (std::string line; std::getline(lines, line);) {
        if (line.size() < 10 || line[8] != ':' || line.find_first_not_of("0123456789abcdef") != 8)
            continue;
        size_t base = std::stoul(line.substr(0, 8), nullptr, 16) & ~size_t(15);
        std::string cols = line.substr(10);
        for (size_t i = 0; i < 16 && 3 * i + 2 <= cols.size(); ++i) {
            std::string h = cols.substr(3 * i, 2);
            if (h != "  ") bytes[base + i] = static_cast<uint8_t>(std::stoi(h, nullptr, 16));
        }
    }
    std::vector<uint8_t> out;
    for (const auto& [offset, b] : bytes) {
        EXPECT_EQ(offset, out.size()) << "gap in the spec's hex dump";
        out.push_back(b);
    }
    return out;
}

TEST(WorkedExample, SpecShowsThePinnedBytes) {
    EXPECT_EQ(pinned().size(), 256u);
    EXPECT_EQ(bytesInSpec(), pinned());
}

TEST(WorkedExample, ParsesAndReserializesExactly) {
    auto bytes = pinned();
    Container c = parseContainer(bytes);
    ASSERT_EQ(c.chunks.size(), 3u);
    EXPECT_EQ(c.chunks[0].type.str(), "MESH");
    EXPECT_EQ(c.chunks[1].type.str(), "TAGS");
    EXPECT_EQ(c.chunks[2].type.str(), "CLSF");
    EXPECT_EQ(serializeContainer(c), bytes);

    Mesh m = loadMesh(c);
    EXPECT_EQ(m.positions, (std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    EXPECT_EQ(m.faceVertices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_FALSE(m.hasUVs());
    EXPECT_FALSE(m.tags.boundary.has_value());
    Classification cl = decodeClassificationChunk(*c.find(kClassificationChunk), m);
    EXPECT_EQ(cl.edges, 3u);
    EXPECT_EQ(cl.boundaryEdges, 3u);
    EXPECT_EQ(cl.vertexValence, (std::vector<uint32_t>{2, 2, 2}));
    // boundary | crease | extraordinary | non-quad, per the flag table in section 5.
    EXPECT_EQ(cl.vertexFlags, (std::vector<uint32_t>{0x249, 0x249, 0x249}));
    EXPECT_EQ(cl.faceFlags, (std::vector<uint32_t>{0x18}));
    EXPECT_EQ(encodeClassificationChunk(cl).payload, c.find(kClassificationChunk)->payload);
}

} // namespace
