// 8-bit sRGB images and their PNG encoding (lib/image's own encoder: IHDR, sRGB, IDAT, IEND; no
// time stamp, software or version text, tests/render pins the chunk list).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn {

struct Image {
    uint32_t width = 0, height = 0;
    uint32_t channels = 4;       // 3 (RGB) or 4 (RGBA); 1 (grey) for masks
    std::vector<uint8_t> pixels; // rows top to bottom, tightly packed

    const uint8_t* at(uint32_t x, uint32_t y) const {
        return pixels.data() + (size_t(y) * width + x) * channels;
    }
};

std::vector<uint8_t> encodePng(const Image& image);
struct Image16;
std::vector<uint8_t> encodePng(const Image16& image); // 16 bits per sample, sRGB-encoded
// Throws Error(BadInput) when the bytes are not a PNG OpenImageIO can read (through lib/image's
// plugin; Error(Capability) when that cannot be loaded). Any bit depth is converted to 8 bits;
// the channel count is kept.
Image decodePng(std::span<const uint8_t> bytes);
// Any image file OpenImageIO reads (PNG, TIFF, OpenEXR, ...), converted to 8 bits per channel.
// Throws Error(BadInput) with OpenImageIO's reason.
Image readImageFile8(const std::string& path);

} // namespace limn
