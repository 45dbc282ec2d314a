// One level of feature-adaptive Catmull-Clark refinement (paper 000, 4.1; Nießner et al. 2012):
// the sparse set of faces that exist at level l, their connectivity, sharpness and rules, where
// each face sits in its ptex face, and where each vertex came from.
#pragma once

#include "topology/features.h"
#include "topology/topology.h"

#include <cstdint>
#include <vector>

namespace limn {

// Where a face lies in OpenSubdiv's ptex parameterization (opensubdiv.md, "ptex indexing"):
// the face covers [u0, u0+size] x [v0, v0+size] of ptex face `ptex`, and its corner `rotation`
// is the one at (u0, v0); the corners then run counter-clockwise like the ptex axes
// (corner rotation+1 at (u0+size, v0)). size is a power of two, so everything is exact.
struct FaceFrame {
    uint32_t ptex = 0;
    uint8_t rotation = 0;
    double u0 = 0, v0 = 0, size = 1;
};

// How a vertex of level l > 0 was made from level l-1 (paper 000, 3.3).
enum class VertexOrigin : uint8_t { Base, Face, Edge, Vertex };

struct Level {
    uint32_t depth = 0;
    Topology topo;
    std::vector<float> edgeSharpness;   // per topology edge
    std::vector<float> vertexSharpness; // per vertex
    std::vector<uint8_t> vertexRule;    // VertexRule, valid for complete vertices
    std::vector<FaceFrame> frames;      // per face
    std::vector<uint8_t> noLimit;       // per face: hole, or no limit under boundary rule none
    std::vector<uint8_t> complete;      // per face: all children of its parent exist (the set D_l)
    // Links to level l-1 (empty at level 0).
    std::vector<VertexOrigin> vertexOrigin;
    std::vector<uint32_t> vertexParent; // parent face, edge or vertex index in level l-1
    std::vector<uint32_t> faceParent;
    // Vertices are numbered face points first, then edge points, then vertex points, so the GPU
    // passes of a level write contiguous ranges.
    uint32_t facePointCount = 0, edgePointCount = 0, vertexPointCount = 0;
};

// A stencil row: the vertex it computes is sum(weight[i] * source[index[i]]). Sources are
// level l-1 vertices, or face points of level l (edge and vertex points; `fromFacePoint`).
struct StencilEntry {
    uint32_t index;
    double weight;
    bool fromFacePoint;
};

// Flat rows (CSR): row r of a table is entries[start[r] .. start[r+1]).
struct LevelStencils {
    std::vector<uint32_t> faceStart{0}, faceVertices; // face points: parent vertices, averaged
    std::vector<uint32_t> edgeStart{0}, vertexStart{0};
    std::vector<StencilEntry> edgeEntries, vertexEntries;
};

// Builds level 0 from the control mesh topology: sharpness, rules, ptex frames, holes.
Level makeBaseLevel(Topology topo, Sharpness sharpness);

// Refines the `selected` faces of `parent` (all their children are created) and computes the
// stencils of every new vertex with OpenSubdiv's Sdc masks. Face points are also made for every
// face around a vertex of a selected face, because the edge and vertex rules read them.
// `ptexBase` maps a base face to its first ptex id (used when refining level 0).
// `childCorners` (optional, per parent vertex): only the children of the selected faces at the
// marked vertices are made, with only their vertices (and the face points those read), in the
// order refineLevel without it gives them. For a caller that reads nothing beyond those
// children and their stencils (the crease chains: crease_basis.cpp).
Level refineLevel(const Level& parent, const std::vector<uint8_t>& selected,
                  const SchemeOptions& options, const std::vector<uint32_t>& ptexBase,
                  LevelStencils& stencils, const std::vector<uint8_t>* childCorners = nullptr);

// refineLevel's level without its stencils (topology, sharpness, rules, frames), where the
// points are not needed.
Level refineLevelTopology(const Level& parent, const std::vector<uint8_t>& selected,
                          const SchemeOptions& options, const std::vector<uint32_t>& ptexBase,
                          const std::vector<uint8_t>* childCorners = nullptr);

// Faces sharing a vertex with a marked face: what must be refined with the marked faces so that
// their children have complete neighbourhoods (the isolation of tables.h).
std::vector<uint8_t> oneRing(const Topology& topo, const std::vector<uint8_t>& marked);

// The rule of every vertex from its sharpness and its incident edges' (Sdc::Crease).
void assignVertexRules(Level& level);

} // namespace limn
