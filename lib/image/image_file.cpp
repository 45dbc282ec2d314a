#include "image/image_file.h"

#include "base/error.h"
#include "base/io.h"
#include "image/plugin_abi.h"
#include "image/png_decode.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

namespace limn {

namespace {

struct Plugin {
    LimnImageRead read = nullptr;
    LimnImageWriteExr writeExr = nullptr;
    std::string error; // why it could not be loaded
};

std::filesystem::path pluginPath() {
    if (const char* env = std::getenv("LIMN_IMAGE_PLUGIN"); env && *env) return env;
    std::error_code ec;
    auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return LIMN_IMAGE_PLUGIN_NAME; // let dlopen search its paths
    return exe.parent_path().parent_path() / "lib" / "limn" / LIMN_IMAGE_PLUGIN_NAME;
}

const Plugin& plugin() {
    static Plugin p;
    static std::once_flag once;
    std::call_once(once, [] {
        const std::string path = pluginPath().string();
        // Never unloaded: OpenImageIO keeps threads and caches for the process's lifetime.
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            p.error = "cannot load the image reader " + path + ": " + (why ? why : "unknown");
            return;
        }
        auto version =
            reinterpret_cast<LimnImageAbiVersion>(dlsym(handle, "limn_image_abi_version"));
        p.read = reinterpret_cast<LimnImageRead>(dlsym(handle, "limn_image_read"));
        p.writeExr = reinterpret_cast<LimnImageWriteExr>(dlsym(handle, "limn_image_write_exr"));
        if (!version || !p.read || !p.writeExr || version() != kLimnImageAbiVersion) {
            p.read = nullptr;
            p.writeExr = nullptr;
            p.error = "the image reader " + path + " is not one this build of limn can use";
        }
    });
    return p;
}

float* allocate(void* context, uint32_t width, uint32_t height, uint32_t channels) {
    if (uint64_t(width) * height * channels > kMaxImageValues) return nullptr;
    auto& img = *static_cast<FloatImage*>(context);
    img.width = width;
    img.height = height;
    img.channels = channels;
    img.values.assign(size_t(width) * height * channels, 0.0f);
    return img.values.data();
}

FloatImage read(const std::string& name, const std::string& path, const uint8_t* bytes,
                size_t size) {
    auto fail = [&](ErrorKind kind, const std::string& why) {
        Error e(kind, why);
        e.setFile(name);
        throw e;
    };
    const Plugin& p = plugin();
    if (!p.read) fail(ErrorKind::Capability, p.error);
    FloatImage img;
    char error[512] = {};
    if (p.read(path.c_str(), bytes, size, &img, allocate, error, sizeof error) != 0)
        fail(ErrorKind::BadInput, std::string("cannot read image: ") + error);
    for (float v : img.values)
        if (!std::isfinite(v)) fail(ErrorKind::BadInput, "the image holds NaN or Inf values");
    return img;
}

bool isPng(std::span<const uint8_t> bytes) {
    return bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1A\n", 8) == 0;
}

uint8_t* allocateBytes(void* context, size_t size) {
    auto& bytes = *static_cast<std::vector<uint8_t>*>(context);
    bytes.resize(size);
    return bytes.data();
}

} // namespace

void requireImageWriter() {
    const Plugin& p = plugin();
    if (!p.writeExr) throw Error(ErrorKind::Capability, p.error + " (needed to write OpenEXR)");
}

std::vector<uint8_t> encodeExr(uint32_t width, uint32_t height,
                               const std::vector<std::string>& channelNames,
                               std::span<const float> values) {
    requireImageWriter();
    if (channelNames.empty() || values.size() != size_t(width) * height * channelNames.size())
        throw Error(ErrorKind::BadInput, "internal: EXR channels do not match the pixels");
    std::vector<const char*> names;
    for (const auto& n : channelNames) names.push_back(n.c_str());
    std::vector<uint8_t> bytes;
    char error[512] = {};
    if (plugin().writeExr(width, height, static_cast<uint32_t>(names.size()), names.data(),
                          values.data(), &bytes, allocateBytes, error, sizeof error) != 0)
        throw Error(ErrorKind::BadInput, std::string("cannot encode OpenEXR: ") + error);
    return bytes;
}

FloatImage readImageFile(const std::string& path) {
    // PNGs limn decodes itself skip the plugin; everything else is OpenImageIO's.
    try {
        std::vector<uint8_t> bytes = readInput(path);
        if (isPng(bytes))
            if (auto img = decodePngCommon(bytes)) return std::move(*img);
    } catch (Error& e) {
        e.setFile(path);
        throw;
    }
    return read(path, path, nullptr, 0);
}

FloatImage readImageBytes(std::span<const uint8_t> bytes, const std::string& formatName) {
    if (isPng(bytes))
        if (auto img = decodePngCommon(bytes)) return std::move(*img);
    // A null pointer would mean "read the file": an empty span still reads from memory.
    static const uint8_t none = 0;
    return read("", formatName, bytes.empty() ? &none : bytes.data(), bytes.size());
}

} // namespace limn
