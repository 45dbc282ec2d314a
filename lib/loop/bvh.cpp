#include "loop/bvh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

namespace limn::loop {

double pointTriangleSquaredDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                    const glm::dvec3& c) {
    auto dist2 = [&](const glm::dvec3& q) { return glm::dot(p - q, p - q); };
    glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return dist2(a);
    glm::dvec3 bp = p - b;
    double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return dist2(b);
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return dist2(a + ab * (d1 / (d1 - d3)));
    glm::dvec3 cp = p - c;
    double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return dist2(c);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return dist2(a + ac * (d2 / (d2 - d6)));
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return dist2(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    double denom = va + vb + vc;
    if (!(denom > 0)) { // degenerate triangle: nearest of its edges
        auto seg = [&](const glm::dvec3& s, const glm::dvec3& t) {
            glm::dvec3 st = t - s;
            double l2 = glm::dot(st, st);
            double u = l2 > 0 ? std::clamp(glm::dot(p - s, st) / l2, 0.0, 1.0) : 0.0;
            return dist2(s + st * u);
        };
        return std::min({seg(a, b), seg(b, c), seg(c, a)});
    }
    double v = vb / denom, w = vc / denom;
    return dist2(a + ab * v + ac * w);
}

namespace {

float roundDown(double x) {
    float f = static_cast<float>(x);
    return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundUp(double x) {
    float f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// Spreads the low 21 bits of x to every third bit (for a 63-bit Morton code).
uint64_t spreadBits(uint64_t x) {
    x &= 0x1FFFFF;
    x = (x | x << 32) & 0x1F00000000FFFFull;
    x = (x | x << 16) & 0x1F0000FF0000FFull;
    x = (x | x << 8) & 0x100F00F00F00F00Full;
    x = (x | x << 4) & 0x10C30C30C30C30C3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

} // namespace

// Triangles are sorted along a Morton curve of their centroids, then the tree splits that order
// recursively where the highest differing code bit flips (a "linear BVH"); boxes are unions of the
// children's. One sort and one linear pass, and the order (hence the tree) is deterministic.
TriangleBvh::TriangleBvh(const std::vector<glm::dvec3>& P, const std::vector<Tri>& triangles) {
    const uint32_t n = static_cast<uint32_t>(triangles.size());
    if (n == 0) return;
    std::vector<glm::dvec3> centroid(n);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
    for (uint32_t t = 0; t < n; ++t) {
        centroid[t] = (P[triangles[t][0]] + P[triangles[t][1]] + P[triangles[t][2]]) / 3.0;
        lo = glm::min(lo, centroid[t]);
        hi = glm::max(hi, centroid[t]);
    }
    glm::dvec3 scale = glm::dvec3(2097151.0) / glm::max(hi - lo, glm::dvec3(1e-300));
    std::vector<std::pair<uint64_t, uint32_t>> keys(n);
    for (uint32_t t = 0; t < n; ++t) {
        glm::dvec3 q = (centroid[t] - lo) * scale;
        keys[t] = {spreadBits(static_cast<uint64_t>(q.x)) | spreadBits(static_cast<uint64_t>(q.y)) << 1 |
                       spreadBits(static_cast<uint64_t>(q.z)) << 2,
                   t};
    }
    std::sort(keys.begin(), keys.end());
    tris_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        const Tri& t = triangles[keys[i].second];
        tris_[i] = {P[t[0]], P[t[1]], P[t[2]]};
    }
    std::vector<uint64_t> codes(n);
    for (uint32_t i = 0; i < n; ++i) codes[i] = keys[i].first;
    nodes_.reserve(2 * (n / kLeafSize + 1));
    nodes_.push_back({});
    build(codes, 0, 0, n);
}

void TriangleBvh::build(const std::vector<uint64_t>& codes, uint32_t node, uint32_t begin,
                        uint32_t end) {
    Node n;
    if (end - begin <= kLeafSize) {
        for (int k = 0; k < 3; ++k) {
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (uint32_t i = begin; i < end; ++i)
                for (const glm::dvec3& p : tris_[i]) {
                    lo = std::min(lo, p[k]);
                    hi = std::max(hi, p[k]);
                }
            n.lo[k] = roundDown(lo);
            n.hi[k] = roundUp(hi);
        }
        n.first = begin;
        n.count = end - begin;
        nodes_[node] = n;
        return;
    }
    const uint32_t left = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    // Split where the highest differing Morton bit flips (a spatial split, as in an octree), or in
    // the middle of a run of equal codes.
    uint32_t mid = begin + (end - begin) / 2;
    if (uint64_t diff = codes[begin] ^ codes[end - 1]; diff != 0) {
        uint64_t bit = uint64_t(1) << (63 - std::countl_zero(diff));
        mid = static_cast<uint32_t>(
            std::partition_point(codes.begin() + begin, codes.begin() + end,
                                 [bit](uint64_t c) { return (c & bit) == 0; }) -
            codes.begin());
    }
    build(codes, left, begin, mid);
    build(codes, left + 1, mid, end);
    for (int k = 0; k < 3; ++k) {
        n.lo[k] = std::min(nodes_[left].lo[k], nodes_[left + 1].lo[k]);
        n.hi[k] = std::max(nodes_[left].hi[k], nodes_[left + 1].hi[k]);
    }
    n.first = left;
    n.count = 0;
    nodes_[node] = n;
}

namespace {

double boxSquaredDistance(const glm::dvec3& p, const float* lo, const float* hi) {
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
        double d = std::max({static_cast<double>(lo[k]) - p[k], p[k] - static_cast<double>(hi[k]), 0.0});
        sum += d * d;
    }
    return sum;
}

} // namespace

double TriangleBvh::squaredDistance(const glm::dvec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    if (nodes_.empty()) return best;
    // Each entry carries its box distance, computed once when its parent pushed it.
    struct Entry {
        uint32_t node;
        double distance;
    };
    Entry stack[160]; // depth <= 63 bit splits + 32 halvings; each level leaves one entry
    int top = 0;
    stack[top++] = {0, boxSquaredDistance(p, nodes_[0].lo, nodes_[0].hi)};
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.distance >= best) continue;
        const Node& node = nodes_[entry.node];
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i)
                best = std::min(best, pointTriangleSquaredDistance(p, tris_[i][0], tris_[i][1], tris_[i][2]));
            continue;
        }
        uint32_t l = node.first, r = node.first + 1;
        double dl = boxSquaredDistance(p, nodes_[l].lo, nodes_[l].hi);
        double dr = boxSquaredDistance(p, nodes_[r].lo, nodes_[r].hi);
        if (dl > dr) {
            std::swap(l, r);
            std::swap(dl, dr);
        }
        // Visit the nearer child first: push it last.
        if (dr < best) stack[top++] = {r, dr};
        if (dl < best) stack[top++] = {l, dl};
    }
    return best;
}

} // namespace limn::loop
