// The blending surface as the GPU draws it (paper 001, 4.1-4.2; math.md A.6, A.9), prepared on the
// CPU once: the BLND records as the shaders read them, and the shared-grid tessellation.
//
// Every face is a grid of K×K cells, grid point (i, j) at face parameters (u, v) = (i/K, j/K)
// (`--grid K`). A point on a mesh edge or at a mesh vertex belongs to several faces; it is
// evaluated once, by its *owner* — the lowest-numbered drawn face that contains it — and every
// face refers to that one evaluation (brief, "Watertight to the bit"; docs/blend.md explains why a
// symmetric evaluation is not enough: the two faces' parameters differ in the last bit).
//
//   points        the surface points, each once: (owner face, i, j). The --eval compute pass and
//                 --mesh-out evaluate these.
//   drawVertices  (K+1)² per drawn face, row-major in (i, j): which point it is, and which face
//                 it is drawn for, so a triangle knows its own face's (u, v) for trimming (A.8).
//   triangles     2K² per drawn face, counter-clockwise in (u, v), into drawVertices.
//
// Faces tagged as holes are not drawn (as with the other surfaces) and own nothing.
#pragma once

#include "blend/blend_surface.h"
#include "mesh/mesh.h"
#include "render/camera.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace limn::render {

struct GpuBlendVertex { // mirrors BlendVertex in shaders/blend_eval.glsl (and BLND's record)
    uint32_t k, kind;
    float theta, p, q;
    float coef[27]; // coef[9c + a + 3b]: coordinate c of c_ab
};
static_assert(sizeof(GpuBlendVertex) == 128);

struct GpuBlendFace { // mirrors BlendFace in shaders/blend_eval.glsl (and BLND's record)
    uint32_t vertex[4];
    uint32_t ring[4];
};
static_assert(sizeof(GpuBlendFace) == 32);

// A surface point: its owner face and grid position, i | j << 16. Mirrors uvec2 in blend_eval.comp.
struct GpuBlendPoint {
    uint32_t face, ij;
};
static_assert(sizeof(GpuBlendPoint) == 8);

// One corner of the grid of a drawn face. Mirrors uvec4 in blend.vert / blend_fetch.vert.
struct GpuBlendDrawVertex {
    uint32_t point;     // index into points: where the evaluated position and normal are
    uint32_t pointFace; // = points[point]: what the vertex stage evaluates (--eval vertex)
    uint32_t pointIJ;
    uint32_t face; // the face this grid is drawn for
};
static_assert(sizeof(GpuBlendDrawVertex) == 16);

inline constexpr uint32_t kMaxBlendGrid = 1024;

struct BlendDraw {
    uint32_t grid = 16; // K: cells per face side
    blend::WeightKind weights = blend::WeightKind::Cubic;
    std::vector<GpuBlendVertex> vertices; // BLND vertex records, in MESH vertex order
    std::vector<GpuBlendFace> faces;      // BLND face records, in MESH face order
    std::vector<GpuBlendPoint> points;
    std::vector<GpuBlendDrawVertex> drawVertices;
    std::vector<uint32_t> triangles; // 3 per triangle, into drawVertices
    std::vector<uint32_t> wireLines; // 2 per segment, into points: every drawn mesh edge once
    std::vector<glm::vec2> faceUVs;  // 4 per face: the mesh UVs of its corners; one zero without
    uint32_t drawnFaces = 0;
    bool hasUVs = false;
    Bounds bounds; // of the control points
};

// (u, v) of grid point `ij` (i | j << 16) on a K-grid, computed as the shaders do (f32 division).
inline float blendGridParam(uint32_t index, uint32_t grid) {
    return static_cast<float>(index) / static_cast<float>(grid);
}

// `surface` must describe `mesh` (blend::loadBlendSurface checks it). Throws Error(Usage) for a
// grid outside 1..kMaxBlendGrid and Error(BadInput) when the buffers would exceed the 128 MiB
// storage-buffer limit.
BlendDraw prepareBlend(const Mesh& mesh, const blend::BlendSurface& surface, uint32_t grid);

} // namespace limn::render
