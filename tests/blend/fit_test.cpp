// Local-surface fits (math.md A.5, A.7) with data placed by the hand formulas of A.5/A.7, and the
// biquadratic Lagrange value of A-9 computed by hand.
#include "base/error.h"
#include "blend/local_surface.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <random>

using namespace limn::blend;
const double pi = std::numbers::pi;

namespace {

// A random biquadratic g(x,y) = Σ a_ab x^a y^b with vector coefficients.
struct Biquadratic {
    Coefficients c;
    explicit Biquadratic(unsigned seed) {
        std::mt19937 rng(seed);
        std::normal_distribution<double> N(0, 1);
        for (auto& v : c) v = {N(rng), N(rng), N(rng)};
    }
    glm::dvec3 operator()(double x, double y) const {
        glm::dvec3 out(0.0);
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) out += c[a + 3 * b] * std::pow(x, a) * std::pow(y, b);
        return out;
    }
};

// Ring point positions by the hand formulas: interior conformal e_j = e^{2πij/k},
// d_j = 2^{2/k} e^{iπ(2j+1)/k}; boundary (Θ = π, q = p = 2/k) e_j = e^{iπj/k},
// d_j = 2^{1/k} e^{iπ(2j+1)/(2k)}, last boundary neighbour at −1.
std::vector<glm::dvec2> handRingPositions(uint32_t k, bool boundary) {
    std::vector<glm::dvec2> out;
    for (uint32_t j = 0; j < k; ++j) {
        double se = boundary ? pi / k : 2 * pi / k;
        double rd = boundary ? std::pow(2.0, 1.0 / k) : std::pow(2.0, 2.0 / k);
        out.push_back({std::cos(se * j), std::sin(se * j)});
        out.push_back({rd * std::cos(se * (j + 0.5)), rd * std::sin(se * (j + 0.5))});
    }
    if (boundary) out.push_back({-1, 0});
    return out;
}

} // namespace

TEST(Fit, RingPositionsMatchHandFormulas) {
    for (uint32_t k = 2; k <= 8; ++k)
        for (bool boundary : {false, true}) {
            Chart c = makeChart(k, boundary ? VertexKind::Boundary : VertexKind::Interior,
                                ChartType::Conformal);
            auto hand = handRingPositions(k, boundary);
            ASSERT_EQ(hand.size(), ringPointCount(c));
            for (size_t n = 0; n < hand.size(); ++n)
                EXPECT_LT(glm::length(ringPointPosition(c, n) - hand[n]), 1e-14) << k << " " << n;
        }
}

// A.5: for k ≥ 4 the 8 unknowns are determined, so data sampled from a biquadratic in chart
// coordinates gives back exactly its coefficients (k = 4 is Lagrange interpolation, k ≥ 5 least
// squares with zero residual). A.7: the same for boundary vertices with k ≥ 4.
TEST(Fit, ReproducesBiquadratics) {
    LocalSurfaceFitter fitter;
    for (uint32_t k = 4; k <= 8; ++k)
        for (bool boundary : {false, true}) {
            Chart c = makeChart(k, boundary ? VertexKind::Boundary : VertexKind::Interior,
                                ChartType::Conformal);
            Biquadratic g(10 * k + boundary);
            std::vector<glm::dvec3> ring;
            for (auto z : handRingPositions(k, boundary)) ring.push_back(g(z.x, z.y));
            Coefficients got = fitter.fit(c, g(0, 0), ring);
            for (int n = 0; n < 9; ++n)
                EXPECT_LT(glm::length(got[n] - g.c[n]), 1e-9) << "k=" << k << " coef " << n;
        }
}

// A.5 k = 3 and A.7 boundary k = 2, 3: fewer points than unknowns; the minimum-norm solution
// interpolates every ring point; boundary fits meet both boundary neighbours exactly.
TEST(Fit, InterpolatesWhenUnderdetermined) {
    LocalSurfaceFitter fitter;
    std::mt19937 rng(7);
    std::normal_distribution<double> N(0, 1);
    struct Case { uint32_t k; bool boundary; };
    for (Case cs : {Case{2, false}, Case{3, false}, Case{2, true}, Case{3, true}}) {
        Chart c = makeChart(cs.k, cs.boundary ? VertexKind::Boundary : VertexKind::Interior,
                            ChartType::Conformal);
        auto pos = handRingPositions(cs.k, cs.boundary);
        std::vector<glm::dvec3> ring;
        for (size_t n = 0; n < pos.size(); ++n) ring.push_back({N(rng), N(rng), N(rng)});
        glm::dvec3 centre(N(rng), N(rng), N(rng));
        Coefficients co = fitter.fit(c, centre, ring);
        EXPECT_LT(glm::length(evaluateLocalSurface(co, {0, 0}).value - centre), 1e-15);
        for (size_t n = 0; n < pos.size(); ++n)
            EXPECT_LT(glm::length(evaluateLocalSurface(co, pos[n]).value - ring[n]), 1e-12)
                << "k=" << cs.k << " boundary=" << cs.boundary << " point " << n;
    }
}

TEST(Fit, ConstantDataGivesConstantSurface) {
    // Affine invariance (A.5 step 3): all points equal -> all coefficients but c_00 vanish.
    LocalSurfaceFitter fitter;
    for (uint32_t k = 2; k <= 8; ++k) {
        Chart c = makeChart(k, VertexKind::Interior, ChartType::CharacteristicMap);
        std::vector<glm::dvec3> ring(2 * k, glm::dvec3(1.5, -2, 3));
        Coefficients co = fitter.fit(c, {1.5, -2, 3}, ring);
        for (int n = 1; n < 9; ++n) EXPECT_LT(glm::length(co[n]), 1e-13);
    }
}

TEST(Fit, CornerIsBilinear) {
    // A.7 k = 1: c00 = P_v, c10 = P_e − P_v, c01 = P_p − P_v, c11 = P_d − P_e − P_p + P_v.
    LocalSurfaceFitter fitter;
    Chart c = makeChart(1, VertexKind::Corner, ChartType::Conformal);
    glm::dvec3 v(0, 0, 1), e(1, 0, 2), d(1, 1, 5), p(0, 1, 3);
    std::vector<glm::dvec3> ring = {e, d, p};
    Coefficients co = fitter.fit(c, v, ring);
    EXPECT_EQ(co[coefficientIndex(1, 1)], glm::dvec3(0, 0, 5 - 2 - 3 + 1));
    EXPECT_EQ(evaluateLocalSurface(co, {0.5, 0.5}).value, (v + e + d + p) * 0.25);
    for (int n : {2, 5, 6, 7, 8}) EXPECT_EQ(co[n], glm::dvec3(0.0));
}

TEST(Fit, LocalSurfaceDerivatives) {
    Biquadratic g(99);
    glm::dvec2 z(0.3, -0.7);
    auto L = evaluateLocalSurface(g.c, z);
    const double e = 1e-6;
    EXPECT_LT(glm::length(L.value - g(z.x, z.y)), 1e-14);
    EXPECT_LT(glm::length(L.dx - (g(z.x + e, z.y) - g(z.x - e, z.y)) / (2 * e)), 1e-8);
    EXPECT_LT(glm::length(L.dy - (g(z.x, z.y + e) - g(z.x, z.y - e)) / (2 * e)), 1e-8);
}

TEST(Fit, RejectsWrongRingSize) {
    LocalSurfaceFitter fitter;
    std::vector<glm::dvec3> ring(5);
    EXPECT_THROW(fitter.fit(makeChart(3, VertexKind::Interior, ChartType::Conformal), {}, ring),
                 limn::Error);
}
