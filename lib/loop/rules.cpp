#include "loop/rules.h"

#include <cmath>
#include <numbers>

namespace limn::loop {

double loopAlpha(int k) {
    if (k == 6) return 0.375; // exact in the regular case (cos(π/3) is not exactly 1/2)
    double c = 3.0 + 2.0 * std::cos(2.0 * std::numbers::pi / k);
    return 0.625 - c * c / 64.0;
}

double limitOmega(int k) { return 3.0 * k / (8.0 * loopAlpha(k)); }

namespace {

// Sum of the neighbours of a smooth vertex (one per outgoing half-edge: a smooth vertex is
// interior, so its outgoing half-edges and its edges correspond one to one) and their count.
glm::dvec3 neighbourSum(const Level& level, uint32_t v, int& k) {
    const Topology& topo = level.topology();
    const auto& P = level.mesh().positions;
    glm::dvec3 sum(0.0);
    k = 0;
    for (uint32_t h : topo.vertexOutgoing(v)) {
        sum += P[topo.destination(h)];
        ++k;
    }
    return sum;
}

} // namespace

std::vector<glm::dvec3> evenPositions(const Level& level) {
    const auto& P = level.mesh().positions;
    std::vector<glm::dvec3> out(P.size());
    for (uint32_t v = 0; v < P.size(); ++v) {
        switch (level.kind(v)) {
        case VertexKind::Corner: out[v] = P[v]; break;
        case VertexKind::Crease: {
            auto [a, b] = level.creaseNeighbours(v);
            out[v] = (P[a] + 6.0 * P[v] + P[b]) / 8.0;
            break;
        }
        case VertexKind::Smooth: {
            int k = 0;
            glm::dvec3 sum = neighbourSum(level, v, k);
            double alpha = loopAlpha(k);
            out[v] = (1.0 - alpha) * P[v] + (alpha / k) * sum;
            break;
        }
        }
    }
    return out;
}

std::vector<glm::dvec3> oddPositions(const Level& level) {
    const Topology& topo = level.topology();
    const auto& P = level.mesh().positions;
    std::vector<glm::dvec3> out(topo.edgeCount());
    for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
        uint32_t h = topo.edgeHalfedge(e);
        glm::dvec3 a = P[topo.vertex(h)], b = P[topo.destination(h)];
        if (level.edgeSharp(e)) {
            out[e] = 0.5 * (a + b);
            continue;
        }
        // The vertices opposite the edge in its two triangles.
        glm::dvec3 c = P[topo.vertex(topo.prev(h))];
        glm::dvec3 d = P[topo.vertex(topo.prev(topo.twin(h)))];
        out[e] = 0.375 * (a + b) + 0.125 * (c + d);
    }
    return out;
}

std::vector<glm::dvec3> limitPositions(const Level& level) {
    const auto& P = level.mesh().positions;
    std::vector<glm::dvec3> out(P.size());
    for (uint32_t v = 0; v < P.size(); ++v) {
        switch (level.kind(v)) {
        case VertexKind::Corner: out[v] = P[v]; break;
        case VertexKind::Crease: {
            auto [a, b] = level.creaseNeighbours(v);
            out[v] = (P[a] + 4.0 * P[v] + P[b]) / 6.0;
            break;
        }
        case VertexKind::Smooth: {
            int k = 0;
            glm::dvec3 sum = neighbourSum(level, v, k);
            double omega = limitOmega(k);
            out[v] = (omega * P[v] + sum) / (omega + k);
            break;
        }
        }
    }
    return out;
}

} // namespace limn::loop
