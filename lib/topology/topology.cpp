#include "topology/topology.h"

#include <algorithm>
#include <numeric>

namespace limn {

Topology::Topology(uint32_t vertexCount, std::span<const uint32_t> faceOffsets,
                   std::span<const uint32_t> faceVertices)
    : vertexCount_(vertexCount), faceOffsets_(faceOffsets.begin(), faceOffsets.end()),
      heVertex_(faceVertices.begin(), faceVertices.end()) {
    const uint32_t H = static_cast<uint32_t>(heVertex_.size());
    const uint32_t F = faceCount();
    heFace_.resize(H);
    for (uint32_t f = 0; f < F; ++f)
        for (uint32_t h = faceOffsets_[f]; h < faceOffsets_[f + 1]; ++h) heFace_[h] = f;

    // Group half-edges by undirected edge: sort (min,max,h) keys. Sorting keeps edge numbering
    // deterministic; edges are then numbered in order of their first half-edge.
    std::vector<std::pair<uint64_t, uint32_t>> keys(H);
    for (uint32_t h = 0; h < H; ++h) {
        uint32_t a = heVertex_[h], b = heVertex_[next(h)];
        uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        keys[h] = {key, h};
    }
    std::sort(keys.begin(), keys.end());
    heEdge_.assign(H, kNone);
    heTwin_.assign(H, kNone);
    std::vector<uint32_t> groupFirst; // index into keys of each group's start, in group order
    for (uint32_t i = 0; i < H;) {
        uint32_t j = i;
        while (j < H && keys[j].first == keys[i].first) ++j;
        groupFirst.push_back(i);
        i = j;
    }
    groupFirst.push_back(H);
    // Number edges by their smallest half-edge (= first appearance in face order).
    std::vector<uint32_t> groupOrder(groupFirst.size() - 1);
    std::iota(groupOrder.begin(), groupOrder.end(), 0u);
    std::sort(groupOrder.begin(), groupOrder.end(), [&](uint32_t x, uint32_t y) {
        return keys[groupFirst[x]].second < keys[groupFirst[y]].second;
    });
    const uint32_t E = static_cast<uint32_t>(groupOrder.size());
    edgeVertices_.resize(E);
    edgeFaceCount_.resize(E);
    edgeHalfedge_.resize(E);
    edgeNonManifold_.assign(E, 0);
    for (uint32_t e = 0; e < E; ++e) {
        uint32_t g = groupOrder[e];
        uint32_t begin = groupFirst[g], end = groupFirst[g + 1];
        uint32_t h0 = keys[begin].second; // smallest h (pairs sort by h within equal keys)
        edgeHalfedge_[e] = h0;
        edgeVertices_[e] = {heVertex_[h0], heVertex_[next(h0)]};
        edgeFaceCount_[e] = end - begin;
        for (uint32_t k = begin; k < end; ++k) heEdge_[keys[k].second] = e;
        if (end - begin == 2) {
            uint32_t h1 = keys[begin + 1].second;
            if (heVertex_[h0] != heVertex_[h1]) { // opposite directions: a proper twin pair
                heTwin_[h0] = h1;
                heTwin_[h1] = h0;
            } else {
                edgeNonManifold_[e] = 1; // two faces disagree about orientation
            }
        } else if (end - begin > 2) {
            edgeNonManifold_[e] = 1;
        }
    }

    // Vertex -> outgoing half-edges (CSR, in half-edge order).
    vertexFaceOffsets_.assign(vertexCount_ + 1, 0);
    for (uint32_t h = 0; h < H; ++h) ++vertexFaceOffsets_[heVertex_[h] + 1];
    for (uint32_t v = 0; v < vertexCount_; ++v) vertexFaceOffsets_[v + 1] += vertexFaceOffsets_[v];
    vertexOutgoing_.resize(H);
    {
        std::vector<uint32_t> fill(vertexFaceOffsets_.begin(), vertexFaceOffsets_.end() - 1);
        for (uint32_t h = 0; h < H; ++h) vertexOutgoing_[fill[heVertex_[h]]++] = h;
    }
    vertexEdgeCount_.assign(vertexCount_, 0);
    for (uint32_t e = 0; e < E; ++e) {
        ++vertexEdgeCount_[edgeVertices_[e][0]];
        ++vertexEdgeCount_[edgeVertices_[e][1]];
    }

    // Boundary / non-manifold flags and the start of each counter-clockwise fan.
    vertexFlags_.assign(vertexCount_, 0);
    vertexFirst_.assign(vertexCount_, kNone);
    for (uint32_t e = 0; e < E; ++e) {
        uint8_t flag = edgeNonManifold_[e] ? kNonManifold : edgeFaceCount_[e] == 1 ? kBoundary : 0;
        vertexFlags_[edgeVertices_[e][0]] |= flag;
        vertexFlags_[edgeVertices_[e][1]] |= flag;
    }
    for (uint32_t v = 0; v < vertexCount_; ++v) {
        auto out = vertexOutgoing(v);
        if (out.empty() || (vertexFlags_[v] & kNonManifold)) continue;
        // Start at a half-edge with no clockwise neighbour (a boundary half-edge leaving v), or
        // anywhere on a closed fan. A manifold vertex's fan must then reach every face once.
        uint32_t start = out[0];
        for (uint32_t h : out)
            if (heTwin_[h] == kNone) {
                start = h;
                break;
            }
        uint32_t reached = 0, h = start;
        do {
            ++reached;
            h = rotateCCW(h);
        } while (h != kNone && h != start && reached <= out.size());
        bool closed = h == start;
        bool boundary = vertexFlags_[v] & kBoundary;
        if (reached != out.size() || closed == boundary) {
            vertexFlags_[v] |= kNonManifold; // several fans meet here ("bow tie")
            continue;
        }
        vertexFirst_[v] = start;
    }
}

void Topology::vertexRing(uint32_t v, std::vector<uint32_t>& out) const {
    out.clear();
    uint32_t start = vertexFirst_[v];
    if (start == kNone) return;
    uint32_t h = start;
    do {
        out.push_back(h);
        h = rotateCCW(h);
    } while (h != kNone && h != start);
}

uint32_t Topology::nonManifoldEdgeCount() const {
    return static_cast<uint32_t>(std::count(edgeNonManifold_.begin(), edgeNonManifold_.end(), 1));
}

uint32_t Topology::boundaryEdgeCount() const {
    return static_cast<uint32_t>(std::count(edgeFaceCount_.begin(), edgeFaceCount_.end(), 1u));
}

} // namespace limn
