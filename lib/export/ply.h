// The triangles limn-render drew, as PLY (--mesh-out): one vertex per drawn corner with
// `float x y z nx ny nz`, `int ptex`, `float u v`, then `float s t` (the texture UV) when the mesh
// has texture coordinates, then `uchar approximate` when some vertex is not on the limit surface
// (DrawnVertex), and faces as `list uchar int vertex_indices`.
// Binary little-endian by default, ASCII on request; floats in ASCII are the shortest text that
// reads back to the same float, so both forms carry the same values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace limn::exporting {

struct DrawnVertex {
    float x = 0, y = 0, z = 0;
    float nx = 0, ny = 0, nz = 0;
    int32_t ptex = 0;
    float u = 0, v = 0;
    // The texture coordinate as drawn (DrawnMesh::hasTexCoords): the vertex's UV in its element's
    // face-varying chart, v = 0 at the bottom of the image as in OBJ and the mesh's UVs.
    float s = 0, t = 0;
    // Where the surface is approximate (drawn bilinear within 2^-K of an extraordinary corner,
    // docs/irregular.md): `uchar approximate` 1, written only when some vertex has it.
    uint8_t approximate = 0;
};

struct DrawnMesh {
    std::vector<DrawnVertex> vertices;
    std::vector<uint32_t> triangles; // 3 per triangle
    bool hasTexCoords = false;       // s, t are set (vertices are split at UV seams)
};

std::vector<uint8_t> encodePly(const DrawnMesh& mesh, bool ascii);

} // namespace limn::exporting
