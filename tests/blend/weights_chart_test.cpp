// Weights (math.md A.4), corner coordinates (A.1), charts and transition maps (A.3) and the
// pseudo-inverse, against hand-derived values and closed forms computed here.
#include "base/error.h"
#include "blend/blend_surface.h"
#include "blend/chart.h"
#include "blend/pseudo_inverse.h"
#include "blend/weights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

using namespace limn::blend;
using cplx = std::complex<double>;
const double pi = std::numbers::pi;

TEST(Weights, HandValues) {
    // Cubic 1 − 3x² + 2x³ and quintic 1 − 10x³ + 15x⁴ − 6x⁵ at x = 1/4 (exact binary fractions).
    EXPECT_EQ(hermiteStep(WeightKind::Cubic, 0.25).h, 0.84375);
    EXPECT_EQ(hermiteStep(WeightKind::Quintic, 0.25).h, 918.0 / 1024);
    EXPECT_EQ(hermiteStep(WeightKind::Cubic, 0.25).dh, -6 * 0.25 * 0.75);
    EXPECT_EQ(hermiteStep(WeightKind::Quintic, 0.25).dh, -30 * 0.0625 * 0.5625);
    for (WeightKind k : {WeightKind::Cubic, WeightKind::Quintic}) {
        EXPECT_EQ(hermiteStep(k, 0).h, 1);
        EXPECT_EQ(hermiteStep(k, 1).h, 0);
        EXPECT_EQ(hermiteStep(k, 0.5).h, 0.5);
        EXPECT_EQ(hermiteStep(k, 0).dh, 0);
        EXPECT_EQ(hermiteStep(k, 1).dh, 0);
    }
}

TEST(Weights, SymmetryAndDerivatives) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> U(0, 1);
    for (WeightKind k : {WeightKind::Cubic, WeightKind::Quintic})
        for (int n = 0; n < 1000; ++n) {
            double x = U(rng);
            EXPECT_NEAR(hermiteStep(k, x).h + hermiteStep(k, 1 - x).h, 1.0, 2e-15);
            double e = 1e-6;
            double fd = (hermiteStep(k, x + e).h - hermiteStep(k, x - e).h) / (2 * e);
            if (x > e && x < 1 - e) {
                EXPECT_NEAR(hermiteStep(k, x).dh, fd, 1e-8);
            }
        }
}

// the four corner weights of a face sum to one at every point (A.4).
TEST(Weights, PartitionOfUnityOnAFace) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> U(0, 1);
    for (WeightKind k : {WeightKind::Cubic, WeightKind::Quintic})
        for (int n = 0; n < 2000; ++n) {
            double u = U(rng), v = U(rng);
            auto w = cornerWeights(k, u, v);
            EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 4e-15);
            // Corner 0's weight is h(u)h(v) by the A.1 table.
            EXPECT_DOUBLE_EQ(w[0], hermiteStep(k, u).h * hermiteStep(k, v).h);
        }
}

TEST(Corners, TableAndComplexRelations) {
    // A.1 table rows for (u,v) = (0.2, 0.7).
    const double u = 0.2, v = 0.7;
    const double expect[4][2] = {{u, v}, {v, 1 - u}, {1 - u, 1 - v}, {1 - v, u}};
    cplx z[4];
    for (uint32_t i = 0; i < 4; ++i) {
        auto st = cornerFromFace(i, u, v);
        EXPECT_DOUBLE_EQ(st.x, expect[i][0]);
        EXPECT_DOUBLE_EQ(st.y, expect[i][1]);
        auto back = faceFromCorner(i, st.x, st.y);
        EXPECT_DOUBLE_EQ(back.x, u);
        EXPECT_DOUBLE_EQ(back.y, v);
        z[i] = {st.x, st.y};
        // J_i by finite differences of the (affine) table.
        Mat2 J = cornerJacobian(i);
        auto du = cornerFromFace(i, u + 0.5, v) - st, dv = cornerFromFace(i, u, v + 0.5) - st;
        EXPECT_DOUBLE_EQ(J.m00, 2 * du.x);
        EXPECT_DOUBLE_EQ(J.m10, 2 * du.y);
        EXPECT_DOUBLE_EQ(J.m01, 2 * dv.x);
        EXPECT_DOUBLE_EQ(J.m11, 2 * dv.y);
    }
    const cplx I(0, 1);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(std::abs(z[(i + 1) % 4] - I * (1.0 - z[i])), 0, 1e-15);
        EXPECT_NEAR(std::abs(z[(i + 2) % 4] - ((1.0 + I) - z[i])), 0, 1e-15);
        EXPECT_NEAR(std::abs(z[(i + 3) % 4] - (1.0 + I * z[i])), 0, 1e-15);
    }
}

