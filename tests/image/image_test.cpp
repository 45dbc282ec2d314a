// lib/image: PNGs from limn's own encoder decode (with OpenImageIO, linked here directly) to the
// exact samples, carry only the chunks the encoder promises, and are the same bytes each time;
// reading through the plugin reports bad files, huge images and a missing plugin clearly.
#include "base/error.h"
#include "image/image_file.h"
#include "image/png_decode.h"
#include "image/png_encode.h"
#include "test_support.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdlib>
#include <random>

using namespace limn;

namespace {

struct Decoded {
    int width = 0, height = 0, channels = 0;
    std::vector<uint16_t> samples;
};

// OpenImageIO's decoder (libpng underneath), not limn's.
Decoded decode(const std::vector<uint8_t>& png) {
    OIIO::Filesystem::IOMemReader memory(png.data(), png.size());
    OIIO::ImageSpec config;
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open("image.png", &config);
    if (!in) throw std::runtime_error("OpenImageIO cannot open it: " + OIIO::geterror());
    Decoded d;
    d.width = in->spec().width;
    d.height = in->spec().height;
    d.channels = in->spec().nchannels;
    d.samples.resize(size_t(d.width) * d.height * d.channels);
    if (!in->read_image(0, 0, 0, d.channels, OIIO::TypeDesc::UINT16, d.samples.data()))
        throw std::runtime_error("OpenImageIO cannot read it: " + in->geterror());
    return d;
}

std::vector<std::string> chunkTypes(const std::vector<uint8_t>& png) {
    std::vector<std::string> types;
    for (size_t i = 8; i + 12 <= png.size();) {
        uint32_t n = uint32_t(png[i]) << 24 | uint32_t(png[i + 1]) << 16 |
                     uint32_t(png[i + 2]) << 8 | png[i + 3];
        types.emplace_back(reinterpret_cast<const char*>(&png[i + 4]), 4);
        i += 12 + n;
    }
    return types;
}

TEST(PngEncode, EightBitRoundTripsExactlyForEveryChannelCount) {
    std::mt19937 rng(7);
    for (uint32_t channels = 1; channels <= 4; ++channels)
        for (auto [w, h] : {std::pair{1u, 1u}, {3u, 7u}, {64u, 5u}, {257u, 33u}}) {
            SCOPED_TRACE(std::to_string(channels) + " channels " + std::to_string(w) + "x" +
                         std::to_string(h));
            // Half noise, half smooth ramps, so every filter type gets chosen somewhere.
            std::vector<uint8_t> samples(size_t(w) * h * channels);
            for (size_t i = 0; i < samples.size(); ++i)
                samples[i] = (i / (w * channels)) % 2 ? uint8_t(rng()) : uint8_t(i * 3);
            auto png = encodePng8(w, h, channels, samples);
            EXPECT_EQ(encodePng8(w, h, channels, samples), png);
            EXPECT_EQ(chunkTypes(png), (std::vector<std::string>{"IHDR", "sRGB", "IDAT", "IEND"}));
            Decoded d = decode(png);
            ASSERT_EQ(d.width, int(w));
            ASSERT_EQ(d.height, int(h));
            ASSERT_EQ(d.channels, int(channels));
            for (size_t i = 0; i < samples.size(); ++i)
                ASSERT_EQ(d.samples[i], samples[i] * 257) << "sample " << i; // 8 -> 16 bit
        }
}

TEST(PngEncode, SixteenBitGreyRoundTripsExactly) {
    std::mt19937 rng(11);
    const uint32_t w = 129, h = 40;
    std::vector<uint16_t> samples(size_t(w) * h);
    for (size_t i = 0; i < samples.size(); ++i)
        samples[i] = i % 3 ? uint16_t(rng()) : uint16_t(i * 1000);
    auto png = encodePngGray16(w, h, samples);
    EXPECT_EQ(chunkTypes(png), (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
    Decoded d = decode(png);
    ASSERT_EQ(d.channels, 1);
    EXPECT_EQ(d.samples, samples);
}

TEST(PngEncode, RefusesBadSizes) {
    std::vector<uint8_t> two(2, 0);
    EXPECT_THROW(encodePng8(0, 1, 1, {}), Error);
    EXPECT_THROW(encodePng8(1, 1, 5, two), Error);
    EXPECT_THROW(encodePng8(3, 1, 1, two), Error); // fewer samples than pixels
}

TEST(ReadImage, ReadsWhatTheEncoderWrote) {
    test::ScratchDir dir;
    std::vector<uint8_t> rgba = {0, 128, 255, 10, 255, 0, 1, 255};
    auto path = dir / "two.png";
    auto png = encodePng8(2, 1, 4, rgba);
    test::writeFile(path, std::string(png.begin(), png.end()));
    FloatImage img = readImageFile(path.string());
    ASSERT_EQ(img.width, 2u);
    ASSERT_EQ(img.height, 1u);
    ASSERT_EQ(img.channels, 4u);
    for (size_t i = 0; i < rgba.size(); ++i)
        EXPECT_FLOAT_EQ(img.values[i], rgba[i] / 255.0f) << "not premultiplied: sample " << i;
}

TEST(ReadImage, BadFilesAreBadInputNamingTheFile) {
    test::ScratchDir dir;
    test::writeFile(dir / "junk.png", "not a PNG at all");
    for (const auto& path : {(dir / "missing.png").string(), (dir / "junk.png").string()}) {
        try {
            readImageFile(path);
            ADD_FAILURE() << "no error for " << path;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_EQ(e.file(), path);
        }
    }
}

TEST(ReadImage, HugeDeclaredSizeIsRefusedBeforeAllocating) {
    // A valid 1x1 PNG whose header then claims 20000 x 20000 RGBA (1.6e9 values).
    std::vector<uint8_t> one = {1, 2, 3, 4};
    auto png = encodePng8(1, 1, 4, one);
    auto put32 = [&](size_t at, uint32_t v) {
        for (int k = 0; k < 4; ++k) png[at + k] = uint8_t(v >> (24 - 8 * k));
    };
    put32(16, 20000);
    put32(20, 20000);
    put32(29, uint32_t(crc32(crc32(0, Z_NULL, 0), png.data() + 12, 17))); // IHDR's CRC
    try {
        readImageBytes(png, "image.png");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();
    }
}

// Formats other than PNG go through the OpenImageIO plugin (build/lib/limn/limn_image_oiio.so,
// found next to bin/): a float EXR arrives as the exact floats written, a 16-bit TIFF as k/65535,
// the displacement maps users have besides PNG.
TEST(ReadImage, PluginReadsFloatExrAndSixteenBitTiffExactly) {
    test::ScratchDir dir;
    const int w = 5, h = 3;
    std::vector<float> heights(w * h);
    std::vector<uint16_t> levels(w * h);
    for (int i = 0; i < w * h; ++i) {
        heights[i] = -0.75f + 0.3125f * float(i) + 1e-3f * float(i * i); // negative, > 1, fractions
        levels[i] = static_cast<uint16_t>((i * 4099) % 65536);
    }
    auto write = [&](const std::filesystem::path& path, OIIO::TypeDesc type, const void* pixels) {
        auto out = OIIO::ImageOutput::create(path.string());
        ASSERT_TRUE(out) << OIIO::geterror();
        ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(w, h, 1, type))) << out->geterror();
        ASSERT_TRUE(out->write_image(type, pixels)) << out->geterror();
        ASSERT_TRUE(out->close());
    };
    write(dir / "map.exr", OIIO::TypeDesc::FLOAT, heights.data());
    write(dir / "map.tif", OIIO::TypeDesc::UINT16, levels.data());

    FloatImage exr = readImageFile((dir / "map.exr").string());
    ASSERT_EQ(exr.width, uint32_t(w));
    ASSERT_EQ(exr.height, uint32_t(h));
    ASSERT_EQ(exr.channels, 1u);
    for (int i = 0; i < w * h; ++i) EXPECT_EQ(exr.values[i], heights[i]) << "texel " << i;

    FloatImage tif = readImageFile((dir / "map.tif").string());
    ASSERT_EQ(tif.width, uint32_t(w));
    ASSERT_EQ(tif.channels, 1u);
    for (int i = 0; i < w * h; ++i)
        EXPECT_FLOAT_EQ(tif.values[i], float(levels[i]) / 65535.0f) << "texel " << i;
}

// gtest_discover_tests runs every test in its own process, so the plugin is not loaded yet.
TEST(ReadImage, MissingPluginIsACapabilityError) {
    setenv("LIMN_IMAGE_PLUGIN", "/nonexistent/limn_image_oiio.so", 1);
    test::ScratchDir dir;
    test::writeFile(dir / "map.exr", "not a PNG, so only OpenImageIO could read it");
    try {
        readImageFile((dir / "map.exr").string());
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Capability);
        EXPECT_NE(std::string(e.what()).find("/nonexistent/limn_image_oiio.so"), std::string::npos)
            << e.what();
    }
}

