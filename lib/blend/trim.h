// Trim masks of the blending surface (paper 001, 4.3: "a binary trim texture per face of the
// control mesh"; math.md A.8). One image, an atlas of square R×R tiles, one per face, in face
// order: tile(f) = (f mod tilesX, f div tilesX), tilesX = ceil(sqrt(F)), tilesY = ceil(F / tilesX),
// so the image is (tilesX·R) × (tilesY·R) and R follows from its size. Inside a tile u runs to the
// right and v up (the tile pictures its face with c0 at the bottom left). The fragment stage keeps
// a fragment where the nearest texel of its face's (u, v) is at least 0.5 (8-bit ≥ 128) and
// discards it elsewhere; trimming never changes positions or normals.
#pragma once

#include "image/srgb_image.h"

#include <cstdint>
#include <vector>

namespace limn::blend {

struct TrimLayout {
    uint32_t tilesX = 0, tilesY = 0;
    uint32_t tile = 0; // R
    uint32_t width() const { return tilesX * tile; }
    uint32_t height() const { return tilesY * tile; }
};

// The atlas for `faces` faces (at least 1) with R = `tile`.
TrimLayout trimAtlasLayout(uint32_t faces, uint32_t tile);

struct TrimMask {
    TrimLayout layout;
    std::vector<uint8_t> texels; // width × height, rows top to bottom: the image's first channel
};

// Throws Error(BadInput) naming the size an atlas for `faces` faces must have when `image` is not
// one (its width a multiple of tilesX, its height tilesY times the tile).
TrimMask trimMaskFromImage(const Image& image, uint32_t faces);

// The texel (column, row from the top) that face f samples at (u, v) ∈ [0,1]², as blend.frag does.
struct TrimTexel {
    uint32_t x, y;
};
TrimTexel trimTexel(const TrimLayout& layout, uint32_t face, double u, double v);

// What limn-trim draws: every `every`-th face (f mod every == 0) gets a round hole of
// `holeRadius` (in face parameters, centred at (0.5, 0.5)); `removed` faces are cut away whole.
// Texels are 0 (cut) or 255 (kept), tested at their centres; one grey channel.
struct TrimPattern {
    uint32_t tile = 32;
    double holeRadius = 0.3;
    uint32_t every = 1;
    std::vector<uint32_t> removed;
};
Image makeTrimAtlas(uint32_t faces, const TrimPattern& pattern);

} // namespace limn::blend
