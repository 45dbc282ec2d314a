// The CPU half of the float output path (render/output_image.h): binary16 decoding, the box
// filter, sRGB encoding with straight alpha, the format chosen by extension. Expected values are
// worked out by hand from the definitions (IEEE 754 binary16, IEC 61966-2-1).
#include "image/output_image.h"

#include "base/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace limn;

TEST(OutputImage, HalfFloatsDecodeExactly) {
    EXPECT_EQ(halfToFloat(0x0000), 0.0f);
    EXPECT_TRUE(std::signbit(halfToFloat(0x8000)));
    EXPECT_EQ(halfToFloat(0x3C00), 1.0f);
    EXPECT_EQ(halfToFloat(0xC000), -2.0f);
    EXPECT_EQ(halfToFloat(0x3555), 0.333251953125f); // 1 + 341/1024, times 2^-2
    EXPECT_EQ(halfToFloat(0x7BFF), 65504.0f);         // the largest finite
    EXPECT_EQ(halfToFloat(0x0001), std::ldexp(1.0f, -24)); // the smallest subnormal
    EXPECT_EQ(halfToFloat(0x03FF), 1023 * std::ldexp(1.0f, -24));
    EXPECT_TRUE(std::isinf(halfToFloat(0x7C00)));
    EXPECT_TRUE(std::isnan(halfToFloat(0x7E00)));
}

TEST(OutputImage, BoxFilterAveragesBlocksAndKeepsTheNearestDepth) {
    LinearImage big;
    big.width = 4, big.height = 2;
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 4; ++c) big.rgba.push_back(float(i * 4 + c));
    const float inf = std::numeric_limits<float>::infinity();
    big.depth = {inf, 3, 7, inf, 2, inf, inf, inf};
    LinearImage small = boxFilter(big, 2);
    ASSERT_EQ(small.width, 2u);
    ASSERT_EQ(small.height, 1u);
    // Block 0: pixels 0, 1, 4, 5 -> mean index 2.5; block 1: 2, 3, 6, 7 -> 4.5.
    for (int c = 0; c < 4; ++c) {
        EXPECT_FLOAT_EQ(small.rgba[c], 2.5f * 4 + float(c));
        EXPECT_FLOAT_EQ(small.rgba[4 + c], 4.5f * 4 + float(c));
    }
    EXPECT_EQ(small.depth[0], 2.0f);
    EXPECT_EQ(small.depth[1], 7.0f);
    EXPECT_THROW(boxFilter(big, 3), limn::Error);
}

TEST(OutputImage, SrgbEncodingWithStraightAlpha) {
    LinearImage img;
    img.width = 3, img.height = 1;
    // Opaque linear 0.5; half-covered linear 0.5 (premultiplied 0.25); transparent.
    img.rgba = {0.5f, 0.5f, 0.5f, 1.0f, 0.25f, 0.25f, 0.25f, 0.5f, 0, 0, 0, 0};
    const std::vector<float> background = {1.0f, 0.0f, 0.0f};
    Image eight = toSrgb8(img, true, background);
    // sRGB(0.5) = 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357 -> 187.52 -> 188; 65535 * 0.735357.
    EXPECT_EQ(eight.pixels[0], 188);
    EXPECT_EQ(eight.pixels[3], 255);
    EXPECT_EQ(eight.pixels[4], 188); // un-premultiplied
    EXPECT_EQ(eight.pixels[7], 128); // alpha 0.5 -> 127.5 -> 128
    EXPECT_EQ(eight.pixels[8], 255); // transparent: the background colour
    EXPECT_EQ(eight.pixels[9], 0);
    EXPECT_EQ(eight.pixels[11], 0);
    Image16 sixteen = toSrgb16(img, false, background);
    EXPECT_EQ(sixteen.channels, 3u);
    EXPECT_EQ(sixteen.samples[0], 48192); // 65535 * 0.7353570 = 48191.6
    EXPECT_NEAR(linearToSrgb(2.0), 1.0, 1e-12); // clamped
    EXPECT_NEAR(srgbToLinear(linearToSrgb(0.2)), 0.2, 1e-12);
}

TEST(OutputImage, FormatsByExtensionOnly) {
    EXPECT_EQ(imageFormatFromPath("a.png"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("dir.x/A.PNG"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("-"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("a.exr"), ImageFormat::Exr);
    for (const char* bad : {"a.jpg", "a.tif", "a", "dir.png/a", "a.png.tmp", ".exr.x"})
        EXPECT_FALSE(imageFormatFromPath(bad).has_value()) << bad;
}