// ---------------------------------------------------------------------------------------------
// limn's own PNG decoder against OpenImageIO's, on PNGs OpenImageIO wrote and on hand-made ones.

std::vector<uint8_t> oiioPng(int w, int h, int channels, OIIO::TypeDesc type, const void* pixels) {
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    OIIO::ImageSpec spec(w, h, channels, type);
    OIIO::Filesystem::IOProxy* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    auto out = OIIO::ImageOutput::create("png");
    if (!out || !out->open("image.png", spec) || !out->write_image(type, pixels) || !out->close())
        throw std::runtime_error("OpenImageIO cannot write the PNG");
    return {bytes.begin(), bytes.end()};
}

std::vector<float> oiioFloats(const std::vector<uint8_t>& png) {
    Decoded d = decode(png); // 16-bit samples; every 8-bit value is k * 257
    std::vector<float> out;
    for (uint16_t v : d.samples) out.push_back(float(v) / 65535.0f);
    return out;
}

void appendChunk(std::vector<uint8_t>& png, const std::string& type,
                 const std::vector<uint8_t>& data) {
    for (int s = 24; s >= 0; s -= 8) png.push_back(uint8_t(data.size() >> s));
    size_t start = png.size();
    png.insert(png.end(), type.begin(), type.end());
    png.insert(png.end(), data.begin(), data.end());
    uint32_t crc =
        uint32_t(crc32(crc32(0, Z_NULL, 0), png.data() + start, uInt(png.size() - start)));
    for (int s = 24; s >= 0; s -= 8) png.push_back(uint8_t(crc >> s));
}

