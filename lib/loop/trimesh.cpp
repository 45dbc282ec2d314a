#include "loop/trimesh.h"

#include "base/error.h"
#include "loop/level.h"
#include "topology/topology.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace limn::loop {

namespace {

std::string pairText(uint32_t a, uint32_t b) {
    return "(" + std::to_string(a) + "," + std::to_string(b) + ")";
}

// Refuses what Loop's rules cannot handle, naming the first edge or vertex at fault.
void checkManifold(const Topology& topo) {
    for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
        if (!topo.edgeIsNonManifold(e)) continue;
        auto [a, b] = topo.edgeVertices(e);
        if (topo.edgeFaceCount(e) > 2)
            throwBadInput("edge " + pairText(a, b) + " is shared by " +
                          std::to_string(topo.edgeFaceCount(e)) +
                          " faces; Loop subdivision needs a manifold mesh");
        uint32_t f0 = topo.face(topo.edgeHalfedge(e)), f1 = f0;
        for (uint32_t h : topo.vertexOutgoing(a))
            if (topo.destination(h) == b && topo.face(h) != f0) f1 = topo.face(h);
        throwBadInput("faces " + std::to_string(f0) + " and " + std::to_string(f1) +
                      " run through edge " + pairText(a, b) +
                      " in the same direction; the mesh must be consistently oriented");
    }
    for (uint32_t v = 0; v < topo.vertexCount(); ++v)
        if (topo.vertexIsNonManifold(v))
            throwBadInput("vertex " + std::to_string(v) +
                          " is non-manifold (separate fans of faces meet there); Loop "
                          "subdivision needs a manifold mesh");
}

bool isSemiSharp(float s) { return s > 0 && s < kInfiniteSharpness; }

} // namespace

TriMesh fromMesh(const Mesh& mesh, const ImportOptions& options, Warnings& warnings) {
    validateMesh(mesh);
    if (!mesh.tags.holes.empty())
        throwBadInput("hole tags are not supported by Loop refinement here (face " +
                      std::to_string(mesh.tags.holes.front()) + " is tagged as a hole)");

    TriMesh out;
    out.positions = mesh.positions;
    const bool uv = mesh.hasUVs();
    if (uv) out.uvs = mesh.uvs;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        auto face = mesh.face(f);
        if (face.size() != 3 && !options.triangulate)
            throwBadInput("face " + std::to_string(f) + " has " + std::to_string(face.size()) +
                          " vertices; Loop subdivision needs triangles (use --triangulate)");
        // A fan from corner 0 (a triangle is its own fan).
        for (uint32_t i = 1; i + 1 < face.size(); ++i) {
            out.triangles.push_back({face[0], face[i], face[i + 1]});
            if (uv) {
                auto t = mesh.faceUVs(f);
                out.uvTriangles.push_back({t[0], t[i], t[i + 1]});
            }
        }
    }

    Topology topo = triangleTopology(out.vertexCount(), out.triangles);
    checkManifold(topo);

    // Sharp features (math.md B.3): tagged creases and corners, plus the boundary rule's corners.
    out.corners.assign(out.vertexCount(), 0);
    const Tags& tags = mesh.tags;
    for (size_t i = 0; i < tags.creases.size(); ++i) {
        const EdgeCrease& c = tags.creases[i];
        std::string what = "crease tag " + std::to_string(i) + " " + pairText(c.v0, c.v1);
        if (isSemiSharp(c.sharpness))
            throwBadInput(what + " has sharpness " + std::to_string(c.sharpness) +
                          "; only smooth (0) and infinitely sharp (>= 10) creases are supported");
        if (c.sharpness <= 0) continue;
        uint32_t e = topo.findEdge(c.v0, c.v1);
        if (e == kNone) {
            warnings.add(what + " names no edge of the mesh; ignored");
            continue;
        }
        if (topo.edgeIsBoundary(e)) continue; // boundary edges are sharp anyway
        out.creases.push_back({std::min(c.v0, c.v1), std::max(c.v0, c.v1)});
    }
    std::sort(out.creases.begin(), out.creases.end());
    out.creases.erase(std::unique(out.creases.begin(), out.creases.end()), out.creases.end());
    for (size_t i = 0; i < tags.corners.size(); ++i) {
        const VertexCorner& c = tags.corners[i];
        if (isSemiSharp(c.sharpness))
            throwBadInput("corner tag " + std::to_string(i) + " (vertex " +
                          std::to_string(c.vertex) + ") has sharpness " +
                          std::to_string(c.sharpness) +
                          "; only smooth (0) and infinitely sharp (>= 10) corners are supported");
        if (c.sharpness > 0) out.corners[c.vertex] = 1;
    }
    BoundaryRule rule = options.boundary ? *options.boundary
                                         : tags.boundary.value_or(BoundaryRule::EdgeOnly);
    // Under edge-and-corner a boundary vertex with one face is a corner (OpenSubdiv sharpens it
    // once on the control mesh; its children inherit the sharpness).
    if (rule == BoundaryRule::EdgeAndCorner)
        for (uint32_t v = 0; v < out.vertexCount(); ++v)
            if (topo.vertexFaceCount(v) == 1 && topo.vertexEdgeCount(v) == 2) out.corners[v] = 1;

    uint32_t isolated = 0, firstIsolated = 0;
    for (uint32_t v = 0; v < out.vertexCount(); ++v)
        if (topo.vertexIsIsolated(v) && isolated++ == 0) firstIsolated = v;
    if (isolated)
        warnings.add(std::to_string(isolated) + " vertices are used by no face (first: vertex " +
                     std::to_string(firstIsolated) + "); they are kept unchanged");
    if (uv && tags.fvar && *tags.fvar != FVarRule::All)
        warnings.add("UVs are interpolated linearly everywhere (facevaryinginterpolateboundary 5), "
                     "not by the mesh's face-varying rule");
    return out;
}

Mesh toMesh(const TriMesh& m, const Tags& inputTags) {
    Mesh out;
    out.positions = m.positions;
    out.faceVertices.reserve(m.triangles.size() * 3);
    out.faceOffsets.reserve(m.triangles.size() + 1);
    for (const Tri& t : m.triangles) out.addFace(t);
    if (m.hasUVs()) {
        out.uvs = m.uvs;
        out.uvIndices.reserve(m.uvTriangles.size() * 3);
        for (const Tri& t : m.uvTriangles) out.uvIndices.insert(out.uvIndices.end(), t.begin(), t.end());
    }
    out.tags.boundary = inputTags.boundary;
    out.tags.fvar = inputTags.fvar;
    out.tags.creaseMethod = inputTags.creaseMethod;
    out.tags.triangles = inputTags.triangles;
    for (const VertexPair& c : m.creases)
        out.tags.creases.push_back({c[0], c[1], kInfiniteSharpness});
    for (uint32_t v = 0; v < m.corners.size(); ++v)
        if (m.corners[v]) out.tags.corners.push_back({v, kInfiniteSharpness});
    return out;
}

double boundingBoxDiagonal(const std::vector<glm::dvec3>& positions) {
    if (positions.empty()) return 0;
    glm::dvec3 lo = positions[0], hi = positions[0];
    for (const auto& p : positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    glm::dvec3 d = hi - lo;
    return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

} // namespace limn::loop
