// Weight functions of the blending surface (math.md A.4, eq. E3; paper 001, 3.4 "Hermite spline").
// Restricted to a face, the weight of the vertex at corner i is h(s_i)·h(t_i) in that corner's
// coordinates (chart.h). Both steps below satisfy h(0)=1, h(1)=0, h'(0)=h'(1)=0 and
// h(x)+h(1−x)=1, so the four weights of a face sum to exactly one (A.4).
#pragma once

#include <algorithm>
#include <cstdint>

namespace limn::blend {

// Stored in BLND (formats/limn.md), so the values are part of the format.
enum class WeightKind : uint8_t {
    Cubic = 0,   // h(x) = 1 − 3x² + 2x³ (smoothstep): surface C¹
    Quintic = 1, // h(x) = 1 − 10x³ + 15x⁴ − 6x⁵ (smootherstep): surface C²
};

struct StepValue {
    double h;  // h(x)
    double dh; // h'(x)
};

// h and h' at x, clamped to [0, 1] (outside the unit interval the weight is constant).
inline StepValue hermiteStep(WeightKind kind, double x) {
    x = std::clamp(x, 0.0, 1.0);
    const double x2 = x * x;
    if (kind == WeightKind::Quintic) {
        // 1 − x³(10 − 15x + 6x²);  h' = −30x²(1 − x)²
        double h = 1.0 - x2 * x * (10.0 - 15.0 * x + 6.0 * x2);
        double omx = 1.0 - x;
        return {h, -30.0 * x2 * omx * omx};
    }
    // 1 − x²(3 − 2x);  h' = −6x(1 − x)
    return {1.0 - x2 * (3.0 - 2.0 * x), -6.0 * x * (1.0 - x)};
}

} // namespace limn::blend
