#include "blend/trim.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace limn::blend {

TrimLayout trimAtlasLayout(uint32_t faces, uint32_t tile) {
    faces = std::max(faces, 1u);
    uint32_t x = static_cast<uint32_t>(std::ceil(std::sqrt(double(faces))));
    while (uint64_t(x) * x < faces) ++x; // guard the square root's rounding
    while (x > 1 && uint64_t(x - 1) * (x - 1) >= faces) --x;
    return {x, (faces + x - 1) / x, tile};
}

TrimMask trimMaskFromImage(const Image& image, uint32_t faces) {
    TrimLayout layout = trimAtlasLayout(faces, 1);
    if (image.width % layout.tilesX != 0 || image.width == 0 ||
        uint64_t(image.width / layout.tilesX) * layout.tilesY != image.height)
        throwBadInput(
            "the trim map is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
            ", but an atlas for " + std::to_string(faces) + " faces has " +
            std::to_string(layout.tilesX) + "x" + std::to_string(layout.tilesY) +
            " square tiles: " + std::to_string(layout.tilesX) + "R x " +
            std::to_string(layout.tilesY) + "R pixels for a tile of R x R (limn-trim writes one)");
    layout.tile = image.width / layout.tilesX;
    TrimMask mask;
    mask.layout = layout;
    mask.texels.resize(size_t(image.width) * image.height);
    for (size_t i = 0; i < mask.texels.size(); ++i)
        mask.texels[i] = image.pixels[i * image.channels];
    return mask;
}

TrimTexel trimTexel(const TrimLayout& l, uint32_t face, double u, double v) {
    const uint32_t R = l.tile;
    auto cell = [R](double x) {
        return std::min(static_cast<uint32_t>(std::clamp(x, 0.0, 1.0) * R), R - 1);
    };
    return {(face % l.tilesX) * R + cell(u), (face / l.tilesX) * R + (R - 1 - cell(v))};
}

Image makeTrimAtlas(uint32_t faces, const TrimPattern& pattern) {
    if (pattern.tile < 1) throw Error(ErrorKind::Usage, "the trim tile must be at least 1 texel");
    const TrimLayout l = trimAtlasLayout(faces, pattern.tile);
    Image image;
    image.width = l.width();
    image.height = l.height();
    image.channels = 1;
    image.pixels.assign(size_t(image.width) * image.height, 0); // unused tiles: cut
    std::vector<uint8_t> removed(faces, 0);
    for (uint32_t f : pattern.removed)
        if (f < faces) removed[f] = 1;
    const uint32_t R = l.tile;
    for (uint32_t f = 0; f < faces; ++f)
        for (uint32_t j = 0; j < R; ++j)
            for (uint32_t i = 0; i < R; ++i) {
                const double u = (i + 0.5) / R, v = (j + 0.5) / R;
                const bool hole = pattern.every > 0 && f % pattern.every == 0 &&
                                  std::hypot(u - 0.5, v - 0.5) < pattern.holeRadius;
                TrimTexel t = trimTexel(l, f, u, v);
                image.pixels[size_t(t.y) * image.width + t.x] = removed[f] || hole ? 0 : 255;
            }
    return image;
}

} // namespace limn::blend
