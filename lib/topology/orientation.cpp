#include "topology/orientation.h"

#include <vector>

namespace limn {

Orientation checkOrientation(const Topology& T) {
    Orientation out;
    const uint32_t E = T.edgeCount(), F = T.faceCount();
    // The two half-edges of every edge with exactly two faces.
    std::vector<uint32_t> first(E, kNone), second(E, kNone);
    for (uint32_t h = 0; h < T.halfedgeCount(); ++h) {
        const uint32_t e = T.edge(h);
        if (T.edgeFaceCount(e) != 2) continue;
        (first[e] == kNone ? first[e] : second[e]) = h;
    }
    // Faces of each half-edge's edge, for the walk: per face, its corners' half-edges are
    // faceHalfedge(f) .. + faceSize(f).
    std::vector<int8_t> flip(F, -1); // -1 unvisited, 0 keep, 1 flip
    std::vector<uint32_t> queue;
    for (uint32_t e = 0; e < E; ++e)
        if (second[e] != kNone && T.vertex(first[e]) == T.vertex(second[e])) {
            if (out.misorientedEdges++ == 0) out.exampleEdge = e;
        }
    if (out.misorientedEdges == 0) return out;
    for (uint32_t start = 0; start < F; ++start) {
        if (flip[start] >= 0) continue;
        flip[start] = 0;
        queue.assign(1, start);
        uint32_t flipped = 0, size = 0;
        for (size_t qi = 0; qi < queue.size(); ++qi) {
            const uint32_t f = queue[qi];
            ++size;
            flipped += uint32_t(flip[f]);
            for (uint32_t k = 0; k < T.faceSize(f); ++k) {
                const uint32_t h = T.faceHalfedge(f) + k, e = T.edge(h);
                if (second[e] == kNone) continue;
                const uint32_t o = first[e] == h ? second[e] : first[e];
                const uint32_t g = T.face(o);
                if (g == f) continue;
                // Same direction: exactly one of the two faces must flip; opposite: both or neither.
                const int8_t want = int8_t(flip[f] ^ (T.vertex(o) == T.vertex(h) ? 1 : 0));
                if (flip[g] < 0) {
                    flip[g] = want;
                    queue.push_back(g);
                } else if (flip[g] != want) {
                    out.orientable = false;
                }
            }
        }
        out.facesToFlip += std::min(flipped, size - flipped);
    }
    return out;
}

std::string describeMisorientation(const Topology& T, const Orientation& o) {
    const auto [a, b] = T.edgeVertices(o.exampleEdge == kNone ? 0 : o.exampleEdge);
    const std::string edge = "edge (" + std::to_string(a) + "," + std::to_string(b) + ")";
    if (!o.orientable)
        return "the mesh is not orientable (a Möbius strip or a Klein bottle: its faces cannot all be "
               "given one orientation; " + edge + " is where two faces disagree); subdivision surfaces "
               "need an orientable mesh";
    return "faces of opposite orientation meet at " + std::to_string(o.misorientedEdges) + " edges (" + edge +
           " first); flipping " + std::to_string(o.facesToFlip) + " faces would make the mesh consistent";
}

} // namespace limn
