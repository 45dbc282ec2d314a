#include "blend/local_surface.h"

#include "base/error.h"
#include "blend/pseudo_inverse.h"

#include <string>

namespace limn::blend {

LocalValue evaluateLocalSurface(const Coefficients& c, glm::dvec2 z) {
    // The paper's vertex-program form: per component, X ᵀ C Y and its two partials (4.2).
    const double X[3] = {1, z.x, z.x * z.x}, dX[3] = {0, 1, 2 * z.x};
    const double Y[3] = {1, z.y, z.y * z.y}, dY[3] = {0, 1, 2 * z.y};
    LocalValue out{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (uint32_t b = 0; b < 3; ++b) {
        // Row b of the sum: Σ_a c_ab X_a and Σ_a c_ab X'_a.
        glm::dvec3 cx = c[coefficientIndex(0, b)] * X[0] + c[coefficientIndex(1, b)] * X[1] +
                        c[coefficientIndex(2, b)] * X[2];
        glm::dvec3 cdx = c[coefficientIndex(1, b)] * dX[1] + c[coefficientIndex(2, b)] * dX[2];
        out.value += cx * Y[b];
        out.dx += cdx * Y[b];
        out.dy += cx * dY[b];
    }
    return out;
}

size_t ringPointCount(const Chart& chart) {
    return 2 * size_t(chart.k) + (chart.kind == VertexKind::Interior ? 0 : 1);
}

glm::dvec2 ringPointPosition(const Chart& chart, size_t n) {
    if (n == 2 * size_t(chart.k)) return chartMap(chart, chart.k - 1, 0.0, 1.0).z;
    uint32_t j = static_cast<uint32_t>(n / 2);
    return chartMap(chart, j, 1.0, n % 2 ? 1.0 : 0.0).z;
}

namespace {

double monomial(uint32_t index, glm::dvec2 z) {
    uint32_t a = index % 3, b = index / 3;
    double x = a == 0 ? 1 : a == 1 ? z.x : z.x * z.x;
    double y = b == 0 ? 1 : b == 1 ? z.y : z.y * z.y;
    return x * y;
}

// Interior: the 8 coefficients other than c_00 (indices 1..8) against the 2k ring points.
// Boundary: the 6 coefficients with a factor y (indices 3..8) against the 2k−1 interior ring
// points 1..2k−1 (e_0 and the last point are the boundary neighbours).
constexpr uint32_t kFirstInteriorUnknown = 1, kFirstBoundaryUnknown = 3;

} // namespace

const std::vector<double>& LocalSurfaceFitter::matrix(const Chart& chart) {
    auto key = std::make_tuple(chart.k, static_cast<uint8_t>(chart.kind), chart.p);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    bool interior = chart.kind == VertexKind::Interior;
    uint32_t first = interior ? kFirstInteriorUnknown : kFirstBoundaryUnknown;
    size_t unknowns = 9 - first;
    size_t begin = interior ? 0 : 1;
    size_t rows = 2 * size_t(chart.k) - begin;
    std::vector<double> m(rows * unknowns);
    for (size_t r = 0; r < rows; ++r) {
        glm::dvec2 z = ringPointPosition(chart, begin + r);
        for (size_t c = 0; c < unknowns; ++c)
            m[r * unknowns + c] = monomial(static_cast<uint32_t>(first + c), z);
    }
    return cache_.emplace(key, pseudoInverse(m, rows, unknowns)).first->second;
}

Coefficients LocalSurfaceFitter::fit(const Chart& chart, const glm::dvec3& center,
                                     std::span<const glm::dvec3> ring) {
    if (ring.size() != ringPointCount(chart))
        throwBadInput("local surface fit: " + std::to_string(ring.size()) +
                      " ring points for a chart that takes " +
                      std::to_string(ringPointCount(chart)));
    Coefficients c{};
    c[0] = center; // pinned: L(0,0) = P_v, so the surface interpolates the vertex (A.5 step 1)
    const size_t k = chart.k;
    if (chart.kind == VertexKind::Corner) {
        // A.7: a convex corner's chart is the identity; L is the bilinear interpolant of its quad.
        const glm::dvec3 &e = ring[0], &d = ring[1], &prev = ring[2];
        c[coefficientIndex(1, 0)] = e - center;
        c[coefficientIndex(0, 1)] = prev - center;
        c[coefficientIndex(1, 1)] = d - e - prev + center;
        return c;
    }
    const std::vector<double>& a = matrix(chart);
    if (chart.kind == VertexKind::Interior) {
        // A.5 step 2: c_ab = Σ_i A[ab][i] (P_i − P_v): least squares for k ≥ 5, exact for k = 4,
        // minimum-norm interpolation for k ≤ 3.
        const size_t rows = 2 * k;
        for (size_t n = 0; n < 8; ++n)
            for (size_t i = 0; i < rows; ++i) c[1 + n] += a[n * rows + i] * (ring[i] - center);
        return c;
    }
    // A.7 "boundary curve first": the boundary neighbours sit at x = +1 (e_0) and x = −1 (the
    // last point), so L(±1, 0) = P_± fixes c_10 and c_20 in closed form ...
    const glm::dvec3 &plus = ring[0], &minus = ring[2 * k];
    c[coefficientIndex(1, 0)] = (plus - minus) * 0.5;
    c[coefficientIndex(2, 0)] = (plus + minus - 2.0 * center) * 0.5;
    // ... and the 6 coefficients with a factor y fit what is left at the interior ring points.
    const size_t rows = 2 * k - 1;
    for (size_t r = 0; r < rows; ++r) {
        glm::dvec2 z = ringPointPosition(chart, 1 + r);
        glm::dvec3 residual = ring[1 + r] - (c[0] + c[1] * z.x + c[2] * (z.x * z.x));
        for (size_t n = 0; n < 6; ++n) c[3 + n] += a[n * rows + r] * residual;
    }
    return c;
}

} // namespace limn::blend
