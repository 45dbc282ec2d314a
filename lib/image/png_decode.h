// limn's own PNG decoder for the common case (8/16-bit grey, grey + alpha, RGB, RGBA and 8-bit
// palette images, not interlaced, no transparency chunk): what limn-heightmap writes and most
// textures are. It spares such maps the OpenImageIO plugin (a third of a second to load); the
// rest goes to the plugin.
#pragma once

#include "image/image_file.h"

#include <cstdint>
#include <optional>
#include <span>

namespace limn {

// The image, or nullopt when the PNG uses a feature left to OpenImageIO. Throws Error(BadInput)
// for a damaged PNG (bad signature, chunk lengths, CRCs, sizes, zlib stream or filter types) and
// for images over kMaxImageValues, before allocating them.
std::optional<FloatImage> decodePngCommon(std::span<const uint8_t> bytes);

} // namespace limn