// A PNG put together here: IHDR, optional PLTE, one IDAT of the given filtered rows, IEND.
std::vector<uint8_t> handMade(uint32_t w, uint32_t h, uint8_t depth, uint8_t colour,
                              const std::vector<uint8_t>& filteredRows,
                              const std::vector<uint8_t>& palette = {}, uint8_t interlace = 0) {
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<uint8_t> ihdr;
    for (uint32_t v : {w, h})
        for (int s = 24; s >= 0; s -= 8) ihdr.push_back(uint8_t(v >> s));
    ihdr.insert(ihdr.end(), {depth, colour, 0, 0, interlace});
    appendChunk(png, "IHDR", ihdr);
    if (!palette.empty()) appendChunk(png, "PLTE", palette);
    uLongf n = compressBound(uLong(filteredRows.size()));
    std::vector<uint8_t> z(n);
    compress2(z.data(), &n, filteredRows.data(), uLong(filteredRows.size()), 9);
    z.resize(n);
    appendChunk(png, "IDAT", z);
    appendChunk(png, "IEND", {});
    return png;
}

TEST(PngDecode, AgreesWithOpenImageIOOnItsOwnPngs) {
    std::mt19937 rng(3);
    for (int channels = 1; channels <= 4; ++channels) {
        const int w = 45, h = 17;
        std::vector<uint8_t> p8(size_t(w) * h * channels);
        std::vector<uint16_t> p16(p8.size());
        for (size_t i = 0; i < p8.size(); ++i) {
            p8[i] = uint8_t(i % 7 ? rng() : i);
            p16[i] = uint16_t(i % 5 ? rng() : i * 77);
        }
        for (const auto& png : {oiioPng(w, h, channels, OIIO::TypeDesc::UINT8, p8.data()),
                                oiioPng(w, h, channels, OIIO::TypeDesc::UINT16, p16.data())}) {
            auto ours = decodePngCommon(png);
            ASSERT_TRUE(ours.has_value()) << channels << " channels";
            EXPECT_EQ(ours->channels, uint32_t(channels));
            EXPECT_EQ(ours->values, oiioFloats(png)) << channels << " channels";
        }
    }
}

