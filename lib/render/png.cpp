#include "render/png.h"

#include "base/error.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace limn::render {

std::vector<uint8_t> encodePng(const Image& image) {
    if (image.channels != 1 && image.channels != 3 && image.channels != 4)
        throw Error(ErrorKind::BadInput, "PNG output needs 1, 3 or 4 channels");
    if (image.pixels.size() != size_t(image.width) * image.height * image.channels)
        throw Error(ErrorKind::BadInput, "internal: image size does not match its pixels");
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height),
                         static_cast<int>(image.channels), OIIO::TypeDesc::UINT8);
    OIIO::Filesystem::IOProxy* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    spec.attribute("png:compressionLevel", 6); // fixed, so the bytes never follow a default
    // The pixels are stored as given: OpenImageIO would otherwise treat RGBA as premultiplied
    // and divide by alpha on the way out.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    auto out = OIIO::ImageOutput::create("png");
    if (!out || !out->open("image.png", spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) || !out->close())
        throw Error(ErrorKind::BadInput,
                    "cannot encode PNG: " + (out ? out->geterror() : OIIO::geterror()));
    return {bytes.begin(), bytes.end()};
}

namespace {

Image readOpened(OIIO::ImageInput* in, const std::string& what) {
    const OIIO::ImageSpec& spec = in->spec();
    Image image;
    image.width = static_cast<uint32_t>(spec.width);
    image.height = static_cast<uint32_t>(spec.height);
    image.channels = static_cast<uint32_t>(spec.nchannels);
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, image.pixels.data()))
        throw Error(ErrorKind::BadInput, "cannot decode " + what + ": " + in->geterror());
    in->close();
    return image;
}

} // namespace

Image decodePng(std::span<const uint8_t> bytes) {
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    OIIO::ImageSpec config;
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    config.attribute("oiio:UnassociatedAlpha", 1); // the stored values, not premultiplied ones
    auto in = OIIO::ImageInput::open("image.png", &config);
    if (!in) throw Error(ErrorKind::BadInput, "cannot decode PNG: " + OIIO::geterror());
    return readOpened(in.get(), "PNG");
}

Image readImageFile(const std::string& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw Error(ErrorKind::BadInput, "cannot read the image: " + OIIO::geterror());
    return readOpened(in.get(), "the image");
}

} // namespace limn::render
