#include "loop/metric.h"

#include <glm/geometric.hpp>

namespace limn::loop {

namespace {

glm::dvec3 unitNormal(const Topology& topo, const std::vector<glm::dvec3>& P, uint32_t h) {
    glm::dvec3 a = P[topo.vertex(h)], b = P[topo.vertex(topo.next(h))],
               c = P[topo.vertex(topo.prev(h))];
    glm::dvec3 n = glm::cross(b - a, c - a);
    double len = glm::length(n);
    return len > 0 ? n / len : glm::dvec3(0.0);
}

} // namespace

std::vector<glm::dvec3> oddLimitPositions(const Level& level, const std::vector<glm::dvec3>& even,
                                          const std::vector<glm::dvec3>& odd) {
    const Topology& topo = level.topology();
    std::vector<glm::dvec3> limit(topo.edgeCount());
    for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
        const uint32_t h = topo.edgeHalfedge(e);
        const glm::dvec3& a1 = even[topo.vertex(h)];
        const glm::dvec3& b1 = even[topo.destination(h)];
        if (level.edgeSharp(e)) {
            limit[e] = (a1 + 4.0 * odd[e] + b1) / 6.0;
            continue;
        }
        const uint32_t g = topo.twin(h);
        glm::dvec3 ring = a1 + b1 + odd[topo.edge(topo.next(h))] + odd[topo.edge(topo.prev(h))] +
                          odd[topo.edge(topo.next(g))] + odd[topo.edge(topo.prev(g))];
        limit[e] = 0.5 * odd[e] + ring / 12.0;
    }
    return limit;
}

std::vector<double> edgeDistances(const Level& level, const std::vector<glm::dvec3>& even,
                                  const std::vector<glm::dvec3>& odd, Metric metric) {
    const Topology& topo = level.topology();
    const auto& P = level.mesh().positions;
    const std::vector<glm::dvec3> limit = oddLimitPositions(level, even, odd);
    std::vector<double> d(topo.edgeCount());
    for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
        const uint32_t h = topo.edgeHalfedge(e);
        const glm::dvec3& a = P[topo.vertex(h)];
        const glm::dvec3& b = P[topo.destination(h)];
        glm::dvec3 r = (metric == Metric::Chord ? 0.5 * (a + b) : odd[e]) - limit[e];
        if (metric == Metric::Normal) {
            if (level.edgeSharp(e)) { // drop the part along the edge: the curve's own drift
                glm::dvec3 t = b - a;
                double len = glm::length(t);
                if (len > 0) r -= glm::dot(r, t / len) * (t / len);
            } else {
                glm::dvec3 n = unitNormal(topo, P, h) + unitNormal(topo, P, topo.twin(h));
                double len = glm::length(n);
                if (len > 0) r = glm::dot(r, n / len) * (n / len);
            }
        }
        d[e] = glm::length(r);
    }
    return d;
}

} // namespace limn::loop
