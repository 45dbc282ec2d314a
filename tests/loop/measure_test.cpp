// The measurement (math.md B.8) against simple computations: point-triangle distance against dense
// sampling, the BVH against a linear scan, and the two-sided distance against a known offset.
#include "loop/adaptive.h"
#include "loop/measure.h"
#include "mesh/import.h"
#include "test_support.h"
#include "tri_mesh_models.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <random>

using namespace limn;
using namespace limn::loop;

namespace {

// Minimum over a fine barycentric grid: an upper bound within (edge length / n) of the truth.
double sampledDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const int n = 400;
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
            glm::dvec3 q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
            best = std::min(best, glm::length(p - q));
        }
    return best;
}

TEST(Measure, PointTriangleDistanceMatchesSampling) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    auto point = [&] { return glm::dvec3(u(rng), u(rng), u(rng)); };
    for (int k = 0; k < 200; ++k) {
        glm::dvec3 a = point(), b = point(), c = point(), p = 2.0 * point();
        if (k % 20 == 0) c = 0.5 * (a + b); // degenerate: a segment
        double exact = std::sqrt(pointTriangleSquaredDistance(p, a, b, c));
        double sampled = sampledDistance(p, a, b, c);
        EXPECT_LE(exact, sampled + 1e-12) << k;
        EXPECT_GE(exact, sampled - 4.0 / 400) << k;
    }
    // Exact cases: above the interior, beyond a vertex, beside an edge.
    glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_DOUBLE_EQ(pointTriangleSquaredDistance({0.2, 0.2, 3}, a, b, c), 9.0);
    EXPECT_DOUBLE_EQ(pointTriangleSquaredDistance({-1, -1, 0}, a, b, c), 2.0);
    EXPECT_DOUBLE_EQ(pointTriangleSquaredDistance({0.5, -2, 0}, a, b, c), 4.0);
}

TEST(Measure, BvhEqualsLinearScan) {
    TriMesh m = test::loadTriMesh("tri/spot_triangulated.obj");
    TriangleBvh bvh(m.positions, m.triangles);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int k = 0; k < 300; ++k) {
        glm::dvec3 p(u(rng), u(rng), u(rng));
        if (k % 3 == 0) p = m.positions[k * 7 % m.vertexCount()] + 0.01 * p; // near the surface
        double scan = 1e300;
        for (const Tri& t : m.triangles)
            scan = std::min(scan, pointTriangleSquaredDistance(p, m.positions[t[0]], m.positions[t[1]],
                                                               m.positions[t[2]]));
        EXPECT_EQ(bvh.squaredDistance(p), scan) << k;
    }
}

// The reference measured against itself is 0; shifted by t, the distance is at most |t| everywhere
// (p + t lies on the shifted surface) and reaches it where the normal is parallel to t.
TEST(Measure, KnownOffsets) {
    TriMesh control = test::loadTriMesh("tri/sphere.obj");
    MeasureOptions options;
    options.referenceLevel = 3;
    options.maxSamples = 50000;
    LimitReference reference(control, options);
    const double D = boundingBoxDiagonal(control.positions);
    Measurement self = reference.measure(reference.mesh());
    EXPECT_LT(self.max, 1e-12);
    EXPECT_GT(self.toLimit.samples, 40000u); // about the cap of 50000 per direction
    EXPECT_GT(self.fromLimit.samples, 0u);
    TriMesh shifted = reference.mesh();
    const glm::dvec3 t(0.003, -0.002, 0.001);
    for (auto& p : shifted.positions) p += t;
    Measurement m = reference.measure(shifted);
    EXPECT_LE(m.max, glm::length(t) / D * (1 + 1e-9));
    EXPECT_GE(m.max, 0.95 * glm::length(t) / D);
    EXPECT_GT(m.rms, 0.3 * glm::length(t) / D);
    EXPECT_LE(m.rms, m.max);
}

// Uniform refinement converges to the limit surface: each level cuts the error by about 4.
TEST(Measure, UniformLevelsConverge) {
    TriMesh control = test::loadTriMesh("tri/sphere.obj");
    MeasureOptions options;
    options.referenceLevel = 4;
    options.maxSamples = 50000;
    LimitReference reference(control, options);
    double previous = 0;
    for (int l = 0; l <= 2; ++l) {
        AdaptiveOptions u;
        u.uniform = true;
        u.levels = l;
        Measurement m = reference.measure(subdivide(control, u).mesh);
        EXPECT_GT(m.max, 0);
        if (l > 0) {
            EXPECT_LT(m.max, previous / 2.5) << "level " << l;
            EXPECT_GT(m.max, previous / 6) << "level " << l;
        }
        previous = m.max;
    }
}

TEST(Measure, DefaultReferenceLevel) {
    TriMesh small = test::loadTriMesh("tri/osd_loop_tetrahedron.obj");
    EXPECT_EQ(defaultReferenceLevel(small, 2), 4);
    // 15894 triangles: 4^4 of them fit 5M, 4^5 do not
    TriMesh cat = test::loadTriMesh("tri/cat_lowres.obj");
    EXPECT_EQ(defaultReferenceLevel(cat, 3), 4);
    EXPECT_EQ(defaultReferenceLevel(cat, 3, 1000), 1);
}

} // namespace
