// Texture and displacement maps read through OpenImageIO (any format it reads: 8/16-bit PNG,
// TIFF, EXR float, ...), kept as float values as stored (8/16-bit integers scaled to [0, 1],
// floats unchanged), rows top to bottom. Image row y holds v = 1 - (y + 0.5) / height (UVs point
// up, as in OBJ).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn::render {

struct FloatImage {
    uint32_t width = 0, height = 0, channels = 0;
    std::vector<float> values; // width * height * channels
};

// Throws Error(BadInput) naming the file when it cannot be read.
FloatImage loadImage(const std::string& path);

// A single-channel 16-bit PNG of values in [0, 1] (clamped), deterministic bytes.
std::vector<uint8_t> encodeGray16Png(uint32_t width, uint32_t height, std::span<const float> values);

// Bilinear lookup at (u, v) with wrap-around (repeat), texel centres at (i + 0.5) / width: the
// same arithmetic the GPU's displacement pass does (shaders/displace.comp).
float sampleBilinear(const FloatImage& image, uint32_t channel, double u, double v);

} // namespace limn::render
