// The manifold blending surface (math.md A.0, eq. E1; paper 001, section 3):
//     S(p) = Σ_v W_v(p) · L_v(χ_v(p)),   W_v = w_v / Σ_u w_u,
// over a consistently oriented 2-manifold quad mesh. Every point of a face lies in the charts of
// its four corners only, so a sample (face, u, v) is evaluated from 4 terms (A.6).
//
// BlendSurface holds exactly what evaluation needs, and nothing of the mesh: per vertex its chart
// and the 9 coefficients of its local surface, per face its 4 corner vertices and each corner's
// ring index. BLND (blend_chunk.h, formats/limn.md) stores the same data in f32 for a vertex
// shader (A.9).
#pragma once

#include "blend/chart.h"
#include "blend/local_surface.h"
#include "blend/weights.h"
#include "mesh/mesh.h"
#include "topology/topology.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace limn::blend {

struct BlendOptions {
    WeightKind weights = WeightKind::Cubic;
    ChartType chart = ChartType::Conformal;
};

struct BlendVertex {
    Chart chart;       // k = 0 for a vertex used by no face (never evaluated)
    Coefficients coef; // c_ab at a + 3b
};

struct BlendFace {
    std::array<uint32_t, 4> vertex; // the face's corners c0..c3 (MESH order)
    std::array<uint32_t, 4> ring;   // ring index j of this face at each corner's vertex (A.2)
};

struct BlendSurface {
    WeightKind weights = WeightKind::Cubic;
    ChartType chartType = ChartType::Conformal;
    std::vector<BlendVertex> vertices;
    std::vector<BlendFace> faces;
};

// Throws Error(BadInput) naming the first face that is not a quad, or the first non-manifold edge
// or vertex (math.md A.0: consistently oriented 2-manifold quad meshes only).
void requireManifold(const Mesh& mesh, const Topology& topo);
void requireQuads(const Mesh& mesh);

// Charts (A.3, A.7), ring indices (A.2, from Topology's counter-clockwise fans) and local surface
// fits (A.5, A.7) for every vertex. Calls requireManifold and requireQuads first.
BlendSurface buildBlendSurface(const Mesh& mesh, const Topology& topo, const BlendOptions& options);

struct SurfaceSample {
    glm::dvec3 position;
    glm::dvec3 du, dv;  // ∂S/∂u, ∂S/∂v (not meaningful exactly at an extraordinary vertex)
    glm::dvec3 normal;  // unit, or zero where the surface is degenerate
};

// Within this distance (in corner coordinates) of a face corner the sample is taken to be the
// vertex itself: position L_v(0) = P_v and normal normalize(c_10 × c_01) (A.6).
inline constexpr double kVertexEpsilon = 1e-12;

// Position, partial derivatives and normal at (face, u, v), (u,v) ∈ [0,1]² (A.6). The single-
// threaded CPU reference the paper's GPU path is compared against. Face must be < faces.size().
SurfaceSample evaluateBlendSurface(const BlendSurface& surface, uint32_t face, double u, double v);

// The weights of the four corners of a face at (u,v) (A.4), for tests and tools.
std::array<double, 4> cornerWeights(WeightKind kind, double u, double v);

} // namespace limn::blend