TEST(Charts, CharacteristicExponentsFromMathMd) {
    // A.3: p(3)=1.2860, p(4)=1, p(5)=0.8625, p(6)=0.7867.
    EXPECT_NEAR(characteristicExponent(3), 1.2860, 5e-5);
    EXPECT_NEAR(characteristicExponent(4), 1.0, 1e-14);
    EXPECT_NEAR(characteristicExponent(5), 0.8625, 5e-5);
    EXPECT_NEAR(characteristicExponent(6), 0.7867, 5e-5);
}

TEST(Charts, RingPointsOfConformalInteriorCharts) {
    // A.5: e_j -> e^{2πij/k}, d_j -> 2^{2/k} e^{iπ(2j+1)/k}; characteristic map: radius 2^{p/2}.
    for (uint32_t k = 2; k <= 9; ++k) {
        Chart c = makeChart(k, VertexKind::Interior, ChartType::Conformal);
        Chart cm = makeChart(k, VertexKind::Interior, ChartType::CharacteristicMap);
        for (uint32_t j = 0; j < k; ++j) {
            cplx e = std::polar(1.0, 2 * pi * j / k);
            cplx d = std::polar(std::pow(2.0, 2.0 / k), pi * (2 * j + 1) / k);
            cplx dm = std::polar(std::pow(2.0, cm.p / 2), pi * (2 * j + 1) / k);
            auto ze = chartMap(c, j, 1, 0).z, zd = chartMap(c, j, 1, 1).z, zm = chartMap(cm, j, 1, 1).z;
            EXPECT_NEAR(std::abs(cplx(ze.x, ze.y) - e), 0, 1e-14) << k << " " << j;
            EXPECT_NEAR(std::abs(cplx(zd.x, zd.y) - d), 0, 1e-14) << k << " " << j;
            EXPECT_NEAR(std::abs(cplx(zm.x, zm.y) - dm), 0, 1e-14) << k << " " << j;
        }
    }
    // Valence 4: every chart type is the rotation z = i^j (s + it) (A.3).
    for (ChartType t : {ChartType::Conformal, ChartType::CharacteristicMap, ChartType::Isodistance}) {
        Chart c = makeChart(4, VertexKind::Interior, t);
        auto z = chartMap(c, 3, 0.3, 0.6).z; // i³(0.3 + 0.6i) = 0.6 − 0.3i
        EXPECT_NEAR(z.x, 0.6, 1e-14);
        EXPECT_NEAR(z.y, -0.3, 1e-14);
    }
}

TEST(Charts, BoundaryAndCornerCharts) {
    // A.7: half-disk charts put the two boundary neighbours at x = +1 and x = −1.
    for (uint32_t k = 2; k <= 6; ++k) {
        Chart c = makeChart(k, VertexKind::Boundary, ChartType::CharacteristicMap);
        EXPECT_DOUBLE_EQ(c.q, 2.0 / k);
        EXPECT_DOUBLE_EQ(c.p, c.q); // boundary charts are conformal whatever the type
        auto plus = chartMap(c, 0, 1, 0).z, minus = chartMap(c, k - 1, 0, 1).z;
        EXPECT_NEAR(plus.x, 1, 1e-15);
        EXPECT_NEAR(plus.y, 0, 1e-15);
        EXPECT_NEAR(minus.x, -1, 1e-15);
        EXPECT_NEAR(minus.y, 0, 1e-15);
    }
    Chart corner = makeChart(1, VertexKind::Corner, ChartType::Conformal); // the identity
    auto z = chartMap(corner, 0, 0.3, 0.8).z;
    EXPECT_NEAR(z.x, 0.3, 1e-15);
    EXPECT_NEAR(z.y, 0.8, 1e-15);
    EXPECT_THROW(makeChart(1, VertexKind::Interior, ChartType::Conformal), limn::Error);
    EXPECT_THROW(makeChart(2, VertexKind::Corner, ChartType::Conformal), limn::Error);
}

