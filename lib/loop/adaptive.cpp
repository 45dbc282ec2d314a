#include "loop/adaptive.h"

#include "loop/hierarchy.h"
#include "loop/rules.h"

#include <glm/geometric.hpp>

#include <limits>

namespace limn::loop {

std::vector<uint8_t> splitDecisions(const Level& level, const std::vector<glm::dvec3>& even,
                                    const std::vector<glm::dvec3>& odd,
                                    const AdaptiveOptions& options, double diagonal) {
    const Topology& topo = level.topology();
    std::vector<uint8_t> split(topo.edgeCount(), 1);
    if (options.uniform) return split;
    std::vector<double> d = edgeDistances(level, even, odd, options.metric);
    const auto& P = level.mesh().positions;
    for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
        double scale = diagonal;
        if (options.normalization == Normalization::EdgeLength) {
            auto [a, b] = topo.edgeVertices(e);
            scale = glm::length(P[a] - P[b]);
        }
        // A zero scale (degenerate edge or mesh) makes any positive distance infinitely large.
        double f = scale > 0 ? d[e] / scale : (d[e] > 0 ? std::numeric_limits<double>::infinity() : 0);
        split[e] = f >= options.epsilon ? 1 : 0;
    }
    return split;
}

AdaptiveResult subdivide(const TriMesh& control, const AdaptiveOptions& options) {
    if (options.positions == Positions::Exact && !options.uniform)
        return subdivideOnHierarchy(control, options);
    AdaptiveResult result;
    result.mesh = control;
    const double diagonal = boundingBoxDiagonal(control.positions);
    for (int l = 1; l <= options.levels; ++l) {
        LevelStats stats;
        stats.level = l;
        Refinement r;
        {
            Level level(result.mesh);
            std::vector<glm::dvec3> even = evenPositions(level), odd = oddPositions(level);
            std::vector<uint8_t> split = splitDecisions(level, even, odd, options, diagonal);
            stats.edges = level.topology().edgeCount();
            for (uint8_t s : split) stats.splitEdges += s;
            if (stats.splitEdges > 0) r = refine(level, split, options.evenUpdate, even, odd);
        }
        if (stats.splitEdges > 0) result.mesh = std::move(r.mesh);
        stats.vertices = result.mesh.vertexCount();
        stats.faces = result.mesh.triangleCount();
        result.levels.push_back(stats);
        if (stats.splitEdges == 0) break;
    }
    return result;
}

} // namespace limn::loop
