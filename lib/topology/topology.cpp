#include "topology/topology.h"

#include <algorithm>

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

    // Group half-edges by undirected edge. A counting sort buckets them by their smaller
    // endpoint (each bucket then lists its half-edges in increasing order), and each bucket,
    // a handful of half-edges, is sorted by the larger endpoint. A group's leader is its first
    // half-edge; edges are numbered in the order of their leaders, i.e. of first appearance in
    // face order, so the numbering is deterministic. (One global sort of all half-edges cost
    // three times as much on a 100k-face mesh.)
    std::vector<uint32_t> heDestination(H);
    for (uint32_t f = 0; f < F; ++f) {
        uint32_t begin = faceOffsets_[f], end = faceOffsets_[f + 1];
        if (begin == end) continue;
        for (uint32_t h = begin; h + 1 < end; ++h) heDestination[h] = heVertex_[h + 1];
        heDestination[end - 1] = heVertex_[begin];
    }
    std::vector<uint32_t> bucketStart(vertexCount_ + 1, 0);
    for (uint32_t h = 0; h < H; ++h) ++bucketStart[std::min(heVertex_[h], heDestination[h]) + 1];
    for (uint32_t v = 0; v < vertexCount_; ++v) bucketStart[v + 1] += bucketStart[v];
    std::vector<std::pair<uint32_t, uint32_t>> bucket(H); // (larger endpoint, half-edge)
    {
        std::vector<uint32_t> fill(bucketStart.begin(), bucketStart.end() - 1);
        for (uint32_t h = 0; h < H; ++h) {
            uint32_t a = heVertex_[h], b = heDestination[h];
            bucket[fill[std::min(a, b)]++] = {std::max(a, b), h};
        }
    }
    // leader[h]: the first half-edge of h's edge; groupSize: at leaders, the edge's half-edges.
    std::vector<uint32_t> leader(H), groupSize(H, 0);
    for (uint32_t v = 0; v < vertexCount_; ++v) {
        auto begin = bucket.begin() + bucketStart[v], end = bucket.begin() + bucketStart[v + 1];
        // A bucket holds about as many half-edges as its vertex has edges: insertion sort,
        // unless a pole (or hostile input) makes it large.
        if (end - begin > 16) {
            std::sort(begin, end);
        } else {
            for (auto i = begin + (begin != end); i < end; ++i)
                for (auto j = i; j > begin && *j < *(j - 1); --j) std::iter_swap(j, j - 1);
        }
        for (auto run = begin; run != end;) {
            auto stop = run;
            while (stop != end && stop->first == run->first) ++stop;
            uint32_t h0 = run->second;
            for (auto it = run; it != stop; ++it) leader[it->second] = h0;
            groupSize[h0] = static_cast<uint32_t>(stop - run);
            run = stop;
        }
    }
    heEdge_.assign(H, kNone);
    heTwin_.assign(H, kNone);
    for (uint32_t h = 0; h < H; ++h) {
        uint32_t l = leader[h];
        if (l != h) {
            uint32_t e = heEdge_[l]; // the leader came first
            heEdge_[h] = e;
            if (edgeFaceCount_[e] == 2) {
                if (heVertex_[l] != heVertex_[h]) { // opposite directions: a proper twin pair
                    heTwin_[h] = l;
                    heTwin_[l] = h;
                } else {
                    edgeNonManifold_[e] = 1; // two faces disagree about orientation
                }
            }
            continue;
        }
        heEdge_[h] = static_cast<uint32_t>(edgeVertices_.size());
        edgeHalfedge_.push_back(h);
        edgeVertices_.push_back({heVertex_[h], heDestination[h]});
        edgeFaceCount_.push_back(groupSize[h]);
        edgeNonManifold_.push_back(groupSize[h] > 2 ? 1 : 0);
    }
    const auto E = static_cast<uint32_t>(edgeVertices_.size());

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
