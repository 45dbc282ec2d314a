// expandSmoothFaces (fvar_surface.h): a smooth UV face (support UVs, per-valence weights) as the
// pieces the GPU draws. The arithmetic is spelled out (double sums in a fixed order, rounded to
// float once) because web/src/fvar_chunk.mjs does the same and must give the same bits.
#include "subdiv/fvar_surface.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>

namespace limn {

namespace {

// The band frame (a, c) has the extraordinary corner at (0, 0); the ptex face's (s, t) is it
// turned by `corner` (evaluateIrregular's rotation): the face-local square whose band square is
// [a0, a0 + h] x [c0, c0 + h].
void bandSquareToFace(uint32_t corner, double a0, double c0, double h, double& s0, double& t0) {
    switch (corner) {
    case 0: s0 = a0, t0 = c0; break;
    case 1: s0 = 1 - c0 - h, t0 = a0; break;
    case 2: s0 = 1 - a0 - h, t0 = 1 - c0 - h; break;
    default: s0 = c0, t0 = 1 - a0 - h; break;
    }
}

} // namespace

FaceVaryingSurface::Gpu expandSmoothFaces(FaceVaryingSurface::Gpu g) {
    using Basis = FaceVaryingSurface::Basis;
    // A boundary configuration's weights hold its sub-patches' phantom points (2 a - b of
    // points), so its control points come out as gatherControlPoints makes them.
    uint32_t next = static_cast<uint32_t>(g.records.size() / 9);
    // Piece `e` at the face-local square (s0, t0, h = 2^-level) below the smooth face's node.
    auto insert = [&](uint32_t node, uint32_t level, double s0, double t0, uint32_t e) {
        const uint32_t i = uint32_t(std::lround(std::ldexp(s0, int(level))));
        const uint32_t j = uint32_t(std::lround(std::ldexp(t0, int(level))));
        g.nodes[fvarQuadtreeCell(g.nodes, node, level, i, j)] = 0x80000000u | e;
    };
    for (const FaceVaryingSurface::SmoothFace& f : g.smoothFaces) {
        if (f.basis >= g.bases.size()) throw Error(ErrorKind::BadInput, "a smooth UV face has no basis");
        const Basis* basis = &g.bases[f.basis];
        const uint32_t M = basis->supportSize(), K = basis->levels;
        const glm::vec2* support = g.points.data() + f.firstPoint;
        g.nodes[f.node] = 0xFFFFFFFFu;
        // The band-frame control points P[i][j] of band k's quadrant q (1: a >= 1/2, 2: both, 3:
        // c >= 1/2; evaluate.h's smoothSubPatchControlPoints).
        auto control = [&](uint32_t k, uint32_t q, glm::dvec2 P[4][4]) {
            const float* w = basis->weights.data() + (size_t(k - 1) * 3 + (q - 1)) * 16 * M;
            for (uint32_t j = 0; j < 16; ++j) {
                double x = 0, y = 0;
                for (uint32_t i = 0; i < M; ++i) {
                    x += double(w[size_t(j) * M + i]) * double(support[i].x);
                    y += double(w[size_t(j) * M + i]) * double(support[i].y);
                }
                P[j % 4][j / 4] = {x, y};
            }
        };
        auto record = [&](double s0, double t0, double h, float kind) {
            g.records.push_back({float(f.u0 + s0 * f.size), float(f.v0 + t0 * f.size), float(h * f.size), kind});
        };
        glm::dvec2 corners[4]; // band K's sub-patches at their (0, 0): the leaf's band corners
        for (uint32_t k = 1; k <= K; ++k) {
            const double h = std::ldexp(1.0, -int(k));
            for (uint32_t q = 1; q <= 3; ++q) {
                glm::dvec2 P[4][4], Q[4][4];
                control(k, q, P);
                // B_i(1 - x) = B_{3-i}(x): the ptex frame's Q[i][j] is a band-frame P.
                for (int i = 0; i < 4; ++i)
                    for (int j = 0; j < 4; ++j)
                        Q[i][j] = f.corner == 0   ? P[i][j]
                                  : f.corner == 1 ? P[j][3 - i]
                                  : f.corner == 2 ? P[3 - i][3 - j]
                                                  : P[3 - j][i];
                double s0, t0;
                bandSquareToFace(f.corner, q == 3 ? 0 : h, q == 1 ? 0 : h, h, s0, t0);
                insert(f.node, k, s0, t0, next++);
                record(s0, t0, h, 0.0f);
                for (int c = 0; c < 16; c += 2)
                    g.records.push_back(glm::vec4(float(Q[c % 4][c / 4].x), float(Q[c % 4][c / 4].y),
                                                  float(Q[(c + 1) % 4][(c + 1) / 4].x), float(Q[(c + 1) % 4][(c + 1) / 4].y)));
                if (k == K) { // the B-spline at (0, 0): (1, 4, 1)/6 in each direction
                    const double b[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6};
                    glm::dvec2 v(0.0);
                    for (int j = 0; j < 3; ++j) {
                        glm::dvec2 row(0.0);
                        for (int i = 0; i < 3; ++i) row += b[i] * P[i][j];
                        v += b[j] * row;
                    }
                    corners[q] = v;
                }
            }
        }
        // The leaf within 2^-K of the corner: bilinear between the limit UV (band corner (0, 0))
        // and band K's (1, 0), (1, 1), (0, 1), taken in ptex order.
        corners[0] = glm::dvec2(f.limit);
        const double h = std::ldexp(1.0, -int(K));
        double s0, t0;
        bandSquareToFace(f.corner, 0, 0, h, s0, t0);
        insert(f.node, K, s0, t0, next++);
        record(s0, t0, h, 1.0f);
        glm::dvec2 c[4];
        const int ds[4] = {0, 1, 1, 0}, dt[4] = {0, 0, 1, 1};
        for (int p = 0; p < 4; ++p) {
            const int da = f.corner == 0 ? ds[p] : f.corner == 1 ? dt[p] : f.corner == 2 ? 1 - ds[p] : 1 - dt[p];
            const int dc = f.corner == 0 ? dt[p] : f.corner == 1 ? 1 - ds[p] : f.corner == 2 ? 1 - dt[p] : ds[p];
            c[p] = corners[da == 0 ? (dc == 0 ? 0 : 3) : (dc == 0 ? 1 : 2)];
        }
        g.records.push_back(glm::vec4(float(c[0].x), float(c[0].y), float(c[1].x), float(c[1].y)));
        g.records.push_back(glm::vec4(float(c[2].x), float(c[2].y), float(c[3].x), float(c[3].y)));
        g.records.insert(g.records.end(), 6, glm::vec4(0.0f));
    }
    g.smoothFaces.clear();
    g.points.clear();
    g.bases.clear();
    return g;
}

} // namespace limn
