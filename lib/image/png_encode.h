// limn's own PNG encoder: every image limn writes goes through it, so the bytes depend only on
// the pixels and zlib (no time stamps, no software text, a fixed filter choice and compression
// level), and writing a PNG does not load OpenImageIO.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace limn {

// 8-bit samples, `channels` 1 (grey), 2 (grey + alpha), 3 (RGB) or 4 (RGBA), rows top to bottom,
// tightly packed. The PNG carries an sRGB chunk (rendering intent perceptual): the samples are
// sRGB-encoded.
std::vector<uint8_t> encodePng8(uint32_t width, uint32_t height, uint32_t channels,
                                std::span<const uint8_t> samples);
// 16-bit samples, `channels` 1 to 4 as above, sRGB-encoded like encodePng8's (the sRGB chunk
// applies to any bit depth), written big-endian as PNG requires.
std::vector<uint8_t> encodePng16(uint32_t width, uint32_t height, uint32_t channels,
                                 std::span<const uint16_t> samples);
// 16-bit grey samples (height maps), rows top to bottom. No colour-space chunk: the values are
// data, not colours.
std::vector<uint8_t> encodePngGray16(uint32_t width, uint32_t height,
                                     std::span<const uint16_t> samples);

} // namespace limn
