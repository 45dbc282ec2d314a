// The local surface of a vertex: a biquadratic in its chart coordinates (math.md A.5, eq. E4;
// paper 001, 3.3 "지역 곡면", after Yoon 2006: "2 vectors and 1 matrix"),
//     L(x,y) = X(x)ᵀ · C · Y(y),  X = (1, x, x²)ᵀ,  Y = (1, y, y²)ᵀ,  C = [c_ab], c_ab ∈ ℝ³,
// and its fit to the one-ring: c_00 pinned to the vertex, the other coefficients by the
// pseudo-inverse (A.5), boundary vertices "boundary curve first" (A.7), corners bilinear.
#pragma once

#include "blend/chart.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <tuple>
#include <vector>

namespace limn::blend {

// c_ab is stored at index a + 3b (x-power a, y-power b).
using Coefficients = std::array<glm::dvec3, 9>;
inline constexpr uint32_t coefficientIndex(uint32_t a, uint32_t b) { return a + 3 * b; }

struct LocalValue {
    glm::dvec3 value; // L(x,y)
    glm::dvec3 dx;    // ∂L/∂x
    glm::dvec3 dy;    // ∂L/∂y
};
LocalValue evaluateLocalSurface(const Coefficients& c, glm::dvec2 z);

// The one-ring points a fit takes, in this order (A.5, A.7): for each ring index j the edge
// neighbour e_j (corner c_{i+1} of ring[j]) then the diagonal d_j (c_{i+2}); boundary and corner
// charts add the last boundary neighbour (c_{i−1} of ring[k−1]). So 2k or 2k+1 points.
size_t ringPointCount(const Chart& chart);
// Where the fit places ring point n in the chart (e_j at χ(j;1,0), d_j at χ(j;1,1), the last
// boundary neighbour at χ(k−1;0,1)).
glm::dvec2 ringPointPosition(const Chart& chart, size_t n);

// Fits local surfaces. The fit is linear in the points, so the matrix for each chart shape
// (k, kind, p) is computed once and reused (A.9: "per-valence fit matrices").
class LocalSurfaceFitter {
public:
    Coefficients fit(const Chart& chart, const glm::dvec3& center,
                     std::span<const glm::dvec3> ring);

private:
    const std::vector<double>& matrix(const Chart& chart);
    std::map<std::tuple<uint32_t, uint8_t, double>, std::vector<double>> cache_;
};

} // namespace limn::blend
