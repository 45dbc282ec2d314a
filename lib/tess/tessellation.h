// The tessellation that limn-render draws: every point of the surface grid exactly once, with
// one owner that evaluates it, and triangles joining them built from topology (brief,
// "Watertight to the bit"). A level-l patch gets min(2^(N-l), cap) segments per side (paper 000,
// 4.3); where neighbours differ (the cap), the finer side's edge vertices are stitched into the
// coarser element, so there is never a T-junction. Shared points are shared vertices, so both
// sides use the same bits.
#pragma once

#include "mesh/mesh.h"
#include "subdiv/tables.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <span>

#include <cstdint>
#include <vector>

namespace limn {

// A surface point: `element` is a patch index (< patches.size()) or patches.size() + the index
// of an irregular face; (s, t) are element-local parameters in units of 1/32768.
struct TessVertex {
    uint32_t element;
    uint16_t s, t;
};
inline constexpr uint32_t kTessParamOne = 32768;

struct Tessellation {
    std::vector<TessVertex> vertices;
    // With UV splitting: per vertex, the UV in the chart of the element that made it, and the
    // vertex whose position it shares (itself for the first; UV-seam copies name the first).
    // Copies keep the first one's (element, s, t), so they evaluate to the same bits.
    std::vector<glm::vec2> uvs;
    // With UVs: per vertex, the element point the UV was evaluated at (the vertex's own, or for
    // a copy the element and point in the chart it was made for).
    std::vector<TessVertex> uvSources;
    std::vector<uint32_t> geometry;
    std::vector<uint32_t> indices; // triangles, counter-clockwise in (u, v)
    std::vector<uint32_t> segments; // per element: segments per side of its own grid
    std::vector<uint32_t> triangleCounts; // per element: its triangles, emitted in element order
    std::vector<uint32_t> outline;  // 2 per segment: every element's boundary (shared ones twice)
    uint32_t stitchedEdges = 0;     // element edges that needed stitching
};

// `cap` limits the segments per side of any element (>= 1; rounded down to a power of two so
// that neighbouring grids nest). With `splitUVSeams` (the mesh must
// have UVs), a point whose faces give it different UVs gets one vertex per distinct UV, so
// textures and displacement can be looked up per side; all copies share the first's geometry.
// UVs are the linear charts (face-varying rule "all"), or with `smooth` the smooth face-varying
// surface's (at the same depth as `tables`).
class ChartUVs;
Tessellation buildTessellation(const Mesh& mesh, const Tables& tables, uint32_t cap,
                               bool splitUVSeams = false, ChartUVs* smooth = nullptr);

// The ptex face and (u, v) of a tessellation vertex.
struct PtexPoint {
    uint32_t ptex;
    double u, v;
};
PtexPoint ptexOf(const Tables& tables, const TessVertex& v);

} // namespace limn

namespace limn {

// CPU reference of what the renderer's vertex stage computes for each tessellation vertex:
// the B-spline of its patch, or the bilinear blend of its irregular face's limit points
// (normals blended and renormalized). `vertices` and `limits` from subdiv/evaluate.h.
struct LimitPoint;
struct TessPoint {
    glm::dvec3 position, normal;
};
std::vector<TessPoint> evaluateTessellation(const Tables& tables, const Tessellation& tess,
                                            std::span<const glm::dvec3> vertices,
                                            std::span<const LimitPoint> limits);

} // namespace limn
