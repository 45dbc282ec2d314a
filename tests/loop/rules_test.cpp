// Loop's weights, limit masks, the edge metric and the retriangulation templates against small
// computations done here: the paper's closed forms, eigenvectors of the local subdivision matrix,
// affine reproduction on planar meshes, and compactness by hand.
#include "loop/adaptive.h"
#include "loop/rules.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

using namespace limn;
using namespace limn::loop;

namespace {

// Paper 004, eq. (1): α(k) = 5/8 − (3 + 2cos(2π/k))²/64.
double paperAlpha(int k) {
    double c = 3 + 2 * std::cos(2 * std::numbers::pi / k);
    return 5.0 / 8 - c * c / 64;
}

TEST(LoopWeights, AlphaMatchesPaperAndLoopsThesis) {
    EXPECT_DOUBLE_EQ(loopAlpha(3), 9.0 / 16); // Loop 1987: β(3) = 3/16
    EXPECT_DOUBLE_EQ(loopAlpha(6), 3.0 / 8);  // regular: 1/16 per neighbour
    for (int k = 3; k <= 20; ++k) EXPECT_NEAR(loopAlpha(k), paperAlpha(k), 1e-15) << k;
    EXPECT_DOUBLE_EQ(limitOmega(6), 6.0); // v∞ = v/2 + Σ v_i / 12 (math.md B.2)
}

// The limit mask (ω, 1, ..., 1)/(ω + k) is the left eigenvector for eigenvalue 1 of the local
// subdivision matrix of a valence-k vertex and its ring (built here from Loop's rules).
TEST(LoopWeights, LimitMaskIsLeftEigenvector) {
    for (int k = 3; k <= 12; ++k) {
        const int n = k + 1;
        std::vector<double> S(n * n, 0.0); // rows: new v, new odd vertices on the k spokes
        double a = paperAlpha(k);
        S[0] = 1 - a;
        for (int i = 1; i <= k; ++i) S[i] = a / k;
        for (int i = 0; i < k; ++i) {
            double* row = &S[(1 + i) * n];
            row[0] = 3.0 / 8;
            row[1 + i] += 3.0 / 8;
            row[1 + (i + 1) % k] += 1.0 / 8;
            row[1 + (i + k - 1) % k] += 1.0 / 8;
        }
        double w = limitOmega(k);
        std::vector<double> l(n, 1.0 / (w + k));
        l[0] = w / (w + k);
        for (int j = 0; j < n; ++j) {
            double lS = 0;
            for (int i = 0; i < n; ++i) lS += l[i] * S[i * n + j];
            EXPECT_NEAR(lS, l[j], 1e-15) << "valence " << k << " column " << j;
        }
    }
}

// A triangulated grid over [0,n]² with z = height(x, y); `flip` chooses diagonals irregularly.
TriMesh grid(int n, bool irregular, double (*height)(double, double)) {
    TriMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.push_back({i, j, height(i, j)});
    auto id = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            bool flip = irregular && ((i * 7 + j * 3) % 5 < 2);
            uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (flip) {
                m.triangles.push_back({a, b, d});
                m.triangles.push_back({b, c, d});
            } else {
                m.triangles.push_back({a, b, c});
                m.triangles.push_back({a, c, d});
            }
        }
    m.corners.assign(m.positions.size(), 0);
    return m;
}

double flat(double, double) { return 0; }
double bowl(double x, double y) { return 0.05 * (x * x + y * y); }

