#include "topology/features.h"

#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/options.h>

#include <algorithm>
#include <string>

namespace limn {

SchemeOptions resolveSchemeOptions(const Tags& tags, std::optional<BoundaryRule> boundaryOverride) {
    SchemeOptions o;
    if (tags.boundary) o.boundary = *tags.boundary;
    if (boundaryOverride) o.boundary = *boundaryOverride;
    if (tags.creaseMethod) o.creaseMethod = *tags.creaseMethod;
    if (tags.triangles) o.triangles = *tags.triangles;
    if (tags.fvar) o.fvar = *tags.fvar;
    return o;
}

Sharpness baseSharpness(const Topology& topo, const Tags& tags, BoundaryRule boundary,
                        Warnings& warnings) {
    Sharpness s;
    s.edge.assign(topo.edgeCount(), 0.0f);
    s.vertex.assign(topo.vertexCount(), 0.0f);

    // Crease tags name vertex pairs. Sort the tagged pairs (tags are few, meshes are large) and
    // let each edge look itself up; a later tag for the same edge wins, as in Far. (A hash map
    // of every edge cost more than the rest of the classification together.)
    auto pairKey = [](uint32_t a, uint32_t b) {
        return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    };
    std::vector<std::pair<uint64_t, uint32_t>> tagged; // (pair, tag index)
    tagged.reserve(tags.creases.size());
    for (uint32_t i = 0; i < tags.creases.size(); ++i)
        tagged.push_back({pairKey(tags.creases[i].v0, tags.creases[i].v1), i});
    std::sort(tagged.begin(), tagged.end());
    std::vector<uint8_t> named(tagged.size(), 0); // per sorted entry: some edge has this pair
    if (!tagged.empty()) {
        for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
            auto [a, b] = topo.edgeVertices(e);
            uint64_t key = pairKey(a, b);
            auto it = std::upper_bound(tagged.begin(), tagged.end(), std::pair{key, ~0u});
            if (it == tagged.begin() || (it - 1)->first != key) continue;
            s.edge[e] = tags.creases[(it - 1)->second].sharpness; // the last tag of the pair
            for (auto k = it; k != tagged.begin() && (k - 1)->first == key; --k)
                named[k - 1 - tagged.begin()] = 1;
        }
    }
    std::vector<uint8_t> tagNamed(tags.creases.size(), 0);
    for (size_t k = 0; k < tagged.size(); ++k) tagNamed[tagged[k].second] = named[k];
    size_t missing = 0;
    for (size_t i = 0; i < tags.creases.size(); ++i) {
        if (tagNamed[i]) continue;
        const auto& c = tags.creases[i];
        if (missing++ == 0)
            warnings.add("crease tag (" + std::to_string(c.v0) + "," + std::to_string(c.v1) +
                         ") names no edge of the mesh; ignored");
    }
    if (missing > 1)
        warnings.add(std::to_string(missing - 1) + " more crease tags name no edge; ignored");
    for (const auto& c : tags.corners) s.vertex[c.vertex] = c.sharpness;

    const float inf = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    // Under "none" the tags, not the sharpening below, decide which boundary faces keep a limit.
    if (boundary == BoundaryRule::None) {
        s.vertexUnsharpBoundary.assign(topo.vertexCount(), 0);
        for (uint32_t e = 0; e < topo.edgeCount(); ++e)
            if (topo.edgeIsBoundary(e) && s.edge[e] < inf)
                for (uint32_t v : topo.edgeVertices(e)) s.vertexUnsharpBoundary[v] = 1;
    }
    for (uint32_t e = 0; e < topo.edgeCount(); ++e)
        if (topo.edgeIsBoundary(e) || topo.edgeIsNonManifold(e)) s.edge[e] = inf;

