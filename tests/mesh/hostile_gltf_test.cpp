// Hostile glTF the fuzzers do not reach: JSON nested deeper than tinygltf's recursive parser's
// stack allows (15,000 levels in a 40 KB file crashed every tool that reads meshes with
// SIGSEGV). Refused before parsing, in .gltf and in a .glb's JSON chunk; nesting inside a string
// is text, not structure.
#include "base/error.h"
#include "mesh/gltf.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace limn;

namespace {

// One triangle, embedded buffer (3 float positions then 3 ushort indices, padded), plus `extra`
// inside the asset object.
std::string triangleGltf(const std::string& extra) {
    return R"({"asset":{"version":"2.0")" + extra +
           R"(},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
           R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)"
           R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],)"
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)"
           R"({"buffer":0,"byteOffset":36,"byteLength":6}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
           R"("min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
}

std::string nested(int depth) {
    return R"(,"extras":)" + std::string(size_t(depth), '[') + std::string(size_t(depth), ']');
}

std::vector<uint8_t> glb(std::string json) {
    while (json.size() % 4) json += ' ';
    std::vector<uint8_t> out(20 + json.size());
    auto put = [&](size_t at, uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
    put(0, 0x46546C67u); // "glTF"
    put(4, 2);
    put(8, uint32_t(out.size()));
    put(12, uint32_t(json.size()));
    put(16, 0x4E4F534Au); // "JSON"
    std::memcpy(out.data() + 20, json.data(), json.size());
    return out;
}

Mesh readText(const std::string& json) {
    Warnings w;
    return readGltf({reinterpret_cast<const uint8_t*>(json.data()), json.size()}, false, "", w);
}

void expectTooDeep(auto read) {
    try {
        read();
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("the JSON nests deeper than 256 levels"), std::string::npos) << e.what();
    }
}

TEST(HostileGltf, DeepNestingIsRefusedNotACrash) {
    EXPECT_EQ(readText(triangleGltf("")).faceCount(), 1u); // the base file is valid
    EXPECT_EQ(readText(triangleGltf(nested(200))).faceCount(), 1u);
    expectTooDeep([] { readText(triangleGltf(nested(257))); });
    expectTooDeep([] { readText(triangleGltf(nested(20000))); });
    const auto bin = glb(triangleGltf(nested(20000)));
    expectTooDeep([&] {
        Warnings w;
        readGltf(bin, true, "", w);
    });
    // Brackets in a string, escaped quotes included, are not nesting.
    const std::string text = R"(,"extras":{"s":"\")" + std::string(1000, '[') + R"("})";
    EXPECT_EQ(readText(triangleGltf(text)).faceCount(), 1u);
}

// Four points (0,0,0), (1,0,0), (0,1,0), (1,1,0), drawn with primitive `mode`, no indices.
std::string fourPoints(int mode) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":)" +
           std::to_string(mode) +
           R"(}]}],"buffers":[{"byteLength":48,"uri":"data:application/octet-stream;base64,)"
           R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAgD8AAAAA"}],)"
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)"
           R"("min":[0,0,0],"max":[1,1,0]}]})";
}

std::vector<std::vector<uint32_t>> faces(const Mesh& m) {
    std::vector<std::vector<uint32_t>> out;
    for (size_t f = 0; f < m.faceCount(); ++f) out.emplace_back(m.face(f).begin(), m.face(f).end());
    return out;
}

// Triangle strips and fans are read as the triangles glTF 2.0 (3.7.2.1) defines, with their
// winding (they once failed with "the mesh has no vertices"); a file of only points or lines
// says so.
TEST(GltfPrimitives, StripsAndFansAreTriangles) {
    using F = std::vector<std::vector<uint32_t>>;
    EXPECT_EQ(faces(readText(fourPoints(5))), (F{{0, 1, 2}, {1, 3, 2}})); // strip
    EXPECT_EQ(faces(readText(fourPoints(6))), (F{{1, 2, 0}, {2, 3, 0}})); // fan
    for (int mode : {0, 1, 3}) { // points, lines, line strip
        try {
            readText(fourPoints(mode));
            ADD_FAILURE() << "accepted mode " << mode;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("no triangles to subdivide, only 1 point or line primitives"),
                      std::string::npos)
                << e.what();
        }
    }
}

// A buffer whose URI names a directory said "out of memory" (tinygltf's reader); limn's reader
// names the file and what it is.
TEST(HostileGltf, ABufferThatIsADirectoryIsNamed) {
    test::ScratchDir dir;
    std::filesystem::create_directories(dir / "sub");
    std::string json = triangleGltf("");
    const std::string embedded = json.substr(json.find("data:"), json.find('"', json.find("data:")) - json.find("data:"));
    json.replace(json.find(embedded), embedded.size(), "sub");
    Warnings w;
    try {
        readGltf({reinterpret_cast<const uint8_t*>(json.data()), json.size()}, false, dir.path().string() + "/", w);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("is a directory, not a file"), std::string::npos) << e.what();
    }
}

// A buffer view past its buffer's end (found by fuzz_gltf: BoxTextured.glb with its buffer's
// byteLength lowered, so that the embedded PNG's view ran past tinygltf's copy of the buffer, read
// out of bounds by the image callback) is refused by name.
TEST(HostileGltf, ABufferViewPastItsBufferIsRefused) {
    std::vector<uint8_t> glb = test::readBytes(test::modelPath("gltf/BoxTextured/BoxTextured.glb"));
    const std::string key = "\"buffers\":[{\"byteLength\":3273}";
    auto at = std::search(glb.begin(), glb.end(), key.begin(), key.end());
    ASSERT_NE(at, glb.end());
    std::memcpy(&*at + key.size() - 5, "1636", 4); // same length: the chunk sizes stay right
    for (const bool embeddedOnly : {false, true}) {
        Warnings w;
        try {
            if (embeddedOnly)
                readGltfEmbedded(glb, true, w);
            else
                readGltf(glb, true, "", w);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("buffer view 3 (2433 bytes at 840) runs past the end of buffer 0 (1636 bytes)"),
                      std::string::npos)
                << e.what();
        }
    }
}

} // namespace
