#include "loop/level.h"

#include "base/error.h"

namespace limn::loop {

Topology triangleTopology(uint32_t vertexCount, const std::vector<Tri>& triangles) {
    std::vector<uint32_t> offsets(triangles.size() + 1), corners(triangles.size() * 3);
    for (size_t f = 0; f <= triangles.size(); ++f) offsets[f] = static_cast<uint32_t>(3 * f);
    for (size_t f = 0; f < triangles.size(); ++f)
        for (int i = 0; i < 3; ++i) corners[3 * f + i] = triangles[f][i];
    return Topology(vertexCount, offsets, corners);
}

Level::Level(const TriMesh& mesh)
    : mesh_(&mesh), topo_(triangleTopology(mesh.vertexCount(), mesh.triangles)) {
    const uint32_t V = topo_.vertexCount(), E = topo_.edgeCount();
    if (topo_.nonManifoldEdgeCount() != 0)
        throwBadInput("the mesh has non-manifold or inconsistently oriented edges");
    edgeSharp_.assign(E, 0);
    for (uint32_t e = 0; e < E; ++e) edgeSharp_[e] = topo_.edgeIsBoundary(e) ? 1 : 0;
    for (const VertexPair& c : mesh.creases) {
        uint32_t e = topo_.findEdge(c[0], c[1]);
        if (e == kNone)
            throwBadInput("crease (" + std::to_string(c[0]) + "," + std::to_string(c[1]) +
                          ") names no edge of the mesh");
        edgeSharp_[e] = 1;
    }
    // Count sharp edges per vertex and remember the first two neighbours along them.
    std::vector<uint8_t> sharpCount(V, 0);
    creaseNeighbours_.assign(V, {kNone, kNone});
    for (uint32_t e = 0; e < E; ++e) {
        if (!edgeSharp_[e]) continue;
        auto [a, b] = topo_.edgeVertices(e);
        for (auto [v, other] : {std::pair{a, b}, std::pair{b, a}}) {
            if (sharpCount[v] < 2) creaseNeighbours_[v][sharpCount[v]] = other;
            if (sharpCount[v] < 255) ++sharpCount[v];
        }
    }
    kind_.assign(V, VertexKind::Smooth);
    for (uint32_t v = 0; v < V; ++v) {
        if (topo_.vertexIsNonManifold(v))
            throwBadInput("vertex " + std::to_string(v) + " is non-manifold");
        bool corner = (v < mesh.corners.size() && mesh.corners[v]) || topo_.vertexIsIsolated(v);
        if (corner || sharpCount[v] >= 3)
            kind_[v] = VertexKind::Corner;
        else if (sharpCount[v] == 2)
            kind_[v] = VertexKind::Crease;
    }
}

} // namespace limn::loop
