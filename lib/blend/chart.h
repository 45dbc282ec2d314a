// Face/corner coordinates and vertex charts of the blending surface (math.md A.1-A.3; paper 001,
// 3.2 "차트": the one-ring of a vertex is opened into the complex plane by a rotation and a
// conformal power map that depend only on the valence).
//
// Face F = (c0,c1,c2,c3), counter-clockwise, parameters (u,v) ∈ [0,1]² with c0=(0,0), c1=(1,0),
// c2=(1,1), c3=(0,1). Corner i has coordinates (s,t) with the corner at the origin, s along the
// edge c_i→c_{i+1}, t along c_i→c_{i−1} (A.1). The chart of a vertex with k faces maps the corner
// (s,t) of the face with ring index j (A.2) to
//     z = r^p (cos Φ, sin Φ),   r = |(s,t)|,  Φ = q·atan2(t,s) + j·Θ/k,  q = 2Θ/(πk)      (E2)
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>

namespace limn::blend {

// A 2×2 matrix, row-major: [[m00, m01], [m10, m11]]. Jacobians ∂(x,y)/∂(s,t) have the derivative
// of the first output in the first row.
struct Mat2 {
    double m00 = 1, m01 = 0, m10 = 0, m11 = 1;
};
inline Mat2 operator*(const Mat2& a, const Mat2& b) {
    return {a.m00 * b.m00 + a.m01 * b.m10, a.m00 * b.m01 + a.m01 * b.m11,
            a.m10 * b.m00 + a.m11 * b.m10, a.m10 * b.m01 + a.m11 * b.m11};
}

// A.1 table: (s,t) of corner i from the face parameters, the inverse, and J_i = ∂(s,t)/∂(u,v).
glm::dvec2 cornerFromFace(uint32_t corner, double u, double v);
glm::dvec2 faceFromCorner(uint32_t corner, double s, double t);
Mat2 cornerJacobian(uint32_t corner);

// How the chart of a vertex is opened (A.3, A.7); stored in BLND (formats/limn.md).
enum class VertexKind : uint8_t {
    Interior = 0, // full disk, Θ = 2π
    Boundary = 1, // boundary vertex with k ≥ 2 faces: half disk, Θ = π
    Corner = 2,   // boundary vertex with one face (convex corner): Θ = π/2, the identity chart
};

// The radial exponent p of interior charts (A.3); boundary and corner charts are always
// conformal (A.7).
enum class ChartType : uint8_t {
    Conformal = 0,         // p = q: z = e^{iΦ₀} ζ^{4/k}, the paper's map (default)
    CharacteristicMap = 1, // p = log₂(1/λ_k), λ_k Catmull–Clark's subdominant eigenvalue (YZ04)
    Isodistance = 2,       // p = 1: only the angle changes
};

struct Chart {
    uint32_t k = 0; // faces around the vertex
    VertexKind kind = VertexKind::Interior;
    double theta = 0; // total angle Θ
    double p = 1, q = 1;
};

// log₂(1/λ_k) with λ_k = (5 + cos(2π/k) + cos(π/k)·√(2(9 + cos(2π/k))))/16 (A.3, math.md C).
double characteristicExponent(uint32_t k);

// The chart of a vertex with k faces (k ≥ 2 for Interior and Boundary, k = 1 for Corner).
// Throws Error(BadInput) for impossible combinations.
Chart makeChart(uint32_t k, VertexKind kind, ChartType type);

// z = χ(j; s, t) and its Jacobian ∂(x,y)/∂(s,t) (A.3). The Jacobian needs r > 0; at r = 0 it is
// returned as zero (the evaluator special-cases the vertex itself, A.6).
struct ChartValue {
    glm::dvec2 z;
    Mat2 jacobian;
};
ChartValue chartMap(const Chart& chart, uint32_t ringIndex, double s, double t);

// The inverse of the chart on the image of the star (A.3): ring index and corner coordinates.
struct ChartPreimage {
    uint32_t ringIndex;
    double s, t;
};
ChartPreimage chartInverse(const Chart& chart, glm::dvec2 z);

} // namespace limn::blend
