#include "bake/heightmap.h"

#include "base/error.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace limn {

namespace {

uint32_t hash(int x, int y, int z, uint32_t seed) {
    uint32_t h = seed * 0x9E3779B1u ^ uint32_t(x) * 0x85EBCA77u ^ uint32_t(y) * 0xC2B2AE3Du ^
                 uint32_t(z) * 0x27D4EB2Fu;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    return h ^ (h >> 15);
}

double gradDot(uint32_t h, double x, double y, double z) {
    // 12 edge directions of a cube (Perlin's improved noise).
    static const int g[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
                                 {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
    const int* d = g[h % 12];
    return d[0] * x + d[1] * y + d[2] * z;
}

double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

// Gradient noise; `period` > 0 wraps x and y (for a seamless UV-space map).
double noise3(double x, double y, double z, uint32_t seed, int period) {
    int xi = int(std::floor(x)), yi = int(std::floor(y)), zi = int(std::floor(z));
    double xf = x - xi, yf = y - yi, zf = z - zi;
    auto corner = [&](int dx, int dy, int dz) {
        int cx = xi + dx, cy = yi + dy;
        if (period > 0) cx = ((cx % period) + period) % period, cy = ((cy % period) + period) % period;
        return gradDot(hash(cx, cy, zi + dz, seed), xf - dx, yf - dy, zf - dz);
    };
    double u = fade(xf), v = fade(yf), w = fade(zf);
    auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
    return lerp(lerp(lerp(corner(0, 0, 0), corner(1, 0, 0), u), lerp(corner(0, 1, 0), corner(1, 1, 0), u), v),
                lerp(lerp(corner(0, 0, 1), corner(1, 0, 1), u), lerp(corner(0, 1, 1), corner(1, 1, 1), u), v), w);
}

double fbm(double x, double y, double z, int octaves, uint32_t seed, int period) {
    double sum = 0, amp = 0.5, norm = 0;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * noise3(x, y, z, seed + uint32_t(o), period);
        norm += amp;
        x *= 2, y *= 2, z *= 2, amp *= 0.5;
        if (period > 0) period *= 2;
    }
    return std::clamp(0.5 + 0.5 * sum / norm, 0.0, 1.0);
}

// Inverse of the bilinear map of quad (a, b, c, d) (counter-clockwise, (0,0) at a): the (s, t)
// whose image is p, or false when p is outside the quad.
bool inverseBilinear(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d, double& s, double& t) {
    auto cross2 = [](glm::dvec2 x, glm::dvec2 y) { return x.x * y.y - x.y * y.x; };
    glm::dvec2 e = b - a, f = d - a, g = a - b + c - d, h = p - a;
    double k2 = cross2(g, f), k1 = cross2(e, f) + cross2(h, g), k0 = cross2(h, e);
    double v;
    if (std::abs(k2) < 1e-12) {
        if (std::abs(k1) < 1e-18) return false;
        v = -k0 / k1;
    } else {
        double disc = k1 * k1 - 4 * k0 * k2;
        if (disc < 0) return false;
        double r = std::sqrt(disc);
        double v1 = (-k1 - r) / (2 * k2), v2 = (-k1 + r) / (2 * k2);
        v = (v1 >= -1e-9 && v1 <= 1 + 1e-9) ? v1 : v2;
    }
    glm::dvec2 den = e + g * v;
    double u = std::abs(den.x) > std::abs(den.y) ? (h.x - f.x * v) / den.x : (h.y - f.y * v) / den.y;
    s = u, t = v;
    const double eps = 1e-9;
    return u >= -eps && u <= 1 + eps && v >= -eps && v <= 1 + eps;
}

} // namespace

double fbm3(double x, double y, double z, int octaves, uint32_t seed) {
    return fbm(x, y, z, octaves, seed, 0);
}

// The unit UV tiles per axis one sub-quad is baked into (wrap-around, above).
constexpr double kMaxTiles = 4;

std::vector<float> bakeHeightmap(const Mesh& mesh, const HeightmapOptions& o) {
    const uint32_t N = o.size;
    std::vector<float> out(size_t(N) * N, 0.5f);
    if (o.kind == HeightmapKind::Uv) {
        const int period = std::max(1, int(std::lround(o.frequency)));
        for (uint32_t y = 0; y < N; ++y)
            for (uint32_t x = 0; x < N; ++x) {
                double u = (x + 0.5) / N, v = 1 - (y + 0.5) / N;
                out[size_t(y) * N + x] = float(fbm(u * period, v * period, 0.5, o.octaves, o.seed, period));
            }
        return out;
    }
    if (!mesh.hasUVs()) throwBadInput("the mesh has no texture coordinates to bake a height map into");
    glm::dvec3 lo(mesh.positions[0]), hi(mesh.positions[0]);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double scale = o.frequency / std::max(glm::length(hi - lo), 1e-30);
    std::vector<uint8_t> covered(size_t(N) * N, 0);
    // Every face as n sub-quads (corner, edge midpoints, centroid): exact for quads split in 4,
    // the same sub-faces ptex and the renderer's linear face-varying rule use.
    for (size_t f = 0; f < mesh.faceCount(); ++f) {
        auto fv = mesh.face(f);
        auto fu = mesh.faceUVs(f);
        const size_t n = fv.size();
        glm::dvec3 pc(0.0);
        glm::dvec2 uc(0.0);
        for (size_t k = 0; k < n; ++k) pc += mesh.positions[fv[k]], uc += mesh.uvs[fu[k]];
        pc /= double(n), uc /= double(n);
        for (size_t k = 0; k < n; ++k) {
            size_t kn = (k + 1) % n, kp = (k + n - 1) % n;
            glm::dvec3 P[4] = {mesh.positions[fv[k]], 0.5 * (mesh.positions[fv[k]] + mesh.positions[fv[kn]]), pc,
                               0.5 * (mesh.positions[fv[kp]] + mesh.positions[fv[k]])};
            glm::dvec2 U[4] = {mesh.uvs[fu[k]], 0.5 * (mesh.uvs[fu[k]] + mesh.uvs[fu[kn]]), uc,
                               0.5 * (mesh.uvs[fu[kp]] + mesh.uvs[fu[k]])};
            const glm::dvec2 lo2 = glm::min(glm::min(U[0], U[1]), glm::min(U[2], U[3]));
            const glm::dvec2 hi2 = glm::max(glm::max(U[0], U[1]), glm::max(U[2], U[3]));
            // The renderer samples the map with wrap-around: UVs in [1, 2] (a UDIM tile) read the
            // same texels as [0, 1], so each unit tile the sub-quad overlaps is baked shifted
            // into the map (at most kMaxTiles per axis: a face over more repeats itself).
            const glm::dvec2 firstTile = glm::floor(lo2);
            const glm::dvec2 tiles = glm::min(glm::floor(hi2) - firstTile + 1.0, glm::dvec2(kMaxTiles));
            for (int ty = 0; ty < int(tiles.y); ++ty)
                for (int tx = 0; tx < int(tiles.x); ++tx) {
                    const glm::dvec2 shift = firstTile + glm::dvec2(tx, ty);
                    const glm::dvec2 a = lo2 - shift, b = hi2 - shift;
                    const glm::dvec2 S[4] = {U[0] - shift, U[1] - shift, U[2] - shift, U[3] - shift};
                    // Texel ranges clamped as doubles first: |UV| N past 2^31 overflowed int.
                    auto texel = [N](double v) { return int(std::clamp(v, -1.0, double(N))); };
                    const int x0 = std::max(0, texel(std::floor(a.x * N - 0.5)));
                    const int x1 = std::min(int(N) - 1, texel(std::ceil(b.x * N - 0.5)));
                    const int y0 = std::max(0, texel(std::floor((1 - b.y) * N - 0.5)));
                    const int y1 = std::min(int(N) - 1, texel(std::ceil((1 - a.y) * N - 0.5)));
                    for (int y = y0; y <= y1; ++y)
                        for (int x = x0; x <= x1; ++x) {
                            glm::dvec2 p((x + 0.5) / N, 1 - (y + 0.5) / N);
                            double s, t;
                            if (!inverseBilinear(p, S[0], S[1], S[2], S[3], s, t)) continue;
                            glm::dvec3 q =
                                (1 - s) * (1 - t) * P[0] + s * (1 - t) * P[1] + s * t * P[2] + (1 - s) * t * P[3];
                            q = (q - lo) * scale;
                            out[size_t(y) * N + x] = float(fbm(q.x, q.y, q.z, o.octaves, o.seed, 0));
                            covered[size_t(y) * N + x] = 1;
                        }
                }
        }
    }
    // Pad: texels next to an island take the mean of their covered neighbours, a few rings out,
    // so bilinear lookups at island borders never read the empty background.
    for (uint32_t ring = 0; ring < o.padding; ++ring) {
        std::vector<uint8_t> next = covered;
        std::vector<float> values = out;
        for (uint32_t y = 0; y < N; ++y)
            for (uint32_t x = 0; x < N; ++x) {
                if (covered[size_t(y) * N + x]) continue;
                double sum = 0;
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int xx = int(x) + dx, yy = int(y) + dy;
                        if (xx < 0 || yy < 0 || xx >= int(N) || yy >= int(N)) continue;
                        if (!covered[size_t(yy) * N + xx]) continue;
                        sum += out[size_t(yy) * N + xx];
                        ++count;
                    }
                if (count) {
                    values[size_t(y) * N + x] = float(sum / count);
                    next[size_t(y) * N + x] = 1;
                }
            }
        covered.swap(next);
        out.swap(values);
    }
    return out;
}

} // namespace limn