// Loop subdivision reproduces affine functions, so on a regular planar grid an odd vertex is its
// own limit: d = 0 away from the boundary. With irregular valences the limit drifts inside the
// plane: the full metric sees it, the normal metric does not (math.md B.4, caveat). (Boundary
// edges near the square's corners bend in the plane, which both metrics see.)
TEST(EdgeMetric, PlanarGrids) {
    for (bool irregular : {false, true}) {
        TriMesh m = grid(8, irregular, flat);
        Level level(m);
        auto even = evenPositions(level), odd = oddPositions(level);
        auto full = edgeDistances(level, even, odd, Metric::Full);
        auto normal = edgeDistances(level, even, odd, Metric::Normal);
        const Topology& topo = level.topology();
        double maxFull = 0;
        for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
            auto [a, b] = topo.edgeVertices(e);
            glm::dvec3 mid = 0.5 * (m.positions[a] + m.positions[b]);
            bool inner = mid.x > 2.5 && mid.x < 5.5 && mid.y > 2.5 && mid.y < 5.5;
            if (!level.edgeSharp(e)) {
                EXPECT_NEAR(normal[e], 0.0, 1e-12) << "edge " << e;
            }
            if (!inner) continue;
            if (!irregular) {
                EXPECT_NEAR(full[e], 0.0, 1e-12) << "edge " << e;
            }
            maxFull = std::max(maxFull, full[e]);
        }
        if (irregular) {
            EXPECT_GT(maxFull, 1e-3);
        }
    }
}

// On a curved regular grid every interior edge has d > 0, and the normal part is the whole
// distance up to the tangential drift, which vanishes by symmetry at the centre.
TEST(EdgeMetric, CurvedGridIsRefined) {
    TriMesh m = grid(8, false, bowl);
    Level level(m);
    auto even = evenPositions(level), odd = oddPositions(level);
    auto full = edgeDistances(level, even, odd, Metric::Full);
    auto normal = edgeDistances(level, even, odd, Metric::Normal);
    for (uint32_t e = 0; e < level.topology().edgeCount(); ++e) {
        if (level.edgeSharp(e)) continue;
        EXPECT_GT(full[e], 0.0);
        EXPECT_LE(normal[e], full[e] + 1e-15);
    }
    // The hand-computed value for one interior edge: z = 0.05 (x² + y²) on the regular lattice.
    // Odd vertex of edge (4,4)-(5,4): z_o = 3/8 (z44 + z54) + 1/8 (z55 + z43); the limit of the
    // refined regular mesh is o/2 + Σ(6 neighbours)/12.
    uint32_t e = level.topology().findEdge(4 * 9 + 4, 4 * 9 + 5);
    ASSERT_NE(e, kNone);
    auto z = [](double x, double y) { return bowl(x, y); };
    auto oddZ = [&](double x0, double y0, double x1, double y1, double cx, double cy, double dx, double dy) {
        return 0.375 * (z(x0, y0) + z(x1, y1)) + 0.125 * (z(cx, cy) + z(dx, dy));
    };
    auto evenZ = [&](double x, double y) {
        double s = z(x + 1, y) + z(x - 1, y) + z(x, y + 1) + z(x, y - 1) + z(x + 1, y + 1) + z(x - 1, y - 1);
        return 0.625 * z(x, y) + s / 16;
    };
    // Triangles (a,b,c) with diagonals along (1,1): edge (4,4)-(5,4) has opposite vertices
    // (5,5) and (4,3).
    double o = oddZ(4, 4, 5, 4, 5, 5, 4, 3);
    double ring = evenZ(4, 4) + evenZ(5, 4) + oddZ(5, 4, 5, 5, 4, 4, 6, 5) + oddZ(4, 4, 5, 5, 5, 4, 4, 5) +
                  oddZ(4, 4, 4, 3, 3, 3, 5, 4) + oddZ(5, 4, 4, 3, 4, 4, 5, 3);
    double expected = std::abs(o - (o / 2 + ring / 12));
    EXPECT_NEAR(full[e], expected, 1e-14);
}

TEST(Compactness, KnownTriangles) {
    glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0);
    EXPECT_NEAR(compactness(a, b, c), 1.0, 1e-15);
    EXPECT_NEAR(compactness(a, b, {0, 1, 0}), std::sqrt(3.0) / 2, 1e-15); // 4√3·½ / (1+1+2)
    EXPECT_NEAR(compactness(3.0 * a, 3.0 * b, 3.0 * c), 1.0, 1e-15);
    EXPECT_EQ(compactness(a, b, {2, 0, 0}), 0.0);
    EXPECT_EQ(compactness(a, a, a), 0.0);
}