// face -> chart -> face round trip, and the Jacobian against central differences.
TEST(Charts, RoundTripAndJacobian) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0.001, 1);
    for (uint32_t k = 2; k <= 8; ++k)
        for (VertexKind kind : {VertexKind::Interior, VertexKind::Boundary})
            for (ChartType type : {ChartType::Conformal, ChartType::CharacteristicMap}) {
                Chart c = makeChart(k, kind, type);
                for (int n = 0; n < 50; ++n) {
                    uint32_t j = n % k;
                    double s = U(rng), t = U(rng);
                    auto v = chartMap(c, j, s, t);
                    auto back = chartInverse(c, v.z);
                    EXPECT_EQ(back.ringIndex, j);
                    EXPECT_NEAR(back.s, s, 1e-13);
                    EXPECT_NEAR(back.t, t, 1e-13);
                    const double e = 1e-7;
                    auto ds = (chartMap(c, j, s + e, t).z - chartMap(c, j, s - e, t).z) / (2 * e);
                    auto dt = (chartMap(c, j, s, t + e).z - chartMap(c, j, s, t - e).z) / (2 * e);
                    double scale = 1 + std::abs(v.jacobian.m00) + std::abs(v.jacobian.m01);
                    EXPECT_NEAR(v.jacobian.m00, ds.x, 1e-6 * scale);
                    EXPECT_NEAR(v.jacobian.m10, ds.y, 1e-6 * scale);
                    EXPECT_NEAR(v.jacobian.m01, dt.x, 1e-6 * scale);
                    EXPECT_NEAR(v.jacobian.m11, dt.y, 1e-6 * scale);
                }
            }
}

// A-8b: the closed-form transition map of A.3 between conformal interior charts (k_v = 5 to
// k_w = 3, for the next, opposite and previous corner) equals the composition of chart maps.
TEST(Charts, ClosedFormTransitionMap) {
    const uint32_t kv = 5, kw = 3;
    Chart cv = makeChart(kv, VertexKind::Interior, ChartType::Conformal);
    Chart cw = makeChart(kw, VertexKind::Interior, ChartType::Conformal);
    const cplx I(0, 1);
    auto cpow = [](cplx x, double e) { return std::polar(std::pow(std::abs(x), e), std::arg(x) * e); };
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> U(0.01, 0.99);
    double worst = 0;
    for (int n = 0; n < 200; ++n) {
        double u = U(rng), v = U(rng);
        uint32_t jv = n % kv, jw = (n / kv) % kw;
        for (uint32_t b = 1; b <= 3; ++b) {
            auto sa = cornerFromFace(0, u, v), sb = cornerFromFace(b, u, v);
            auto zv = chartMap(cv, jv, sa.x, sa.y).z, zw = chartMap(cw, jw, sb.x, sb.y).z;
            cplx zeta = cpow(std::polar(1.0, -2 * pi * jv / kv) * cplx(zv.x, zv.y), kv / 4.0);
            cplx m = b == 1 ? I * (1.0 - zeta) : b == 2 ? (1.0 + I) - zeta : 1.0 + I * zeta;
            cplx pred = std::polar(1.0, 2 * pi * jw / kw) * cpow(m, 4.0 / kw);
            worst = std::max(worst, std::abs(pred - cplx(zw.x, zw.y)));
        }
    }
    EXPECT_LT(worst, 1e-13);
}

namespace {
std::vector<double> multiply(const std::vector<double>& a, const std::vector<double>& b, size_t n,
                             size_t k, size_t m) {
    std::vector<double> c(n * m, 0);
    for (size_t i = 0; i < n; ++i)
        for (size_t l = 0; l < k; ++l)
            for (size_t j = 0; j < m; ++j) c[i * m + j] += a[i * k + l] * b[l * m + j];
    return c;
}
double maxDiff(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0;
    for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}
} // namespace

// The four Penrose conditions define the pseudo-inverse uniquely: A X A = A, X A X = X, and A X,
// X A symmetric. Shapes as in the fits: under-, exactly and over-determined, and rank-deficient.
TEST(PseudoInverse, PenroseConditions) {
    std::mt19937 rng(5);
    std::normal_distribution<double> N(0, 1);
    const size_t shapes[][3] = {{6, 8, 6}, {8, 8, 8}, {16, 8, 8}, {3, 6, 3}, {9, 6, 4}, {10, 8, 5}};
    for (auto [rows, cols, rank] : shapes) {
        // A = B·C with B rows×rank and C rank×cols has rank `rank`.
        std::vector<double> B(rows * rank), C(rank * cols);
        for (auto& x : B) x = N(rng);
        for (auto& x : C) x = N(rng);
        auto A = multiply(B, C, rows, rank, cols);
        auto X = pseudoInverse(A, rows, cols);
        auto AX = multiply(A, X, rows, cols, rows), XA = multiply(X, A, cols, rows, cols);
        EXPECT_LT(maxDiff(multiply(AX, A, rows, rows, cols), A), 1e-12) << rows << "x" << cols;
        EXPECT_LT(maxDiff(multiply(XA, X, cols, cols, rows), X), 1e-10) << rows << "x" << cols;
        for (size_t i = 0; i < rows; ++i)
            for (size_t j = 0; j < rows; ++j) EXPECT_NEAR(AX[i * rows + j], AX[j * rows + i], 1e-12);
        for (size_t i = 0; i < cols; ++i)
            for (size_t j = 0; j < cols; ++j) EXPECT_NEAR(XA[i * cols + j], XA[j * cols + i], 1e-12);
    }
}
