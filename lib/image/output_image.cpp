#include "image/output_image.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace limn {

double linearToSrgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::optional<ImageFormat> imageFormatFromPath(const std::string& path) {
    if (path == "-") return ImageFormat::Png;
    const auto slash = path.find_last_of('/');
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::nullopt;
    std::string ext = path.substr(dot + 1);
    for (char& c : ext)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    if (ext == "png") return ImageFormat::Png;
    if (ext == "exr") return ImageFormat::Exr;
    return std::nullopt;
}

float halfToFloat(uint16_t h) {
    const uint32_t sign = uint32_t(h >> 15) << 31;
    const uint32_t exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
    float value;
    if (exponent == 0) { // zero or subnormal: mantissa * 2^-24, exact in float
        value = std::ldexp(float(mantissa), -24);
    } else if (exponent == 31) {
        value = mantissa ? std::numeric_limits<float>::quiet_NaN()
                         : std::numeric_limits<float>::infinity();
    } else {
        uint32_t bits = ((exponent + 112) << 23) | (mantissa << 13);
        std::memcpy(&value, &bits, 4);
    }
    uint32_t bits;
    std::memcpy(&bits, &value, 4);
    bits |= sign;
    std::memcpy(&value, &bits, 4);
    return value;
}

LinearImage boxFilter(const LinearImage& image, uint32_t k) {
    if (k <= 1) return image;
    if (image.width % k || image.height % k)
        throw Error(ErrorKind::BadInput, "internal: supersampled size is not a multiple of K");
    LinearImage out;
    out.width = image.width / k;
    out.height = image.height / k;
    out.rgba.assign(size_t(out.width) * out.height * 4, 0.0f);
    const bool depth = !image.depth.empty();
    if (depth) out.depth.assign(size_t(out.width) * out.height, std::numeric_limits<float>::infinity());
    const double weight = 1.0 / (double(k) * k);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            double sum[4] = {0, 0, 0, 0};
            float nearest = std::numeric_limits<float>::infinity();
            // A fixed order of additions in double: the same bytes every run.
            for (uint32_t j = 0; j < k; ++j)
                for (uint32_t i = 0; i < k; ++i) {
                    const size_t s = size_t(y * k + j) * image.width + (x * k + i);
                    for (int c = 0; c < 4; ++c) sum[c] += image.rgba[4 * s + c];
                    if (depth) nearest = std::min(nearest, image.depth[s]);
                }
            const size_t o = size_t(y) * out.width + x;
            for (int c = 0; c < 4; ++c) out.rgba[4 * o + c] = float(sum[c] * weight);
            if (depth) out.depth[o] = nearest;
        }
    return out;
}

namespace {

// Straight (unassociated) sRGB-encoded values 0..1 of pixel i.
void encodePixel(const LinearImage& image, size_t i, bool alpha, const std::vector<float>& background,
                 double out[4]) {
    const float* p = &image.rgba[4 * i];
    const double a = std::clamp(double(p[3]), 0.0, 1.0);
    for (int c = 0; c < 3; ++c) {
        double linear = p[c];
        if (alpha) linear = a > 0 ? linear / a : background[c];
        out[c] = linearToSrgb(linear);
    }
    out[3] = a;
}

// Every pixel encoded (encodePixel) and scaled to integer samples 0 .. maxValue.
template <typename Sample>
void encodeSamples(const LinearImage& image, bool alpha, const std::vector<float>& background,
                   double maxValue, uint32_t channels, std::vector<Sample>& out) {
    const size_t n = size_t(image.width) * image.height;
    out.resize(n * channels);
    for (size_t i = 0; i < n; ++i) {
        double v[4];
        encodePixel(image, i, alpha, background, v);
        for (uint32_t c = 0; c < channels; ++c) out[i * channels + c] = static_cast<Sample>(std::lround(v[c] * maxValue));
    }
}

// The encoded image (Image or Image16), RGB or RGBA, whose samples are the member `samples`.
template <typename Encoded, typename Sample>
Encoded encodeImage(const LinearImage& image, bool alpha, const std::vector<float>& background,
                    double maxValue, std::vector<Sample> Encoded::*samples) {
    Encoded out;
    out.width = image.width;
    out.height = image.height;
    out.channels = alpha ? 4 : 3;
    encodeSamples(image, alpha, background, maxValue, out.channels, out.*samples);
    return out;
}

} // namespace

Image toSrgb8(const LinearImage& image, bool alpha, const std::vector<float>& background) {
    return encodeImage(image, alpha, background, 255.0, &Image::pixels);
}

Image16 toSrgb16(const LinearImage& image, bool alpha, const std::vector<float>& background) {
    return encodeImage(image, alpha, background, 65535.0, &Image16::samples);
}

} // namespace limn
