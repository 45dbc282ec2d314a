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

    size_t missing = 0;
    for (const auto& c : tags.creases) {
        uint32_t edge = topo.findEdge(c.v0, c.v1);
        if (edge == kNone) {
            if (missing++ == 0)
                warnings.add("crease tag (" + std::to_string(c.v0) + "," + std::to_string(c.v1) +
                             ") names no edge of the mesh; ignored");
            continue;
        }
        s.edge[edge] = c.sharpness; // a later tag for the same edge wins, as in Far
    }
    if (missing > 1)
        warnings.add(std::to_string(missing - 1) + " more crease tags name no edge; ignored");
    for (const auto& c : tags.corners) s.vertex[c.vertex] = c.sharpness;

    const float inf = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    s.faceNoLimit.assign(topo.faceCount(), 0);
    s.vertexOnUnsharpBoundary.assign(topo.vertexCount(), 0);
    for (uint32_t f : tags.holes) s.faceNoLimit[f] = 1;
    if (boundary == BoundaryRule::None) {
        // Before boundaries are sharpened: a vertex with a boundary edge that is not tagged
        // infinitely sharp takes all its faces out of the surface.
        for (uint32_t v = 0; v < topo.vertexCount(); ++v) {
            bool exclude = false;
            for (uint32_t h : topo.vertexOutgoing(v)) {
                uint32_t p = topo.prev(h);
                if ((topo.twin(h) == kNone && s.edge[topo.edge(h)] < inf) ||
                    (topo.twin(p) == kNone && s.edge[topo.edge(p)] < inf))
                    exclude = true;
            }
            s.vertexOnUnsharpBoundary[v] = exclude;
            if (exclude)
                for (uint32_t h : topo.vertexOutgoing(v)) s.faceNoLimit[topo.face(h)] = 1;
        }
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

namespace {

// Whether the inf-sharp edges at a manifold, all-quad vertex cut its neighbourhood into sectors
// that each look like a regular boundary (OpenSubdiv's "inf-sharp regular" vertex tag, the rule
// behind its useInfSharpPatch): the surface on either side of an infinitely sharp crease depends
// only on the points on that side (the crease and vertex rules read nothing across it), so each
// sector is a B-spline patch with phantom points P_-1 = 2 P_0 - P_1 beyond the crease (math.md
// C.4). Regular are: a crease-rule vertex on a boundary with 2 faces, or inside with 4 edges of
// which 2 opposite are inf-sharp (two sectors of 2 faces); and a corner-rule vertex all of whose
// edges are inf-sharp (every sector one face: corner patches), except a smooth corner (2 edges,
// no vertex sharpness). Semi-sharp edges or vertex sharpness at the vertex make it irregular.
bool infSharpRegular(const Topology& topo, const std::vector<float>& edgeSharpness,
                     float vertexSharpness, uint32_t v) {
    const float inf = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    if (vertexSharpness > 0 && vertexSharpness < inf) return false;
    // The incident edges' sharpness, counter-clockwise (then the arriving boundary edge).
    std::vector<uint32_t> ring;
    topo.vertexRing(v, ring);
    std::vector<float> edges;
    for (uint32_t h : ring) edges.push_back(edgeSharpness[topo.edge(h)]);
    if (topo.vertexIsBoundary(v)) edges.push_back(edgeSharpness[topo.edge(topo.prev(ring.back()))]);
    int infEdges = 0;
    for (float s : edges) {
        if (s > 0 && s < inf) return false;
        if (s >= inf) ++infEdges;
    }
    const bool vertexInf = vertexSharpness >= inf;
    if (infEdges == 0) return false; // a smooth vertex: the plain test applies
    OpenSubdiv::Sdc::Crease crease;
    auto rule = crease.DetermineVertexVertexRule(vertexInf ? inf : 0.0f, infEdges);
    const uint32_t faces = topo.vertexFaceCount(v);
    if (rule == OpenSubdiv::Sdc::Crease::RULE_CREASE) {
        if (topo.vertexIsBoundary(v)) return faces == 2;
        // Counter-clockwise, edges[i] and edges[i + 2] are opposite.
        return edges.size() == 4 && (edges[0] >= inf) == (edges[2] >= inf) &&
               (edges[1] >= inf) == (edges[3] >= inf);
    }
    if (rule == OpenSubdiv::Sdc::Crease::RULE_CORNER)
        return infEdges == int(edges.size()) && (edges.size() > 2 || vertexInf);
    return false; // a dart
}

// The sharpness of the semi-sharp crease running straight through an interior vertex of 4
// quads and 4 edges (two opposite edges of equal sharpness s > 0, the other two smooth, no vertex
// sharpness), or 0 when the vertex is no such crease vertex.
float straightCreaseSharpness(const Topology& topo, const std::vector<float>& edgeSharpness,
                              float vertexSharpness, uint32_t v, std::vector<uint32_t>& ring) {
    if (topo.vertexIsBoundary(v) || vertexSharpness != 0 || topo.vertexFaceCount(v) != 4) return 0;
    topo.vertexRing(v, ring);
    if (ring.size() != 4) return 0;
    float s[4];
    for (int i = 0; i < 4; ++i) {
        if (topo.faceSize(topo.face(ring[i])) != 4) return 0;
        s[i] = edgeSharpness[topo.edge(ring[i])];
    }
    if (s[0] != s[2] || s[1] != s[3]) return 0;
    if ((s[0] > 0) == (s[1] > 0)) return 0;
    const float crease = std::max(s[0], s[1]);
    return crease < OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE ? crease : 0;
}

} // namespace

namespace {

// Whether vertex v is a regular corner of the patches around it (analyzeRegularity).
uint8_t vertexRegularity(const Topology& topo, const std::vector<float>& edgeSharpness,
                         const std::vector<float>& vertexSharpness, uint32_t v, bool infSharpPatches) {
    const float inf = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    if (topo.vertexIsIsolated(v) || topo.vertexIsNonManifold(v)) return 0;
    uint32_t faces = topo.vertexFaceCount(v);
    bool allQuads = true, interiorEdgesSmooth = true, infSharpEdge = false;
    for (uint32_t h : topo.vertexOutgoing(v)) {
        if (topo.faceSize(topo.face(h)) != 4) allQuads = false;
        if (topo.twin(h) != kNone && edgeSharpness[topo.edge(h)] > 0)
            interiorEdgesSmooth = false;
        if (topo.twin(h) != kNone && edgeSharpness[topo.edge(h)] >= inf) infSharpEdge = true;
    }
    if (!allQuads) return 0;
    if (infSharpPatches && (infSharpEdge || vertexSharpness[v] >= inf) &&
        !(topo.vertexIsBoundary(v) && faces == 1))
        return infSharpRegular(topo, edgeSharpness, vertexSharpness[v], v);
    if (!interiorEdgesSmooth) return 0;
    if (!topo.vertexIsBoundary(v)) return faces == 4 && vertexSharpness[v] == 0;
    if (faces == 2) return vertexSharpness[v] == 0;
    if (faces == 1) return vertexSharpness[v] >= inf;
    return 0;
}

} // namespace

Regularity analyzeRegularity(const Topology& topo, const std::vector<float>& edgeSharpness,
                             const std::vector<float>& vertexSharpness,
                             const std::vector<uint8_t>& faceNoLimit, bool infSharpPatches,
                             bool singleCreasePatches, const std::vector<uint8_t>* only) {
    Regularity r;
    r.vertexRegular.assign(topo.vertexCount(), 0);
    if (!only) {
        for (uint32_t v = 0; v < topo.vertexCount(); ++v)
            r.vertexRegular[v] = vertexRegularity(topo, edgeSharpness, vertexSharpness, v, infSharpPatches);
    } else { // the corners of the faces asked about (and of their single-crease checks: the same)
        std::vector<uint8_t> done(topo.vertexCount(), 0);
        for (uint32_t f = 0; f < topo.faceCount(); ++f)
            if ((*only)[f])
                for (uint32_t v : topo.faceVertices(f))
                    if (!done[v]) {
                        done[v] = 1;
                        r.vertexRegular[v] = vertexRegularity(topo, edgeSharpness, vertexSharpness, v, infSharpPatches);
                    }
    }
    r.faceRegular.assign(topo.faceCount(), 0);
    for (uint32_t f = 0; f < topo.faceCount(); ++f) {
        if (only && !(*only)[f]) continue;
        bool regular = topo.faceSize(f) == 4 && !faceNoLimit[f];
        for (uint32_t v : topo.faceVertices(f))
            if (!r.vertexRegular[v]) regular = false;
        r.faceRegular[f] = regular;
    }
    // Single-crease patches (Nießner, Loop and Greiner 2012; OpenSubdiv's useSingleCreasePatch):
    // an interior quad whose corners are two smooth regular vertices and, along one edge, two
    // vertices on a straight semi-sharp crease of one sharpness s (so the crease continues
    // straight on beyond both). Subdivision there acts on the rows across the crease alone: the
    // surface is a B-spline along the crease times a curve with a semi-sharp vertex across it.
    r.faceCreaseEdge.assign(topo.faceCount(), kNone);
    if (!singleCreasePatches) return r;
    std::vector<uint32_t> ring;
    for (uint32_t f = 0; f < topo.faceCount(); ++f) {
        if ((only && !(*only)[f]) || r.faceRegular[f] || topo.faceSize(f) != 4 || faceNoLimit[f]) continue;
        const uint32_t h0 = topo.faceHalfedge(f);
        float crease[4];
        int creaseMask = 0;
        bool otherwiseRegular = true;
        for (int k = 0; k < 4; ++k) {
            const uint32_t v = topo.vertex(h0 + k);
            crease[k] = straightCreaseSharpness(topo, edgeSharpness, vertexSharpness[v], v, ring);
            if (crease[k] > 0)
                creaseMask |= 1 << k;
            else if (!r.vertexRegular[v] || topo.vertexIsBoundary(v) || vertexSharpness[v] != 0)
                otherwiseRegular = false;
            else
                for (uint32_t h : topo.vertexOutgoing(v))
                    if (edgeSharpness[topo.edge(h)] != 0) otherwiseRegular = false;
        }
        // Exactly two adjacent crease corners k, k+1: the crease is face edge k.
        int k = -1;
        for (int i = 0; i < 4; ++i)
            if (creaseMask == ((1 << i) | (1 << ((i + 1) % 4)))) k = i;
        if (!otherwiseRegular || k < 0) continue;
        const uint32_t edge = topo.edge(h0 + k);
        if (edgeSharpness[edge] != crease[k] || crease[(k + 1) % 4] != crease[k]) continue;
        r.faceRegular[f] = 1;
        r.faceCreaseEdge[f] = edge;
    }
    return r;
}

} // namespace limn
