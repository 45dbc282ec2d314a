// Height maps for the displacement examples and tests (issue: the project generates its own):
//  - Surface: 3D noise evaluated at the surface point each texel maps to (the control mesh,
//    interpolated bilinearly in each face's UV chart), so the field is continuous across UV seams
//    and any crack comes from the renderer. Islands are padded a few texels past their borders.
//  - Uv: 2D noise in UV space, unrelated across seams: the stress case for the seam fix.
// Deterministic: a fixed seed gives the same values on every machine.
#pragma once

#include "mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace limn {

enum class HeightmapKind { Surface, Uv };

struct HeightmapOptions {
    HeightmapKind kind = HeightmapKind::Surface;
    uint32_t size = 1024;     // width = height
    double frequency = 6;     // noise cycles across the mesh's bounding box (or the UV square)
    int octaves = 4;
    uint32_t seed = 1;
    uint32_t padding = 4;     // texels the surface map is extended past each island
};

// Values in [0, 1], rows top to bottom (row y holds v = 1 - (y + 0.5) / size). Throws
// Error(BadInput) when a surface map is asked of a mesh without UVs.
std::vector<float> bakeHeightmap(const Mesh& mesh, const HeightmapOptions& options);

// fBm of gradient noise in [0, 1] (3D; the 2D map uses z = 0 with wrap-around in x and y).
double fbm3(double x, double y, double z, int octaves, uint32_t seed);

} // namespace limn
