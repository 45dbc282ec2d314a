// Connectivity of a polygon mesh as half-edges: one half-edge per face corner (half-edge h of face
// f runs from corner h to the next corner), undirected edges, twins across manifold edges, and
// ordered vertex fans. Built once per mesh (and per subdivision level); every consumer walks it
// instead of building its own adjacency.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace limn {

inline constexpr uint32_t kNone = 0xFFFFFFFFu;

class Topology {
  public:
    // `faceOffsets` has faceCount+1 entries; corners index vertices below `vertexCount`. The caller
    // guarantees the indices are valid (validateMesh); this never throws on topology oddities, it
    // records them (non-manifold edges and vertices, inconsistent orientation).
    Topology(uint32_t vertexCount, std::span<const uint32_t> faceOffsets,
             std::span<const uint32_t> faceVertices);
    // No vertices and no faces: the constructor's topology of an empty mesh, without its work
    // (every Level starts with one).
    Topology() : allQuads_(true), faceOffsets_{0}, vertexFaceOffsets_{0} {}
    // The same topology, array for array, for faces whose twins the caller already knows:
    // `twins[h]` is the half-edge opposite h, or kNone where h has none, and every edge is
    // manifold (one half-edge, or two in opposite directions). Catmull-Clark refinement knows
    // its children's twins from the parent's (level.cpp), which saves matching the edges, the
    // costliest part of the constructor, on every refined level.
    static Topology withTwins(uint32_t vertexCount, std::vector<uint32_t> faceOffsets,
                              std::vector<uint32_t> faceVertices, std::vector<uint32_t> twins);

    bool operator==(const Topology&) const = default;

    uint32_t vertexCount() const { return vertexCount_; }
    uint32_t faceCount() const { return static_cast<uint32_t>(faceOffsets_.size() - 1); }
    uint32_t edgeCount() const { return static_cast<uint32_t>(edgeVertices_.size()); }
    uint32_t halfedgeCount() const { return static_cast<uint32_t>(heVertex_.size()); }

    // Faces.
    uint32_t faceSize(uint32_t f) const { return faceOffsets_[f + 1] - faceOffsets_[f]; }
    uint32_t faceHalfedge(uint32_t f) const { return faceOffsets_[f]; } // corner 0
    std::span<const uint32_t> faceVertices(uint32_t f) const {
        return {heVertex_.data() + faceOffsets_[f], faceSize(f)};
    }

    // Half-edges. h runs from vertex(h) to vertex(next(h)) inside face(h).
    uint32_t vertex(uint32_t h) const { return heVertex_[h]; }
    uint32_t face(uint32_t h) const { return heFace_[h]; }
    uint32_t edge(uint32_t h) const { return heEdge_[h]; }
    uint32_t twin(uint32_t h) const { return heTwin_[h]; } // kNone on boundary / non-manifold
    uint32_t next(uint32_t h) const {
        if (allQuads_) return (h & ~3u) | ((h + 1) & 3u); // refined levels: arithmetic only
        uint32_t f = heFace_[h];
        return h + 1 == faceOffsets_[f + 1] ? faceOffsets_[f] : h + 1;
    }
    uint32_t prev(uint32_t h) const {
        if (allQuads_) return (h & ~3u) | ((h + 3) & 3u);
        uint32_t f = heFace_[h];
        return h == faceOffsets_[f] ? faceOffsets_[f + 1] - 1 : h - 1;
    }
    uint32_t destination(uint32_t h) const { return heVertex_[next(h)]; }
    // Index of half-edge h among its face's corners.
    uint32_t cornerIndex(uint32_t h) const { return allQuads_ ? h & 3u : h - faceOffsets_[heFace_[h]]; }
    // The next outgoing half-edge counter-clockwise around vertex(h) (seen from outside, for
    // counter-clockwise faces): across the edge of prev(h). kNone at a boundary.
    uint32_t rotateCCW(uint32_t h) const {
        uint32_t t = heTwin_[prev(h)];
        return t;
    }
    // The previous outgoing half-edge (clockwise): across the edge of h. kNone at a boundary.
    uint32_t rotateCW(uint32_t h) const {
        uint32_t t = heTwin_[h];
        return t == kNone ? kNone : next(t);
    }

    // Edges.
    std::array<uint32_t, 2> edgeVertices(uint32_t e) const { return edgeVertices_[e]; }
    uint32_t edgeFaceCount(uint32_t e) const { return edgeFaceCount_[e]; }
    uint32_t edgeHalfedge(uint32_t e) const { return edgeHalfedge_[e]; } // the first one
    bool edgeIsBoundary(uint32_t e) const { return edgeFaceCount_[e] == 1; }
    // More than two faces, or two faces that traverse it in the same direction.
    bool edgeIsNonManifold(uint32_t e) const { return edgeNonManifold_[e] != 0; }

    // Vertices.
    uint32_t vertexFaceCount(uint32_t v) const {
        return vertexFaceOffsets_[v + 1] - vertexFaceOffsets_[v];
    }
    // Every half-edge leaving v, in no particular order (works for non-manifold vertices too).
    std::span<const uint32_t> vertexOutgoing(uint32_t v) const {
        return {vertexOutgoing_.data() + vertexFaceOffsets_[v], vertexFaceCount(v)};
    }
    uint32_t vertexEdgeCount(uint32_t v) const { return vertexEdgeCount_[v]; }
    bool vertexIsBoundary(uint32_t v) const { return vertexFlags_[v] & kBoundary; }
    bool vertexIsNonManifold(uint32_t v) const { return vertexFlags_[v] & kNonManifold; }
    bool vertexIsIsolated(uint32_t v) const { return vertexFaceCount(v) == 0; }
    // For a manifold vertex: the outgoing half-edge to start a counter-clockwise walk from (the
    // boundary half-edge leaving v at a boundary vertex). kNone for isolated or non-manifold ones.
    uint32_t vertexFirstOutgoing(uint32_t v) const { return vertexFirst_[v]; }
    // The outgoing half-edges of a manifold vertex in counter-clockwise order (math.md A.2).
    void vertexRing(uint32_t v, std::vector<uint32_t>& out) const;

    // The edge joining a and b, or kNone. O(faces around a and b).
    uint32_t findEdge(uint32_t a, uint32_t b) const;

    uint32_t nonManifoldEdgeCount() const;
    uint32_t boundaryEdgeCount() const;

  private:
    void setFaces();    // heFace_ and allQuads_ from faceOffsets_
    void setVertices(); // every vertex array from the half-edges and edges
    enum : uint8_t { kBoundary = 1, kNonManifold = 2 };
    uint32_t vertexCount_ = 0;
    bool allQuads_ = false; // every face has 4 corners, so face f's half-edges are 4f..4f+3
    std::vector<uint32_t> faceOffsets_;
    std::vector<uint32_t> heVertex_, heFace_, heEdge_, heTwin_;
    std::vector<std::array<uint32_t, 2>> edgeVertices_;
    std::vector<uint32_t> edgeFaceCount_, edgeHalfedge_;
    std::vector<uint8_t> edgeNonManifold_;
    std::vector<uint32_t> vertexFaceOffsets_, vertexOutgoing_, vertexEdgeCount_, vertexFirst_;
    std::vector<uint8_t> vertexFlags_;
};

} // namespace limn
