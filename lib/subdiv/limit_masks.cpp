#include "subdiv/limit_masks.h"

#include <cmath>
#include <numbers>

namespace limn {

namespace {

constexpr double kPi = std::numbers::pi;

// A_n of [HKD93] (math.md C.3); paper 000 prints it with '+' instead of '·' before the root.
double A(double n) {
    return 1 + std::cos(2 * kPi / n) + std::cos(kPi / n) * std::sqrt(2 * (9 + std::cos(2 * kPi / n)));
}

void add(std::vector<WeightedPoint>& m, uint32_t v, double w) {
    if (w != 0) m.push_back({v, w});
}

} // namespace

std::vector<Sector> vertexSectors(const VertexNeighborhood& hood, VertexRule rule,
                                  const std::vector<float>& edgeSharpness) {
    const uint32_t k = static_cast<uint32_t>(hood.faces.size());
    std::vector<uint32_t> sharp; // ring edge indices that cut the ring
    if (hood.boundary) {
        for (uint32_t i = 0; i <= k; ++i)
            if (i == 0 || i == k || (edgeSharpness[hood.edges[i]] > 0 && rule != VertexRule::Smooth &&
                                     rule != VertexRule::Dart))
                sharp.push_back(i);
    } else if (rule == VertexRule::Crease || rule == VertexRule::Corner) {
        for (uint32_t i = 0; i < k; ++i)
            if (edgeSharpness[hood.edges[i]] > 0) sharp.push_back(i);
    }
    if (!hood.boundary && sharp.size() < 2) return {{0, k, true}};
    std::vector<Sector> sectors;
    for (size_t s = 0; s + 1 < sharp.size(); ++s)
        sectors.push_back({sharp[s], sharp[s + 1] - sharp[s], false});
    if (!hood.boundary) // the sector that wraps around from the last sharp edge to the first
        sectors.push_back({sharp.back(), k - sharp.back() + sharp.front(), false});
    return sectors;
}

void limitMasks(const VertexNeighborhood& hood, VertexRule rule, const Sector& sector,
                const std::vector<float>& edgeSharpness, float vertexSharpness, LimitMasks& m) {
    m.position.clear();
    m.tangent1.clear();
    m.tangent2.clear();
    m.exact = true;
    const uint32_t v = hood.vertex;
    const uint32_t n = static_cast<uint32_t>(hood.faces.size());
    const uint32_t E = static_cast<uint32_t>(hood.edges.size());
    auto ringVertex = [&](uint32_t i) { return hood.ringVertex[i % E]; };
    auto diagonal = [&](uint32_t i) { return hood.diagonal[i % n]; };

    // Semi-sharp features that have not decayed by the last level are treated as fully sharp
    // by the crease and corner masks: an approximation (opensubdiv.md, "Exact vertex limits").
    if (vertexSharpness > 0 && vertexSharpness < 10) m.exact = false;
    for (uint32_t e : hood.edges)
        if (edgeSharpness[e] > 0 && edgeSharpness[e] < 10) m.exact = false;

    // Position.
    if (rule == VertexRule::Corner) {
        add(m.position, v, 1.0);
    } else if (rule == VertexRule::Crease) {
        // The crease is a cubic B-spline of its polygon (math.md C.4): (e_a + 4v + e_b)/6.
        std::vector<uint32_t> ends;
        for (uint32_t i = 0; i < E; ++i)
            if (edgeSharpness[hood.edges[i]] > 0) ends.push_back(hood.ringVertex[i]);
        add(m.position, v, 4.0 / 6.0);
        add(m.position, ends[0], 1.0 / 6.0);
        add(m.position, ends[1], 1.0 / 6.0);
    } else {
        // (E6): (n^2 v + 4 sum e_j + sum f_j) / (n (n + 5)), e_j the ring, f_j the diagonals.
        // Darts use it too; their exact limit differs slightly (exact_limits.h replaces it).
        double d = double(n) * (n + 5);
        add(m.position, v, double(n) * n / d);
        for (uint32_t i = 0; i < n; ++i) {
            add(m.position, hood.ringVertex[i], 4.0 / d);
            add(m.position, hood.diagonal[i], 1.0 / d);
        }
        if (rule == VertexRule::Dart || n == 2) m.exact = false;
    }

    // Tangents.
    if (sector.closed && rule == VertexRule::Corner) m.exact = false; // a cone point: no plane
    if (sector.closed) {
        if (n == 2) { // valence 2: no rotational structure; use the two edge directions
            add(m.tangent1, ringVertex(0), 1);
            add(m.tangent1, v, -1);
            add(m.tangent2, ringVertex(1), 1);
            add(m.tangent2, v, -1);
            m.exact = false;
            return;
        }
        // c2 and c3 of [HKD93] (math.md C.3); c3 is c2 rotated by one index.
        double a = A(n);
        for (uint32_t i = 0; i < n; ++i) {
            double ci = std::cos(2 * kPi * i / n), ci1 = std::cos(2 * kPi * (i + 1) / n);
            double cim = std::cos(2 * kPi * (double(i) - 1) / n);
            add(m.tangent1, hood.ringVertex[i], a * ci);
            add(m.tangent1, hood.diagonal[i], ci + ci1);
            add(m.tangent2, hood.ringVertex[i], a * cim);
            add(m.tangent2, hood.diagonal[i], cim + ci);
        }
        return;
    }

    // A sector of k faces between the sharp edges `lead` (e_0) and `trail` (e_k), treated as a
    // boundary (math.md C.4): exact for boundaries and infinitely sharp creases.
    const uint32_t k = sector.faceCount, f0 = sector.firstFace;
    auto e = [&](uint32_t i) { return ringVertex(f0 + i); };  // e_0 .. e_k
    auto f = [&](uint32_t i) { return diagonal(f0 + i); };    // f_0 .. f_{k-1}
    if (rule == VertexRule::Corner && k > 1) {
        // The sector's two sharp edges are curves that end at the fixed corner, in the
        // directions of these edges (OpenSubdiv's corner tangent masks). With more than one
        // face between them a mode of the sector's interior outgrows those directions, so the
        // surface has no tangent plane at v: exact_limits.h gives each face its own normal.
        // Tables are built from topology alone, so a corner whose two edges happen to be
        // collinear (on a straight boundary) gets a degenerate normal here; the renderer falls
        // back to the face.
        m.exact = false;
        add(m.tangent1, e(0), 1);
        add(m.tangent1, v, -1);
        add(m.tangent2, e(k), 1);
        add(m.tangent2, v, -1);
        return;
    }
    add(m.tangent1, e(0), 1);
    add(m.tangent1, e(k), -1);
    if (k == 1) {
        add(m.tangent2, e(0), 1);
        add(m.tangent2, e(1), 1);
        add(m.tangent2, v, -2);
    } else if (k == 2) {
        // The regular boundary: the B-spline derivative with phantom row P_-1 = 2 P_0 - P_1.
        add(m.tangent2, v, -4.0 / 6);
        add(m.tangent2, e(0), -1.0 / 6);
        add(m.tangent2, e(2), -1.0 / 6);
        add(m.tangent2, e(1), 4.0 / 6);
        add(m.tangent2, f(0), 1.0 / 6);
        add(m.tangent2, f(1), 1.0 / 6);
    } else {
        // k >= 3: the exact left eigenvector for the cross eigenvalue lambda_{2k} (math.md C.4;
        // OpenSubdiv's Biermann et al. mask is not an eigenvector under these rules).
        double theta = kPi / k, a = A(2.0 * k), lambda = (a + 4) / 16;
        for (uint32_t i = 1; i < k; ++i) add(m.tangent2, e(i), a * std::sin(i * theta));
        for (uint32_t i = 0; i < k; ++i)
            add(m.tangent2, f(i), std::sin(i * theta) + std::sin((i + 1) * theta));
        // [1/8, 1/2 - l; 3/4 - l, 1] [xv; x0] = -[a sin/16 + sin/4; cot(t/2)(3a/8 + 1/2)]
        double m00 = 1.0 / 8, m01 = 0.5 - lambda, m10 = 0.75 - lambda, m11 = 1;
        double r0 = -(a * std::sin(theta) / 16 + std::sin(theta) / 4);
        double r1 = -(1 / std::tan(theta / 2) * (3 * a / 8 + 0.5));
        double det = m00 * m11 - m01 * m10;
        double xv = (r0 * m11 - m01 * r1) / det, x0 = (m00 * r1 - m10 * r0) / det;
        add(m.tangent2, v, xv);
        add(m.tangent2, e(0), x0);
        add(m.tangent2, e(k), x0);
    }
}

} // namespace limn
