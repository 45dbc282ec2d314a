// What limn-render writes, from what the GPU drew: the float path behind 16-bit PNG, EXR and
// --supersample. The GPU draws into an RGBA16F target in linear light (with a transparent
// background cleared to 0, so the MSAA resolve and the box filter average premultiplied colour);
// here the K x K blocks of a supersampled image are averaged (a box filter: every sample of the
// block weighs 1 / K^2, in linear light, alpha included), then encoded: sRGB 8 or 16 bits with
// straight alpha for PNG, linear premultiplied float for EXR.
#pragma once

#include "image/srgb_image.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace limn {

// Linear-light RGBA (premultiplied by alpha), rows top to bottom, and optionally the depth Z:
// the distance from the eye along the view direction (camera-space depth, world units) of the
// nearest surface in the pixel, +Inf where nothing was drawn.
struct LinearImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;  // width * height * 4
    std::vector<float> depth; // width * height, or empty
};

// 16-bit sRGB samples, like Image (channels 3 or 4).
struct Image16 {
    uint32_t width = 0, height = 0;
    uint32_t channels = 4;
    std::vector<uint16_t> samples;
};

double linearToSrgb(double linear); // IEC 61966-2-1, input clamped to 0..1
double srgbToLinear(double encoded);

// Averages each k x k block of `image` (whose size is a multiple of k) into one pixel; the depth
// takes the block's smallest value (Z is not anti-aliased: it is the nearest surface seen).
LinearImage boxFilter(const LinearImage& image, uint32_t k);

// sRGB-encoded, rounded to the nearest level; with `alpha` straight alpha (colour divided by
// alpha where it is above 0, `background` where it is 0), else RGB.
Image toSrgb8(const LinearImage& image, bool alpha, const std::vector<float>& background);
Image16 toSrgb16(const LinearImage& image, bool alpha, const std::vector<float>& background);

// limn-render's image formats, by the output's extension (case-insensitive): .png, or standard
// output ("-"), and .exr; anything else is nullopt (refused: never silently another format).
enum class ImageFormat { Png, Exr };
std::optional<ImageFormat> imageFormatFromPath(const std::string& path);
inline constexpr const char* kImageFormats = ".png (8- or 16-bit sRGB), .exr (linear float RGBA + Z)";

// IEEE 754 binary16 to float (the RGBA16F readback).
float halfToFloat(uint16_t h);

} // namespace limn
