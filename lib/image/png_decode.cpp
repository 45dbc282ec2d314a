// PNG, ISO/IEC 15948 sections 5 (chunks), 11.2 (IHDR, PLTE, IDAT), 9 (filters), read the way the
// encoder in png_encode.cpp writes it and most tools do: one zlib stream across the IDATs, one
// filter byte per row. Every length, index and size is checked before use.
#include "image/png_decode.h"

#include "base/error.h"
#include "image/png_filter.h"

#include <zlib.h>

#include <cstdlib>
#include <cstring>
#include <string>

namespace limn {

namespace {

[[noreturn]] void bad(const std::string& why) {
    throw Error(ErrorKind::BadInput, "damaged PNG: " + why);
}

uint32_t get32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3];
}

} // namespace

std::optional<FloatImage> decodePngCommon(std::span<const uint8_t> bytes) {
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), signature, 8) != 0) bad("no PNG signature");

    uint32_t width = 0, height = 0;
    uint8_t depth = 0, colour = 0;
    bool haveHeader = false, ended = false;
    std::vector<uint8_t> palette; // RGB triples
    std::vector<uint8_t> compressed;
    for (size_t at = 8; !ended;) {
        if (bytes.size() - at < 12) bad("truncated chunk at byte " + std::to_string(at));
        const uint32_t length = get32(&bytes[at]);
        if (length > bytes.size() - at - 12)
            bad("chunk at byte " + std::to_string(at) + " runs past the end");
        const uint8_t* type = &bytes[at + 4];
        const uint8_t* data = type + 4;
        uLong crc = crc32(crc32(0L, Z_NULL, 0), type, static_cast<uInt>(length + 4));
        if (uint32_t(crc) != get32(data + length))
            bad("CRC mismatch in chunk at byte " + std::to_string(at));
        const std::string name(reinterpret_cast<const char*>(type), 4);
        if (!haveHeader && name != "IHDR") bad("the first chunk is not IHDR");
        if (name == "IHDR") {
            if (haveHeader || length != 13) bad("bad IHDR");
            width = get32(data);
            height = get32(data + 4);
            depth = data[8];
            colour = data[9];
            if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu)
                bad("bad image size");
            if (data[10] != 0 || data[11] != 0) bad("unknown compression or filter method");
            if (data[12] != 0) return std::nullopt; // interlaced: OpenImageIO
            haveHeader = true;
        } else if (name == "PLTE") {
            if (length % 3 != 0 || length == 0 || length > 768) bad("bad PLTE");
            palette.assign(data, data + length);
        } else if (name == "tRNS") {
            return std::nullopt; // transparency turns into an alpha channel: OpenImageIO
        } else if (name == "IDAT") {
            compressed.insert(compressed.end(), data, data + length);
        } else if (name == "IEND") {
            ended = true;
        } else if (!(type[0] & 0x20)) {
            return std::nullopt; // an unknown critical chunk: let OpenImageIO decide
        }
        at += 12 + size_t(length);
    }

    uint32_t channels = 0;
    switch (colour) {
    case 0:
        channels = 1;
        break;
    case 2:
        channels = 3;
        break;
    case 3:
        channels = 3;
        break;
    case 4:
        channels = 2;
        break;
    case 6:
        channels = 4;
        break;
    default:
        bad("unknown colour type " + std::to_string(colour));
    }
    const bool paletted = colour == 3;
    if (paletted ? depth != 8 : (depth != 8 && depth != 16))
        return std::nullopt; // 1/2/4-bit samples: OpenImageIO
    if (paletted && palette.empty()) bad("a palette image without PLTE");
    if (uint64_t(width) * height * channels > kMaxImageValues)
        throw Error(ErrorKind::BadInput, "image too large: " + std::to_string(width) + "x" +
                                             std::to_string(height) + "x" +
                                             std::to_string(channels));

    const uint32_t samplesPerPixel = paletted ? 1 : channels;
    const size_t bytesPerPixel = samplesPerPixel * (depth / 8u);
    const size_t stride = size_t(width) * bytesPerPixel;
    if (compressed.empty()) bad("no IDAT");

    // Inflate row by row and grow the output as rows arrive, so a tiny file that claims a huge
    // size fails when its data runs out, not after allocating the whole image.
    z_stream zs{};
    if (inflateInit(&zs) != Z_OK) throw Error(ErrorKind::BadInput, "zlib could not start");
    struct End {
        z_stream* s;
        ~End() { inflateEnd(s); }
    } end{&zs};
    zs.next_in = compressed.data();
    zs.avail_in = static_cast<uInt>(compressed.size());
    std::vector<uint8_t> filtered(stride + 1), previous(stride, 0), row(stride);
    FloatImage img;
    img.width = width;
    img.height = height;
    img.channels = channels;
    std::vector<float> decoded(size_t(width) * channels);
    for (uint32_t y = 0; y < height; ++y) {
        zs.next_out = filtered.data();
        zs.avail_out = static_cast<uInt>(filtered.size());
        while (zs.avail_out > 0) {
            int z = inflate(&zs, Z_NO_FLUSH);
            if (z == Z_STREAM_END && zs.avail_out > 0)
                bad("the image data ends in row " + std::to_string(y));
            if (z != Z_OK && z != Z_STREAM_END) bad("bad zlib stream in row " + std::to_string(y));
        }
        const uint8_t filter = filtered[0];
        if (filter > 4)
            bad("unknown filter type " + std::to_string(filter) + " in row " + std::to_string(y));
        for (size_t i = 0; i < stride; ++i) {
            const int a = i >= bytesPerPixel ? row[i - bytesPerPixel] : 0;
            const int b = previous[i];
            const int c = i >= bytesPerPixel ? previous[i - bytesPerPixel] : 0;
            const int predictor = png::predict(unsigned(filter), a, b, c);
            row[i] = static_cast<uint8_t>(filtered[1 + i] + predictor);
        }
        float* out = decoded.data();
        for (uint32_t x = 0; x < width; ++x) {
            if (paletted) {
                const size_t index = row[x];
                if (3 * index + 2 >= palette.size())
                    bad("palette index out of range in row " + std::to_string(y));
                for (uint32_t k = 0; k < 3; ++k)
                    out[3 * x + k] = float(palette[3 * index + k]) / 255.0f;
            } else if (depth == 8) {
                for (uint32_t k = 0; k < channels; ++k)
                    out[x * channels + k] = float(row[x * channels + k]) / 255.0f;
            } else {
                for (uint32_t k = 0; k < channels; ++k) {
                    const size_t i = 2 * (size_t(x) * channels + k);
                    out[x * channels + k] = float(uint32_t(row[i]) << 8 | row[i + 1]) / 65535.0f;
                }
            }
        }
        img.values.insert(img.values.end(), decoded.begin(), decoded.end());
        std::swap(previous, row);
    }
    return img;
}

} // namespace limn