    // Non-manifold edges at each vertex, for the "non-manifold crease" exception.
    std::vector<uint8_t> nonManifoldEdges(topo.vertexCount(), 0);
    for (uint32_t e = 0; e < topo.edgeCount(); ++e)
        if (topo.edgeIsNonManifold(e))
            for (uint32_t v : topo.edgeVertices(e))
                nonManifoldEdges[v] = static_cast<uint8_t>(std::min(nonManifoldEdges[v] + 1, 255));
    for (uint32_t v = 0; v < topo.vertexCount(); ++v) {
        bool corner = topo.vertexFaceCount(v) == 1 && topo.vertexEdgeCount(v) == 2;
        // Far leaves a vertex on an interior non-manifold crease smooth: two non-manifold edges,
        // no boundary edge, and more faces than edges (one more per extra fin).
        bool onNonManifoldCrease = nonManifoldEdges[v] == 2 && !topo.vertexIsBoundary(v) &&
                                   topo.vertexFaceCount(v) > topo.vertexEdgeCount(v);
        if (corner && boundary == BoundaryRule::EdgeAndCorner)
            s.vertex[v] = inf;
        else if (topo.vertexIsNonManifold(v) && !onNonManifoldCrease)
            s.vertex[v] = inf;
    }
    return s;
}

VertexRule vertexRule(const Topology& topo, const Sharpness& sharp, uint32_t v) {
    int sharpEdges = 0;
    if (!topo.vertexIsNonManifold(v)) {
        for (uint32_t h : topo.vertexOutgoing(v)) {
            // Each incident edge once: outgoing half-edges cover interior edges once each;
            // boundary edges arriving at v (no outgoing twin) are counted from prev().
            if (sharp.edge[topo.edge(h)] > 0) ++sharpEdges;
            uint32_t p = topo.prev(h);
            if (topo.twin(p) == kNone && sharp.edge[topo.edge(p)] > 0) ++sharpEdges;
        }
    } else {
        // Around a non-manifold vertex an edge can leave or arrive in any number of faces
        // (fins, inconsistent orientation): collect the distinct edges.
        std::vector<uint32_t> edges;
        for (uint32_t h : topo.vertexOutgoing(v)) {
            edges.push_back(topo.edge(h));
            edges.push_back(topo.edge(topo.prev(h)));
        }
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        for (uint32_t e : edges)
            if (sharp.edge[e] > 0) ++sharpEdges;
    }
    OpenSubdiv::Sdc::Crease crease;
    auto rule = crease.DetermineVertexVertexRule(sharp.vertex[v], sharpEdges);
    return static_cast<VertexRule>(rule);
}

Regularity analyzeRegularity(const Topology& topo, const Sharpness& sharp,
                             const std::vector<uint8_t>& faceIsHole, BoundaryRule boundary) {
    const float inf = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    Regularity r;
    const bool none = boundary == BoundaryRule::None && !sharp.vertexUnsharpBoundary.empty();
    auto unsharpBoundary = [&](uint32_t v) { return none && sharp.vertexUnsharpBoundary[v]; };
    r.vertexRegular.assign(topo.vertexCount(), 0);
    for (uint32_t v = 0; v < topo.vertexCount(); ++v) {
        if (topo.vertexIsIsolated(v) || topo.vertexIsNonManifold(v) || unsharpBoundary(v)) continue;
        uint32_t faces = topo.vertexFaceCount(v);
        bool allQuads = true, interiorEdgesSmooth = true;
        for (uint32_t h : topo.vertexOutgoing(v)) {
            if (topo.faceSize(topo.face(h)) != 4) allQuads = false;
            if (topo.twin(h) != kNone && sharp.edge[topo.edge(h)] > 0) interiorEdgesSmooth = false;
        }
        if (!allQuads || !interiorEdgesSmooth) continue;
        if (!topo.vertexIsBoundary(v)) {
            r.vertexRegular[v] = faces == 4 && sharp.vertex[v] == 0;
        } else if (faces == 2) {
            r.vertexRegular[v] = sharp.vertex[v] == 0;
        } else if (faces == 1) {
            r.vertexRegular[v] = sharp.vertex[v] >= inf;
        }
    }
    r.faceRegular.assign(topo.faceCount(), 0);
    r.faceHasNoLimit.assign(topo.faceCount(), 0);
    for (uint32_t f = 0; f < topo.faceCount(); ++f) {
        bool noLimit = !faceIsHole.empty() && faceIsHole[f];
        bool regular = topo.faceSize(f) == 4;
        for (uint32_t v : topo.faceVertices(f)) {
            if (!r.vertexRegular[v]) regular = false;
            if (unsharpBoundary(v)) noLimit = true;
        }
        r.faceHasNoLimit[f] = noLimit;
        r.faceRegular[f] = regular && !noLimit;
    }
    return r;
}

} // namespace limn
