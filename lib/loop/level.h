// One level of Loop refinement seen by the rules: the half-edge topology of a TriMesh, which edges
// are sharp (boundary or crease) and which rule each vertex follows (math.md B.3, as OpenSubdiv's
// Sdc::Crease::Rule): smooth (no or one sharp edge: a dart), crease (two sharp edges) or corner
// (three or more sharp edges, a corner tag, or no faces at all).
#pragma once

#include "loop/trimesh.h"
#include "topology/topology.h"

#include <vector>

namespace limn::loop {

enum class VertexKind : uint8_t { Smooth, Crease, Corner };

class Level {
public:
    // Keeps a reference to `mesh`, which must outlive the Level. Throws Error(BadInput) if the
    // mesh is not manifold (fromMesh() gives the precise message first) or a crease names no edge.
    explicit Level(const TriMesh& mesh);

    const TriMesh& mesh() const { return *mesh_; }
    const Topology& topology() const { return topo_; }
    bool edgeSharp(uint32_t e) const { return edgeSharp_[e] != 0; }
    VertexKind kind(uint32_t v) const { return kind_[v]; }
    // The two neighbours along sharp edges of a crease vertex.
    VertexPair creaseNeighbours(uint32_t v) const { return creaseNeighbours_[v]; }

private:
    const TriMesh* mesh_;
    Topology topo_;
    std::vector<uint8_t> edgeSharp_;
    std::vector<VertexKind> kind_;
    std::vector<VertexPair> creaseNeighbours_;
};


// Topology of a triangle list (corner lists in CSR form, as limn::Topology wants them).
Topology triangleTopology(uint32_t vertexCount, const std::vector<Tri>& triangles);

} // namespace limn::loop
