// PNG and PLY encodings: deterministic bytes, no metadata that varies, exact layouts.
#include "export/ply.h"
#include "image/srgb_image.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

using namespace limn;
using namespace limn::exporting;

namespace {

std::vector<std::string> pngChunks(const std::vector<uint8_t>& png) {
    std::vector<std::string> chunks;
    size_t i = 8;
    while (i + 8 <= png.size()) {
        uint32_t n = uint32_t(png[i]) << 24 | uint32_t(png[i + 1]) << 16 |
                     uint32_t(png[i + 2]) << 8 | png[i + 3];
        chunks.emplace_back(reinterpret_cast<const char*>(&png[i + 4]), 4);
        i += 12 + n;
    }
    EXPECT_EQ(i, png.size());
    return chunks;
}

Image gradient(uint32_t channels) {
    Image img;
    img.width = 7;
    img.height = 5;
    img.channels = channels;
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x)
            for (uint32_t c = 0; c < channels; ++c)
                img.pixels.push_back(static_cast<uint8_t>(x * 30 + y * 7 + c * 50));
    return img;
}

TEST(Png, RoundTripsAndCarriesNoVaryingMetadata) {
    for (uint32_t channels : {3u, 4u}) {
        Image img = gradient(channels);
        auto bytes = encodePng(img);
        ASSERT_GT(bytes.size(), 8u);
        EXPECT_EQ(std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8), 0);
        EXPECT_EQ(encodePng(img), bytes); // same pixels, same bytes
        // No tIME, tEXt, zTXt or iTXt: nothing that changes with the clock or the version.
        for (const auto& c : pngChunks(bytes))
            EXPECT_TRUE(c == "IHDR" || c == "IDAT" || c == "IEND" || c == "oFFs" || c == "sRGB")
                << "unexpected PNG chunk " << c;
        Image back = decodePng(bytes);
        EXPECT_EQ(back.width, img.width);
        EXPECT_EQ(back.height, img.height);
        EXPECT_EQ(back.channels, channels);
        EXPECT_EQ(back.pixels, img.pixels);
    }
}

TEST(Png, GarbageIsAnError) {
    std::vector<uint8_t> junk = {1, 2, 3, 4, 5};
    EXPECT_ANY_THROW(decodePng(junk));
}

DrawnMesh oneTriangle() {
    DrawnMesh m;
    m.vertices = {{0.1f, 0, 0, 0, 0, 1, 7, 0.5f, 0.25f},
                  {1, 0, 0, 0, 0, 1, 7, 1, 0},
                  {0, 1, 0, 0, 0, 1, 7, 0, 1}};
    m.triangles = {0, 1, 2};
    return m;
}

TEST(Ply, BinaryLayout) {
    auto bytes = encodePly(oneTriangle(), false);
    std::string text(bytes.begin(), bytes.end());
    auto end = text.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    std::string header = text.substr(0, end);
    EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
    EXPECT_NE(header.find("element vertex 3\n"), std::string::npos);
    EXPECT_NE(header.find("property float x\n"), std::string::npos);
    EXPECT_NE(header.find("property int ptex\n"), std::string::npos);
    EXPECT_NE(header.find("element face 1\n"), std::string::npos);
    EXPECT_NE(header.find("property list uchar int vertex_indices\n"), std::string::npos);
    size_t body = end + 11;
    ASSERT_EQ(bytes.size() - body, 3u * 36 + 13);
    float x;
    std::memcpy(&x, &bytes[body], 4);
    EXPECT_EQ(x, 0.1f);
    int32_t ptex;
    std::memcpy(&ptex, &bytes[body + 24], 4);
    EXPECT_EQ(ptex, 7);
    EXPECT_EQ(bytes[body + 3 * 36], 3);
}

// The approximate flag is a last `uchar approximate` property, present only when some vertex
// has it (so meshes drawn on the limit everywhere keep the layout above).
TEST(Ply, ApproximateFlagOnlyWhenSomeVertexHasIt) {
    DrawnMesh m = oneTriangle();
    EXPECT_EQ(encodePly(m, false).size(), encodePly(oneTriangle(), false).size());
    m.vertices[1].approximate = 1;
    auto bytes = encodePly(m, false);
    std::string text(bytes.begin(), bytes.end());
    const size_t end = text.find("end_header\n");
    EXPECT_NE(text.substr(0, end).find("property float v\nproperty uchar approximate\nelement face"), std::string::npos);
    const size_t body = end + 11;
    ASSERT_EQ(bytes.size() - body, 3u * 37 + 13);
    EXPECT_EQ(bytes[body + 36], 0);
    EXPECT_EQ(bytes[body + 37 + 36], 1);
    EXPECT_EQ(bytes[body + 2 * 37 + 36], 0);
    const auto ascii = encodePly(m, true);
    EXPECT_NE(std::string(ascii.begin(), ascii.end()).find(" 0.5 0.25 0\n"), std::string::npos);
}

TEST(Ply, AsciiRoundTripsFloats) {
    auto bytes = encodePly(oneTriangle(), true);
    std::string text(bytes.begin(), bytes.end());
    EXPECT_NE(text.find("format ascii 1.0"), std::string::npos);
    EXPECT_NE(text.find("\n0.1 0 0 0 0 1 7 0.5 0.25\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\n3 0 1 2\n"), std::string::npos);
}

} // namespace
