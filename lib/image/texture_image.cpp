#include "image/texture_image.h"

#include "base/error.h"

#include "image/png_encode.h"

#include <algorithm>
#include <cmath>

namespace limn {

FloatImage loadImage(const std::string& path) {
    return readImageFile(path);
}

std::vector<uint8_t> encodeGray16Png(uint32_t width, uint32_t height,
                                     std::span<const float> values) {
    std::vector<uint16_t> samples(values.size());
    for (size_t i = 0; i < values.size(); ++i)
        samples[i] =
            static_cast<uint16_t>(std::lround(std::clamp(values[i], 0.0f, 1.0f) * 65535.0f));
    return encodePngGray16(width, height, samples);
}

float sampleBilinear(const FloatImage& img, uint32_t channel, double u, double v) {
    // Same operations, in the same order and precision, as displace.comp.
    float x = float(u) * float(img.width) - 0.5f;
    float y = (1.0f - float(v)) * float(img.height) - 0.5f;
    float fx0 = std::floor(x), fy0 = std::floor(y);
    float fx = x - fx0, fy = y - fy0;
    auto wrap = [](float i, uint32_t n) {
        long long k = static_cast<long long>(i) % static_cast<long long>(n);
        return static_cast<uint32_t>(k < 0 ? k + n : k);
    };
    uint32_t x0 = wrap(fx0, img.width), x1 = wrap(fx0 + 1.0f, img.width);
    uint32_t y0 = wrap(fy0, img.height), y1 = wrap(fy0 + 1.0f, img.height);
    auto at = [&](uint32_t xx, uint32_t yy) {
        return img.values[(size_t(yy) * img.width + xx) * img.channels + channel];
    };
    float top = at(x0, y0) + fx * (at(x1, y0) - at(x0, y0));
    float bottom = at(x0, y1) + fx * (at(x1, y1) - at(x0, y1));
    return top + fy * (bottom - top);
}

} // namespace limn
