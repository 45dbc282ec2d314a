// The image reader behind limn_image's readImageFile/readImageBytes and the EXR writer behind
// writeExr: OpenImageIO, in its own shared object so that only processes that read images load OpenImageIO's libraries
// (lib/image/CMakeLists.txt says why). Everything is caught here: nothing may unwind through C.
#include "image/plugin_abi.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

int fail(const std::string& message, char* error, size_t errorSize) {
    if (errorSize > 0) {
        size_t n = std::min(message.size(), errorSize - 1);
        std::memcpy(error, message.data(), n);
        error[n] = '\0';
    }
    return 1;
}

// libpng (under OpenImageIO) prints its errors on stderr itself ("libpng error: Invalid IHDR
// data") before OpenImageIO reports the same text. While a read runs, stderr goes to a temporary
// file; on failure that text is dropped (the error message carries it), after a successful read
// it is passed on unchanged.
class StderrCapture {
public:
    StderrCapture() {
        std::fflush(stderr);
        file_ = std::tmpfile();
        saved_ = file_ ? ::dup(STDERR_FILENO) : -1;
        if (saved_ >= 0) ::dup2(::fileno(file_), STDERR_FILENO);
    }
    ~StderrCapture() { finish(false); }
    void finish(bool passOn) {
        if (saved_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
        saved_ = -1;
        if (passOn) {
            std::rewind(file_);
            char buf[4096];
            size_t n;
            while ((n = std::fread(buf, 1, sizeof buf, file_)) > 0) std::fwrite(buf, 1, n, stderr);
        }
        std::fclose(file_);
        file_ = nullptr;
    }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;

private:
    std::FILE* file_ = nullptr;
    int saved_ = -1;
};

} // namespace

extern "C" __attribute__((visibility("default"))) int limn_image_abi_version(void) {
    return kLimnImageAbiVersion;
}

extern "C" __attribute__((visibility("default"))) int
limn_image_read(const char* path, const void* bytes, size_t size, void* context,
                LimnImageAllocate allocate, char* error, size_t errorSize) {
    StderrCapture capture;
    try {
        std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
        if (bytes) memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size);
        // The stored values: OpenImageIO would otherwise premultiply colour by alpha.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        // OpenImageIO 2.4 reads from memory only when the proxy is passed this way.
        OIIO::Filesystem::IOProxy* proxy = memory.get();
        if (proxy) config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in) {
            std::string why = OIIO::geterror();
            return fail(why.empty() ? "not an image OpenImageIO can read" : why, error, errorSize);
        }
        const OIIO::ImageSpec& spec = in->spec();
        if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
            return fail("unsupported image layout (volume or empty image)", error, errorSize);
        float* out = allocate(context, uint32_t(spec.width), uint32_t(spec.height),
                              uint32_t(spec.nchannels));
        if (!out)
            return fail("image too large: " + std::to_string(spec.width) + "x" +
                            std::to_string(spec.height) + "x" + std::to_string(spec.nchannels),
                        error, errorSize);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out))
            return fail(in->geterror(), error, errorSize);
        in->close();
        capture.finish(true);
        return 0;
    } catch (const std::exception& e) {
        return fail(e.what(), error, errorSize);
    } catch (...) {
        return fail("unknown error in the image reader", error, errorSize);
    }
}

extern "C" __attribute__((visibility("default"))) int
limn_image_write_exr(uint32_t width, uint32_t height, uint32_t channels, const char* const* names,
                     const float* pixels, void* context, LimnImageAllocateBytes allocate,
                     char* error, size_t errorSize) {
    try {
        OIIO::ImageSpec spec(int(width), int(height), int(channels), OIIO::TypeDesc::FLOAT);
        spec.channelnames.clear();
        for (uint32_t c = 0; c < channels; ++c) {
            spec.channelnames.emplace_back(names[c]);
            if (spec.channelnames.back() == "A") spec.alpha_channel = int(c);
            if (spec.channelnames.back() == "Z") spec.z_channel = int(c);
        }
        spec.attribute("compression", "zip");
        // The same bytes for the same pixels: OpenImageIO's OpenEXR writer stamps the time
        // (capDate) and its version (Software) unless told otherwise.
        spec.attribute("DateTime", "");
        spec.attribute("Software", "");
        std::vector<unsigned char> bytes;
        OIIO::Filesystem::IOVecOutput memory(bytes);
        auto out = OIIO::ImageOutput::create("image.exr");
        if (!out) return fail("OpenImageIO has no OpenEXR writer: " + OIIO::geterror(), error, errorSize);
        if (!out->supports("ioproxy") || !out->set_ioproxy(&memory))
            return fail("OpenImageIO's OpenEXR writer cannot write to memory", error, errorSize);
        if (!out->open("image.exr", spec) ||
            !out->write_image(OIIO::TypeDesc::FLOAT, pixels) || !out->close())
            return fail(out->geterror(), error, errorSize);
        uint8_t* dst = allocate(context, bytes.size());
        if (!dst) return fail("no memory for the encoded image", error, errorSize);
        std::memcpy(dst, bytes.data(), bytes.size());
        return 0;
    } catch (const std::exception& e) {
        return fail(e.what(), error, errorSize);
    } catch (...) {
        return fail("unknown error in the image writer", error, errorSize);
    }
}