// One triangle, every subset of split edges: 1 + (number of split edges) triangles, all oriented
// like the parent, tiling it (the even rule is off: EvenUpdate::Split keeps the corners of a
// boundary triangle on its crease rule, so use a planar triangle and compare areas in the plane).
TEST(Templates, SingleTriangleAllPatterns) {
    TriMesh m;
    m.positions = {{0, 0, 0}, {4, 0, 0}, {1, 3, 0}};
    m.triangles = {{0, 1, 2}};
    m.corners = {1, 1, 1}; // corners: even positions stay put, so the children tile the parent
    Level level(m);
    auto even = evenPositions(level), odd = oddPositions(level);
    for (int mask = 0; mask < 8; ++mask) {
        std::vector<uint8_t> split(3);
        int count = 0;
        for (int i = 0; i < 3; ++i) count += split[i] = (mask >> i) & 1;
        Refinement r = refine(level, split, EvenUpdate::Split, even, odd);
        ASSERT_EQ(r.mesh.triangleCount(), static_cast<uint32_t>(1 + count)) << mask;
        double area = 0;
        for (const Tri& t : r.mesh.triangles) {
            const auto& P = r.mesh.positions;
            double z = glm::cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]).z;
            EXPECT_GT(z, 0) << "pattern " << mask << ": a triangle flipped";
            area += z / 2;
        }
        EXPECT_NEAR(area, 6.0, 1e-12) << mask;
    }
}

// Two split edges: the quad left after cutting off the corner is split by the diagonal whose two
// triangles have the larger minimum compactness (paper 004, eq. (3); math.md B.6).
TEST(Templates, TwoSplitDiagonalByCompactness) {
    int choseA = 0, choseB = 0;
    for (double apexX : {-3.0, 0.5, 6.0}) {
        TriMesh m;
        m.positions = {{0, 0, 0}, {4, 0, 0}, {apexX, 1.5, 0}};
        m.triangles = {{0, 1, 2}};
        m.corners = {1, 1, 1};
        Level level(m);
        auto even = evenPositions(level), odd = oddPositions(level);
        const Topology& topo = level.topology();
        // Split x→y = (0,1) and y→z = (1,2); zx = (2,0) stays.
        std::vector<uint8_t> split(3, 0);
        split[topo.findEdge(0, 1)] = 1;
        split[topo.findEdge(1, 2)] = 1;
        Refinement r = refine(level, split, EvenUpdate::Split, even, odd);
        const auto& P = r.mesh.positions;
        glm::dvec3 x = P[0], z = P[2], mxy = 0.5 * (P[0] + P[1]), myz = 0.5 * (P[1] + P[2]);
        double qa = std::min(compactness(x, mxy, myz), compactness(x, myz, z));
        double qb = std::min(compactness(x, mxy, z), compactness(mxy, myz, z));
        bool wantA = qa >= qb;
        bool hasA = false; // diagonal x – m_yz present?
        uint32_t myzIndex = 3 + (topo.findEdge(0, 1) < topo.findEdge(1, 2) ? 1 : 0);
        for (const Tri& t : r.mesh.triangles)
            for (int i = 0; i < 3; ++i)
                if ((t[i] == 0 && t[(i + 1) % 3] == myzIndex) || (t[i] == myzIndex && t[(i + 1) % 3] == 0))
                    hasA = true;
        EXPECT_EQ(hasA, wantA) << "apex x " << apexX << " qa " << qa << " qb " << qb;
        (hasA ? choseA : choseB)++;
    }
    EXPECT_GT(choseA, 0); // the cases exercise both diagonals
    EXPECT_GT(choseB, 0);
}

} // namespace
