#include "image/srgb_image.h"

#include "base/error.h"
#include "image/image_file.h"
#include "image/png_encode.h"
#include "image/output_image.h"

#include <algorithm>
#include <cmath>

namespace limn {

namespace {

// Floats from lib/image to 8 bits: 8-bit samples come back as k / 255 exactly, so rounding
// restores k; deeper samples round to the nearest 8-bit value.
Image toEightBit(const FloatImage& f, const std::string& what) {
    if (f.channels > 4)
        throw Error(ErrorKind::BadInput, "cannot decode " + what + ": more than 4 channels");
    Image image;
    image.width = f.width;
    image.height = f.height;
    image.channels = f.channels;
    image.pixels.resize(f.values.size());
    for (size_t i = 0; i < f.values.size(); ++i)
        image.pixels[i] =
            static_cast<uint8_t>(std::lround(std::clamp(f.values[i], 0.0f, 1.0f) * 255.0f));
    return image;
}

} // namespace

std::vector<uint8_t> encodePng(const Image& image) {
    if (image.channels != 1 && image.channels != 3 && image.channels != 4)
        throw Error(ErrorKind::BadInput, "PNG output needs 1, 3 or 4 channels");
    if (image.pixels.size() != size_t(image.width) * image.height * image.channels)
        throw Error(ErrorKind::BadInput, "internal: image size does not match its pixels");
    return encodePng8(image.width, image.height, image.channels, image.pixels);
}

std::vector<uint8_t> encodePng(const Image16& image) {
    if (image.channels != 1 && image.channels != 3 && image.channels != 4)
        throw Error(ErrorKind::BadInput, "PNG output needs 1, 3 or 4 channels");
    if (image.samples.size() != size_t(image.width) * image.height * image.channels)
        throw Error(ErrorKind::BadInput, "internal: image size does not match its pixels");
    return encodePng16(image.width, image.height, image.channels, image.samples);
}

Image decodePng(std::span<const uint8_t> bytes) {
    return toEightBit(readImageBytes(bytes, "image.png"), "PNG");
}

Image readImageFile8(const std::string& path) {
    return toEightBit(limn::readImageFile(path), "the image");
}

} // namespace limn
