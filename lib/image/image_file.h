// Reading texture and displacement maps in any format OpenImageIO reads (8/16-bit PNG, TIFF, EXR
// float, ...), and encoding OpenEXR (limn-render -o x.exr). OpenImageIO lives in a plugin (limn_image_oiio.so, lib/image/CMakeLists.txt says
// why) found at <directory of the executable>/../lib/limn/, or at $LIMN_IMAGE_PLUGIN.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn {

// Channel values as float: 8/16-bit integers scaled to [0, 1], floats as stored (alpha not
// premultiplied); rows top to bottom. Image row y holds v = 1 - (y + 0.5) / height (UVs point up,
// as in OBJ).
struct FloatImage {
    uint32_t width = 0, height = 0, channels = 0;
    std::vector<float> values; // width * height * channels
};

// The most values (width * height * channels) a map may hold: 2^28 floats, 1 GiB.
inline constexpr uint64_t kMaxImageValues = uint64_t(1) << 28;

// Throw Error(BadInput) naming the file when it cannot be read, is too large or holds NaN/Inf;
// Error(Capability) when the reader plugin cannot be loaded.
FloatImage readImageFile(const std::string& path);
// `formatName` is a file name whose extension names the format, e.g. "image.png".
FloatImage readImageBytes(std::span<const uint8_t> bytes, const std::string& formatName);

// Throws Error(Capability) when the plugin (and so the OpenEXR writer) cannot be loaded: callers
// check before any work, so that a missing plugin writes nothing.
void requireImageWriter();
// An OpenEXR file's bytes: 32-bit float channels named `channelNames` ("R", "G", "B", "A", "Z"),
// rows top to bottom, ZIP compression. Throws Error(Capability) as above, Error(BadInput) when
// OpenImageIO fails.
std::vector<uint8_t> encodeExr(uint32_t width, uint32_t height,
                               const std::vector<std::string>& channelNames,
                               std::span<const float> values);

} // namespace limn
