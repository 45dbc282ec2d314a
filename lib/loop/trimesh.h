// The triangle mesh adaptive Loop subdivision works on (paper 004; math.md B): positions,
// counter-clockwise triangles, optional face-varying UVs, and the infinitely sharp features that
// Loop's boundary and crease rules need (math.md B.3). Conversion from and to limn::Mesh checks
// everything the rules rely on, so the rest of lib/loop can assume a clean manifold mesh.
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace limn::loop {

using Tri = std::array<uint32_t, 3>;
using VertexPair = std::array<uint32_t, 2>;

struct TriMesh {
    std::vector<glm::dvec3> positions;
    std::vector<Tri> triangles;         // counter-clockwise corners
    std::vector<glm::dvec2> uvs;        // face-varying values
    std::vector<Tri> uvTriangles;       // empty, or one UV index per triangle corner
    std::vector<VertexPair> creases;    // infinitely sharp interior edges (the boundary is implied)
    std::vector<uint8_t> corners;       // per vertex: 1 = infinitely sharp corner (v' = v∞ = v)

    uint32_t vertexCount() const { return static_cast<uint32_t>(positions.size()); }
    uint32_t triangleCount() const { return static_cast<uint32_t>(triangles.size()); }
    bool hasUVs() const { return !uvTriangles.empty(); }
};

struct ImportOptions {
    // Split polygons into triangle fans from their first corner instead of refusing them.
    bool triangulate = false;
    // Overrides the mesh's interpolateboundary tag (default edge-only, as OpenSubdiv's harness).
    std::optional<BoundaryRule> boundary;
};

// Converts and checks a control mesh. Throws Error(BadInput) naming the first offending face,
// edge, vertex or tag for: polygons (without `triangulate`), non-manifold edges or vertices,
// inconsistent orientation, hole tags, and semi-sharp creases or corners (0 < s < 10) — limn-loop
// supports smooth (0) and infinitely sharp (>= 10) features only. Crease tags that name no edge,
// unreferenced vertices and a face-varying rule other than "all" are reported as warnings.
TriMesh fromMesh(const Mesh& mesh, const ImportOptions& options, Warnings& warnings);

// Back to limn's mesh. Creases and corners become infinitely sharp `t crease`/`t corner` tags,
// the input's boundary, face-varying and other scheme tags are copied from `inputTags`.
Mesh toMesh(const TriMesh& mesh, const Tags& inputTags);

// Diagonal of the axis-aligned bounding box of the positions (0 for an empty mesh).
double boundingBoxDiagonal(const std::vector<glm::dvec3>& positions);

} // namespace limn::loop
