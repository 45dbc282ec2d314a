#include "render/texture_image.h"

#include "base/error.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace limn::render {

FloatImage loadImage(const std::string& path) {
    auto fail = [&](const std::string& why) {
        Error e(ErrorKind::BadInput, "cannot read image: " + why);
        e.setFile(path);
        throw e;
    };
    auto in = OIIO::ImageInput::open(path);
    if (!in) fail(OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
        fail("unsupported image layout");
    if (uint64_t(spec.width) * spec.height * spec.nchannels > (1ull << 28)) fail("image too large");
    FloatImage img;
    img.width = static_cast<uint32_t>(spec.width);
    img.height = static_cast<uint32_t>(spec.height);
    img.channels = static_cast<uint32_t>(spec.nchannels);
    img.values.resize(size_t(img.width) * img.height * img.channels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.values.data()))
        fail(in->geterror());
    in->close();
    for (float v : img.values)
        if (!std::isfinite(v)) fail("the image holds NaN or Inf values");
    return img;
}

std::vector<uint8_t> encodeGray16Png(uint32_t width, uint32_t height, std::span<const float> values) {
    std::vector<uint16_t> pixels(values.size());
    for (size_t i = 0; i < values.size(); ++i)
        pixels[i] = static_cast<uint16_t>(std::lround(std::clamp(values[i], 0.0f, 1.0f) * 65535.0f));
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 1, OIIO::TypeDesc::UINT16);
    OIIO::Filesystem::IOProxy* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    spec.attribute("png:compressionLevel", 6);
    auto out = OIIO::ImageOutput::create("png");
    if (!out || !out->open("map.png", spec) ||
        !out->write_image(OIIO::TypeDesc::UINT16, pixels.data()) || !out->close())
        throw Error(ErrorKind::BadInput, "cannot encode PNG: " + (out ? out->geterror() : OIIO::geterror()));
    return {bytes.begin(), bytes.end()};
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
    auto at = [&](uint32_t xx, uint32_t yy) { return img.values[(size_t(yy) * img.width + xx) * img.channels + channel]; };
    float top = at(x0, y0) + fx * (at(x1, y0) - at(x0, y0));
    float bottom = at(x0, y1) + fx * (at(x1, y1) - at(x0, y1));
    return top + fy * (bottom - top);
}

} // namespace limn::render
