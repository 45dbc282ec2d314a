#include "topology/topology.h"

#include <algorithm>

namespace limn {

Topology::Topology(uint32_t vertexCount, std::span<const uint32_t> faceOffsets,
                   std::span<const uint32_t> faceVertices)
    : vertexCount_(vertexCount), faceOffsets_(faceOffsets.begin(), faceOffsets.end()),
      heVertex_(faceVertices.begin(), faceVertices.end()) {
    const uint32_t H = static_cast<uint32_t>(heVertex_.size());
    setFaces();

    // Group half-edges by undirected edge in linear time: bucket them by their smaller vertex
    // (counting sort keeps half-edge order inside a bucket), then match larger vertices within
    // the bucket. Edges are numbered in order of their first half-edge, so numbering is
    // deterministic and follows face order.
    std::vector<uint32_t> bucketStart(vertexCount_ + 1, 0), bucket(H), other(H);
    for (uint32_t h = 0; h < H; ++h) {
        uint32_t a = heVertex_[h], b = heVertex_[next(h)];
        other[h] = std::max(a, b);
        ++bucketStart[std::min(a, b) + 1];
    }
    for (uint32_t v = 0; v < vertexCount_; ++v) bucketStart[v + 1] += bucketStart[v];
    {
        std::vector<uint32_t> fill(bucketStart.begin(), bucketStart.end() - 1);
        for (uint32_t h = 0; h < H; ++h)
            bucket[fill[std::min(heVertex_[h], heVertex_[next(h)])]++] = h;
    }
    // Within a bucket, half-edges with the same larger vertex form one edge: chain them in
    // bucket (= half-edge) order through a slot per larger vertex, reset after each bucket. One
    // pass over each bucket, so a vertex shared by many edges (an n-gon's centre after one
    // level) costs linear time, not its bucket size per edge.
    std::vector<uint32_t> nextInEdge(H, kNone), lastInEdge(H), slot(vertexCount_, kNone);
    uint32_t edgeCount = 0; // counted here so that the edge arrays are allocated once
    for (uint32_t v = 0; v < vertexCount_; ++v) {
        for (uint32_t i = bucketStart[v]; i < bucketStart[v + 1]; ++i) {
            const uint32_t h = bucket[i];
            uint32_t& first = slot[other[h]];
            if (first == kNone) {
                ++edgeCount;
                first = h;
                lastInEdge[h] = h;
            } else {
                nextInEdge[lastInEdge[first]] = h;
                lastInEdge[first] = h;
            }
        }
        for (uint32_t i = bucketStart[v]; i < bucketStart[v + 1]; ++i) slot[other[bucket[i]]] = kNone;
    }
    heEdge_.assign(H, kNone);
    heTwin_.assign(H, kNone);
    edgeHalfedge_.reserve(edgeCount);
    edgeVertices_.reserve(edgeCount);
    edgeFaceCount_.reserve(edgeCount);
    edgeNonManifold_.reserve(edgeCount);
    uint32_t group[64];
    for (uint32_t h0 = 0; h0 < H; ++h0) {
        if (heEdge_[h0] != kNone) continue; // h0 is the first half-edge of a new edge
        const uint32_t e = static_cast<uint32_t>(edgeVertices_.size());
        uint32_t n = 0, count = 0;
        for (uint32_t h = h0; h != kNone; h = nextInEdge[h]) {
            heEdge_[h] = e;
            if (n < 64) group[n++] = h;
            ++count;
        }
        edgeHalfedge_.push_back(h0);
        edgeVertices_.push_back({heVertex_[h0], heVertex_[next(h0)]});
        edgeFaceCount_.push_back(count);
        uint8_t nonManifold = 0;
        if (count == 2) {
            uint32_t h1 = group[0] == h0 ? group[1] : group[0];
            if (heVertex_[h0] != heVertex_[h1]) { // opposite directions: a proper twin pair
                heTwin_[h0] = h1;
                heTwin_[h1] = h0;
            } else {
                nonManifold = 1; // two faces disagree about orientation
            }
        } else if (count > 2) {
            nonManifold = 1;
        }
        edgeNonManifold_.push_back(nonManifold);
    }
    setVertices();
}

Topology Topology::withTwins(uint32_t vertexCount, std::vector<uint32_t> faceOffsets,
                             std::vector<uint32_t> faceVertices, std::vector<uint32_t> twins) {
    Topology t;
    t.vertexCount_ = vertexCount;
    t.faceOffsets_ = std::move(faceOffsets);
    t.heVertex_ = std::move(faceVertices);
    t.heTwin_ = std::move(twins);
    t.setFaces();
    // Edges numbered in order of their first half-edge, as the constructor numbers them: a
    // half-edge starts an edge unless its twin comes before it (and then already named it).
    const uint32_t H = t.halfedgeCount();
    const uint32_t* twin = t.heTwin_.data();
    uint32_t E = 0;
    for (uint32_t h = 0; h < H; ++h) E += twin[h] > h; // kNone is above every half-edge
    t.heEdge_.resize(H);
    t.edgeHalfedge_.resize(E);
    t.edgeVertices_.resize(E);
    t.edgeFaceCount_.resize(E);
    t.edgeNonManifold_.assign(E, 0);
    uint32_t *heEdge = t.heEdge_.data(), *edgeHalfedge = t.edgeHalfedge_.data(), *faceCount = t.edgeFaceCount_.data();
    std::array<uint32_t, 2>* edgeVertices = t.edgeVertices_.data();
    const uint32_t* heVertex = t.heVertex_.data();
    for (uint32_t h = 0, e = 0; h < H; ++h) {
        const uint32_t tw = twin[h];
        if (tw < h) continue; // named by its twin
        heEdge[h] = e;
        if (tw != kNone) heEdge[tw] = e;
        edgeHalfedge[e] = h;
        edgeVertices[e] = {heVertex[h], heVertex[t.next(h)]};
        faceCount[e] = tw == kNone ? 1 : 2;
        ++e;
    }
    t.setVertices();
    return t;
}

// The loops below read and write through local pointers: the flag bytes they store could alias
// the vectors' own pointers for the compiler, which would reload them at every step.
void Topology::setFaces() {
    const uint32_t F = faceCount();
    heFace_.resize(heVertex_.size());
    const uint32_t* offsets = faceOffsets_.data();
    uint32_t* heFace = heFace_.data();
    bool quads = true;
    for (uint32_t f = 0; f <= F; ++f) quads &= offsets[f] == 4 * f;
    allQuads_ = quads;
    if (quads) {
        for (uint32_t h = 0; h < 4 * F; ++h) heFace[h] = h / 4;
        return;
    }
    for (uint32_t f = 0; f < F; ++f)
        for (uint32_t h = offsets[f]; h < offsets[f + 1]; ++h) heFace[h] = f;
}

void Topology::setVertices() {
    const uint32_t H = halfedgeCount(), E = edgeCount(), V = vertexCount_;
    const uint32_t* heVertex = heVertex_.data();
    const uint32_t* heTwin = heTwin_.data();
    const uint32_t* heFace = heFace_.data();
    const uint32_t* faceOffsets = faceOffsets_.data();
    const std::array<uint32_t, 2>* edgeVertices = edgeVertices_.data();
    const uint32_t* edgeFaceCount = edgeFaceCount_.data();
    const uint8_t* edgeNonManifold = edgeNonManifold_.data();
    const bool quads = allQuads_;

    // Vertex -> outgoing half-edges (CSR, in half-edge order).
    vertexFaceOffsets_.assign(V + 1, 0);
    uint32_t* start = vertexFaceOffsets_.data();
    for (uint32_t h = 0; h < H; ++h) ++start[heVertex[h] + 1];
    for (uint32_t v = 0; v < V; ++v) start[v + 1] += start[v];
    vertexOutgoing_.resize(H);
    uint32_t* outgoing = vertexOutgoing_.data();
    {
        std::vector<uint32_t> fill(start, start + V);
        uint32_t* at = fill.data();
        for (uint32_t h = 0; h < H; ++h) outgoing[at[heVertex[h]]++] = h;
    }
    vertexEdgeCount_.assign(V, 0);
    uint32_t* edgeCount = vertexEdgeCount_.data();
    for (uint32_t e = 0; e < E; ++e) {
        ++edgeCount[edgeVertices[e][0]];
        ++edgeCount[edgeVertices[e][1]];
    }

    // Boundary / non-manifold flags and the start of each counter-clockwise fan.
    vertexFlags_.assign(V, 0);
    vertexFirst_.assign(V, kNone);
    uint8_t* flags = vertexFlags_.data();
    uint32_t* first = vertexFirst_.data();
    for (uint32_t e = 0; e < E; ++e) {
        uint8_t flag = edgeNonManifold[e] ? kNonManifold : edgeFaceCount[e] == 1 ? kBoundary : 0;
        flags[edgeVertices[e][0]] |= flag;
        flags[edgeVertices[e][1]] |= flag;
    }
    // Each vertex's outgoing half-edges fall into fans: cycles, or paths from a half-edge with
    // no clockwise neighbour (its twin missing) to one with no counter-clockwise one. A manifold
    // vertex has one fan, its start the path's first half-edge, or the first outgoing one (in
    // half-edge order) on a cycle: walk counter-clockwise from that one, and on reaching the end
    // of a path, clockwise back to its start.
    auto fans = [&](auto prev) {
        for (uint32_t v = 0; v < V; ++v) {
            const uint32_t count = start[v + 1] - start[v];
            if (count == 0 || (flags[v] & kNonManifold)) continue;
            const uint32_t h0 = outgoing[start[v]];
            uint32_t reached = 0, h = h0;
            do {
                ++reached;
                h = heTwin[prev(h)]; // rotateCCW
            } while (h != kNone && h != h0 && reached <= count);
            const bool closed = h == h0;
            uint32_t begin = h0;
            if (!closed)
                for (uint32_t t = heTwin[h0]; t != kNone && reached <= count; t = heTwin[begin]) {
                    begin = quads ? (t & ~3u) | ((t + 1) & 3u) : next(t); // rotateCW
                    ++reached;
                }
            const bool boundary = flags[v] & kBoundary;
            if (reached != count || closed == boundary) {
                flags[v] |= kNonManifold; // several fans meet here ("bow tie")
                continue;
            }
            first[v] = begin;
        }
    };
    if (quads)
        fans([](uint32_t h) { return (h & ~3u) | ((h + 3) & 3u); });
    else
        fans([&](uint32_t h) {
            const uint32_t f = heFace[h];
            return h == faceOffsets[f] ? faceOffsets[f + 1] - 1 : h - 1;
        });
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

uint32_t Topology::findEdge(uint32_t a, uint32_t b) const {
    if (a >= vertexCount_ || b >= vertexCount_) return kNone;
    // Around the vertex of fewer faces first (an edge with a face is in both rings): every edge
    // of a cone or dart of thousands of faces would otherwise cost that vertex's whole ring, and
    // the callers that look up each edge in turn (ptex keys, chart UVs) became quadratic in it.
    const bool aFirst = vertexFaceCount(a) <= vertexFaceCount(b);
    for (uint32_t v : {aFirst ? a : b, aFirst ? b : a})
        for (uint32_t h : vertexOutgoing(v)) {
            uint32_t w = v == a ? b : a;
            if (destination(h) == w) return edge(h);
            if (vertex(prev(h)) == w) return edge(prev(h));
        }
    return kNone;
}

uint32_t Topology::nonManifoldEdgeCount() const {
    return static_cast<uint32_t>(std::count(edgeNonManifold_.begin(), edgeNonManifold_.end(), 1));
}

uint32_t Topology::boundaryEdgeCount() const {
    return static_cast<uint32_t>(std::count(edgeFaceCount_.begin(), edgeFaceCount_.end(), 1u));
}

} // namespace limn
