// PNG, ISO/IEC 15948: signature, IHDR, optional sRGB, one IDAT (zlib), IEND. Each row takes the
// filter (None, Sub, Up, Average, Paeth) with the smallest sum of |signed residuals|, the
// heuristic the PNG specification recommends (section 12.8), then the whole image is deflated
// at level 6 in one go: deterministic for a given zlib.
#include "image/png_encode.h"

#include "base/error.h"
#include "image/png_filter.h"

#include <zlib.h>

#include <array>
#include <cstdlib>
#include <string>

namespace limn {

namespace {

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

void chunk(std::vector<uint8_t>& out, const char type[4], std::span<const uint8_t> data) {
    put32(out, static_cast<uint32_t>(data.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, out.data() + start, static_cast<uInt>(out.size() - start));
    put32(out, static_cast<uint32_t>(crc));
}

// `raw` holds the rows as bytes (bytesPerPixel per pixel, big-endian 16-bit samples).
std::vector<uint8_t> encode(uint32_t width, uint32_t height, uint8_t bitDepth, uint8_t colourType,
                            uint32_t bytesPerPixel, std::span<const uint8_t> raw, bool srgb) {
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu)
        throw Error(ErrorKind::BadInput, "PNG size must be 1 to 2^31-1 in each direction");
    const size_t stride = size_t(width) * bytesPerPixel;
    if (raw.size() != stride * height)
        throw Error(ErrorKind::BadInput, "internal: PNG samples do not match the image size");

    std::vector<uint8_t> filtered;
    filtered.reserve((stride + 1) * height);
    std::array<std::vector<uint8_t>, 5> candidate;
    for (auto& c : candidate) c.resize(stride);
    const std::vector<uint8_t> zeros(stride, 0);
    for (uint32_t y = 0; y < height; ++y) {
        const uint8_t* row = raw.data() + y * stride;
        const uint8_t* up = y ? row - stride : zeros.data();
        size_t best = 0;
        uint64_t bestCost = UINT64_MAX;
        for (size_t f = 0; f < 5; ++f) {
            uint64_t cost = 0;
            for (size_t i = 0; i < stride; ++i) {
                const int a = i >= bytesPerPixel ? row[i - bytesPerPixel] : 0;
                const int b = up[i];
                const int c = i >= bytesPerPixel ? up[i - bytesPerPixel] : 0;
                const int predictor = png::predict(unsigned(f), a, b, c);
                const uint8_t r = static_cast<uint8_t>(row[i] - predictor);
                candidate[f][i] = r;
                cost += static_cast<uint64_t>(std::abs(static_cast<int8_t>(r)));
            }
            if (cost < bestCost) bestCost = cost, best = f;
        }
        filtered.push_back(static_cast<uint8_t>(best));
        filtered.insert(filtered.end(), candidate[best].begin(), candidate[best].end());
    }

    uLongf packedSize = compressBound(static_cast<uLong>(filtered.size()));
    std::vector<uint8_t> packed(packedSize);
    if (compress2(packed.data(), &packedSize, filtered.data(), static_cast<uLong>(filtered.size()),
                  6) != Z_OK)
        throw Error(ErrorKind::BadInput, "zlib could not compress the image");
    packed.resize(packedSize);

    std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<uint8_t> header;
    put32(header, width);
    put32(header, height);
    header.insert(header.end(), {bitDepth, colourType, 0, 0, 0}); // deflate, adaptive, no interlace
    chunk(out, "IHDR", header);
    if (srgb) {
        const uint8_t perceptual = 0;
        chunk(out, "sRGB", {&perceptual, 1});
    }
    chunk(out, "IDAT", packed);
    chunk(out, "IEND", {});
    return out;
}

// PNG colour type by channel count (PNG spec 11.2.2): grey, grey + alpha, RGB, RGBA.
uint8_t colourType(uint32_t channels) {
    static const uint8_t types[5] = {0, 0, 4, 2, 6};
    if (channels < 1 || channels > 4)
        throw Error(ErrorKind::BadInput, "PNG output needs 1 to 4 channels");
    return types[channels];
}

} // namespace

std::vector<uint8_t> encodePng8(uint32_t width, uint32_t height, uint32_t channels,
                                std::span<const uint8_t> samples) {
    return encode(width, height, 8, colourType(channels), channels, samples, true);
}

namespace {

std::vector<uint8_t> bigEndian(std::span<const uint16_t> samples) {
    std::vector<uint8_t> bytes;
    bytes.reserve(samples.size() * 2);
    for (uint16_t s : samples) {
        bytes.push_back(static_cast<uint8_t>(s >> 8));
        bytes.push_back(static_cast<uint8_t>(s & 0xFF));
    }
    return bytes;
}

} // namespace

std::vector<uint8_t> encodePng16(uint32_t width, uint32_t height, uint32_t channels,
                                 std::span<const uint16_t> samples) {
    // The filters work on bytes, with the pixel's byte count as the left neighbour's distance
    // (PNG spec 9.2), so 16-bit samples need nothing special.
    return encode(width, height, 16, colourType(channels), 2 * channels, bigEndian(samples), true);
}

std::vector<uint8_t> encodePngGray16(uint32_t width, uint32_t height,
                                     std::span<const uint16_t> samples) {
    return encode(width, height, 16, 0, 2, bigEndian(samples), false);
}

} // namespace limn
