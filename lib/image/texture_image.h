// Texture and displacement maps (read by lib/image: any format OpenImageIO reads), the 16-bit
// height-map encoding, and the bilinear lookup the displacement pass does.
#pragma once

#include "image/image_file.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn {

// Throws Error(BadInput) naming the file when it cannot be read.
FloatImage loadImage(const std::string& path);

// A single-channel 16-bit PNG of values in [0, 1] (clamped), deterministic bytes.
std::vector<uint8_t> encodeGray16Png(uint32_t width, uint32_t height, std::span<const float> values);

// Bilinear lookup at (u, v) with wrap-around (repeat), texel centres at (i + 0.5) / width: the
// same arithmetic the GPU's displacement pass does (shaders/displace.comp).
float sampleBilinear(const FloatImage& image, uint32_t channel, double u, double v);

} // namespace limn
