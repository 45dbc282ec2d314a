#include "loop/bvh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
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

TriangleBvh::TriangleBvh(const std::vector<glm::dvec3>& P, const std::vector<Tri>& triangles) {
    const uint32_t n = static_cast<uint32_t>(triangles.size());
    if (n == 0) return;
    std::vector<glm::dvec3> centroid(n);
    for (uint32_t t = 0; t < n; ++t)
        centroid[t] = (P[triangles[t][0]] + P[triangles[t][1]] + P[triangles[t][2]]) / 3.0;
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    constexpr uint32_t kLeafSize = 4;
    struct Task {
        uint32_t node, begin, end;
    };
    nodes_.reserve(2 * (n / kLeafSize + 1));
    nodes_.push_back({});
    std::vector<Task> stack{{0, 0, n}};
    while (!stack.empty()) {
        Task task = stack.back();
        stack.pop_back();
        glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo, clo = lo, chi = hi;
        for (uint32_t i = task.begin; i < task.end; ++i) {
            const Tri& t = triangles[order[i]];
            for (uint32_t v : t) {
                lo = glm::min(lo, P[v]);
                hi = glm::max(hi, P[v]);
            }
            clo = glm::min(clo, centroid[order[i]]);
            chi = glm::max(chi, centroid[order[i]]);
        }
        nodes_[task.node].lo = lo;
        nodes_[task.node].hi = hi;
        if (task.end - task.begin <= kLeafSize) {
            nodes_[task.node].first = static_cast<uint32_t>(tris_.size());
            nodes_[task.node].count = task.end - task.begin;
            for (uint32_t i = task.begin; i < task.end; ++i) {
                const Tri& t = triangles[order[i]];
                tris_.push_back({P[t[0]], P[t[1]], P[t[2]]});
            }
            continue;
        }
        glm::dvec3 ext = chi - clo;
        int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
        uint32_t mid = task.begin + (task.end - task.begin) / 2;
        std::nth_element(order.begin() + task.begin, order.begin() + mid, order.begin() + task.end,
                         [&](uint32_t x, uint32_t y) {
                             if (centroid[x][axis] != centroid[y][axis])
                                 return centroid[x][axis] < centroid[y][axis];
                             return x < y;
                         });
        uint32_t left = static_cast<uint32_t>(nodes_.size());
        nodes_[task.node].first = left;
        nodes_[task.node].count = 0;
        nodes_.push_back({});
        nodes_.push_back({});
        stack.push_back({left + 1, mid, task.end});
        stack.push_back({left, task.begin, mid});
    }
}

namespace {

double boxSquaredDistance(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
    glm::dvec3 d = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
    return glm::dot(d, d);
}

} // namespace

double TriangleBvh::squaredDistance(const glm::dvec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    if (nodes_.empty()) return best;
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (boxSquaredDistance(p, node.lo, node.hi) >= best) continue;
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i)
                best = std::min(best, pointTriangleSquaredDistance(p, tris_[i][0], tris_[i][1],
                                                                   tris_[i][2]));
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
        if (dr < best) stack[top++] = r;
        if (dl < best) stack[top++] = l;
    }
    return best;
}

} // namespace limn::loop
