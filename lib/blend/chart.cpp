#include "blend/chart.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace limn::blend {

glm::dvec2 cornerFromFace(uint32_t corner, double u, double v) {
    switch (corner & 3u) {
    case 0: return {u, v};
    case 1: return {v, 1.0 - u};
    case 2: return {1.0 - u, 1.0 - v};
    default: return {1.0 - v, u};
    }
}

glm::dvec2 faceFromCorner(uint32_t corner, double s, double t) {
    switch (corner & 3u) {
    case 0: return {s, t};
    case 1: return {1.0 - t, s};
    case 2: return {1.0 - s, 1.0 - t};
    default: return {t, 1.0 - s};
    }
}

Mat2 cornerJacobian(uint32_t corner) {
    switch (corner & 3u) {
    case 0: return {1, 0, 0, 1};
    case 1: return {0, 1, -1, 0};
    case 2: return {-1, 0, 0, -1};
    default: return {0, -1, 1, 0};
    }
}

double characteristicExponent(uint32_t k) {
    const double pi = std::numbers::pi;
    double c = std::cos(2 * pi / k);
    double lambda = (5 + c + std::cos(pi / k) * std::sqrt(2 * (9 + c))) / 16;
    return std::log2(1 / lambda);
}

Chart makeChart(uint32_t k, VertexKind kind, ChartType type) {
    const double pi = std::numbers::pi;
    Chart c;
    c.k = k;
    c.kind = kind;
    switch (kind) {
    case VertexKind::Interior:
        if (k < 2) throwBadInput("an interior vertex needs at least 2 faces, got " + std::to_string(k));
        c.theta = 2 * pi;
        break;
    case VertexKind::Boundary:
        if (k < 2) throwBadInput("a boundary chart needs at least 2 faces, got " + std::to_string(k));
        c.theta = pi;
        break;
    case VertexKind::Corner:
        if (k != 1) throwBadInput("a corner chart has exactly 1 face, got " + std::to_string(k));
        c.theta = pi / 2;
        break;
    }
    c.q = 2 * c.theta / (pi * k); // each quad corner (π/2) opens to Θ/k
    c.p = c.q;                    // conformal
    if (kind == VertexKind::Interior) {
        if (type == ChartType::CharacteristicMap) c.p = characteristicExponent(k);
        if (type == ChartType::Isodistance) c.p = 1.0;
    }
    return c;
}

ChartValue chartMap(const Chart& c, uint32_t j, double s, double t) {
    double r = std::hypot(s, t);
    double phi = c.q * std::atan2(t, s) + j * c.theta / c.k;
    double cp = std::cos(phi), sp = std::sin(phi);
    double rp = std::pow(r, c.p);
    ChartValue out{{rp * cp, rp * sp}, {0, 0, 0, 0}};
    if (r > 0) {
        // ∂z/∂(s,t) = ∂z/∂r ⊗ ∂r/∂(s,t) + ∂z/∂θ ⊗ ∂θ/∂(s,t)   (A.3)
        double dr = c.p * rp / r;   // |∂z/∂r|
        double dth = c.q * rp;      // |∂z/∂θ|
        double rs = s / r, rt = t / r;             // ∂r/∂s, ∂r/∂t
        double ts = -t / (r * r), tt = s / (r * r); // ∂θ/∂s, ∂θ/∂t
        out.jacobian = {dr * cp * rs - dth * sp * ts, dr * cp * rt - dth * sp * tt,
                        dr * sp * rs + dth * cp * ts, dr * sp * rt + dth * cp * tt};
    }
    return out;
}

ChartPreimage chartInverse(const Chart& c, glm::dvec2 z) {
    const double twoPi = 2 * std::numbers::pi;
    double phi = std::atan2(z.y, z.x);
    if (phi < 0) {
        // A point on the positive real axis may come back as −0 or −1e-17 (boundary charts).
        if (c.kind != VertexKind::Interior && phi > -1e-12)
            phi = 0;
        else
            phi += twoPi;
    }
    double sector = c.theta / c.k;
    uint32_t j = static_cast<uint32_t>(std::min<double>(std::floor(phi / sector), c.k - 1));
    double theta = (phi - j * sector) / c.q;
    double r = std::pow(std::hypot(z.x, z.y), 1 / c.p);
    return {j, r * std::cos(theta), r * std::sin(theta)};
}

} // namespace limn::blend