TEST(PngDecode, PaletteAndEveryFilterType) {
    // 3 x 5 palette image, one row per filter type (None, Sub, Up, Average, Paeth), raw indices
    // chosen so the filtered bytes wrap around.
    const std::vector<uint8_t> palette = {10, 20, 30, 200, 100, 0, 255, 255, 255, 1, 2, 3};
    const uint8_t idx[5][3] = {{0, 1, 2}, {3, 2, 1}, {1, 1, 3}, {2, 0, 3}, {3, 3, 0}};
    std::vector<uint8_t> rows;
    for (int y = 0; y < 5; ++y) {
        rows.push_back(uint8_t(y));
        for (int x = 0; x < 3; ++x) {
            int a = x ? idx[y][x - 1] : 0, b = y ? idx[y - 1][x] : 0,
                c = x && y ? idx[y - 1][x - 1] : 0;
            int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
            int pred[5] = {0, a, b, (a + b) / 2, pa <= pb && pa <= pc ? a : pb <= pc ? b : c};
            rows.push_back(uint8_t(idx[y][x] - pred[y]));
        }
    }
    auto png = handMade(3, 5, 8, 3, rows, palette);
    auto ours = decodePngCommon(png);
    ASSERT_TRUE(ours.has_value());
    ASSERT_EQ(ours->channels, 3u);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 3; ++x)
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(ours->values[(y * 3 + x) * 3 + k], palette[idx[y][x] * 3 + k] / 255.0f);
    EXPECT_EQ(ours->values, oiioFloats(png));
}

TEST(PngDecode, LeavesRareFeaturesToTheOpenImageIOPlugin) {
    // 1-bit grey and an interlaced image: not ours, but readImageBytes still reads them.
    auto oneBit = handMade(8, 2, 1, 0, {0, 0xA5, 0, 0x0F});
    EXPECT_FALSE(decodePngCommon(oneBit).has_value());
    FloatImage img = readImageBytes(oneBit, "image.png");
    EXPECT_EQ(img.values, oiioFloats(oneBit));
    auto interlaced = handMade(1, 1, 8, 0, {0, 77}, {}, 1);
    EXPECT_FALSE(decodePngCommon(interlaced).has_value());
    EXPECT_EQ(readImageBytes(interlaced, "image.png").values, oiioFloats(interlaced));
}

TEST(PngDecode, DamageIsBadInputNeverACrash) {
    std::vector<uint8_t> samples(20 * 9 * 3);
    for (size_t i = 0; i < samples.size(); ++i) samples[i] = uint8_t(i * 13);
    const auto good = encodePng8(20, 9, 3, samples);
    auto expectBad = [](const std::vector<uint8_t>& png, const std::string& what) {
        try {
            decodePngCommon(png);
            ADD_FAILURE() << "no error for " << what;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput) << what;
        }
    };
    for (size_t n = 0; n < good.size(); ++n)
        expectBad({good.begin(), good.begin() + long(n)}, "truncated to " + std::to_string(n));
    for (size_t i = 8; i < good.size(); ++i) { // any flipped bit breaks a CRC or a length
        auto bad = good;
        bad[i] ^= 0x10;
        expectBad(bad, "bit flipped at " + std::to_string(i));
    }
    expectBad(handMade(2, 1, 8, 0, {5, 1, 2}), "filter type 5");
    expectBad(handMade(2, 2, 8, 0, {0, 1, 2}), "too little data");
    expectBad(handMade(1, 1, 8, 3, {0, 9}, {1, 2, 3}), "palette index past the palette");
    expectBad(handMade(1, 1, 8, 3, {0, 0}), "palette image without PLTE");
    expectBad(handMade(1, 1, 8, 5, {0, 0}), "colour type 5");
    expectBad(handMade(0x7FFFFFFF, 0x7FFFFFFF, 8, 6, {0}), "2^31 x 2^31 RGBA");
    expectBad(handMade(16384, 16384, 16, 6, {0}), "2^30 values: over the limit");
    expectBad(handMade(8192, 8192, 8, 6, {0, 1, 2, 3, 4}), "2^28 values claimed, 4 given");
}

} // namespace
