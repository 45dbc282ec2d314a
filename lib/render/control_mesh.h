// The control mesh as the GPU draws it, prepared on the CPU once (topology only; positions are
// uploaded per frame). Faces are drawn as fans over their corners through an index buffer; tagged
// holes are left out of the triangles and of the wire edges (an edge is drawn when at least one
// face that is not a hole uses it).
#pragma once

#include "image/image_file.h"
#include "mesh/mesh.h"
#include "render/camera.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace limn::render {

// One draw vertex per corner of a drawn face; mirrors `uvec4 c` in mesh.vert.
struct GpuCorner {
    uint32_t vertex = 0; // into the vertex buffer
    uint32_t face = 0;   // into the face normals
    uint32_t uv = 0;     // into the UVs (0 when the mesh has none)
    uint32_t ptex = 0;   // Ptex face index (OpenSubdiv numbering, see ptexFaceBase)
};

struct ControlMeshDraw {
    std::vector<glm::vec4> controlPoints; // positions as float, w = 1
    std::vector<uint32_t> faceOffsets;    // F + 1, for the face-normal pass (every face)
    std::vector<uint32_t> faceVertices;
    std::vector<GpuCorner> corners;  // corners of drawn faces, face by face
    std::vector<glm::vec2> uvs;      // float UVs; one (0, 0) when the mesh has none
    std::vector<uint32_t> triangles; // 3 per triangle, into corners
    std::vector<uint32_t> edges;     // 2 per edge, into vertices, sorted
    uint32_t drawnFaces = 0;
    bool hasUVs = false;
    Bounds bounds; // of the vertices of drawn faces (all vertices if every face is a hole)
};

// Ptex face index of each face's first Ptex face: a quad has one Ptex face, an n-gon n of them
// (OpenSubdiv's Far::PtexIndices numbering). Size F.
std::vector<uint32_t> ptexFaceBase(const Mesh& mesh);

// The colour texture as the fragment stages read it (shaders/texture_sample.glsl): width, height,
// then sRGB RGBA8 texels, rows top to bottom; one white texel when there is none.
std::vector<uint32_t> textureWords(const FloatImage* image);

// The mesh must be valid (validateMesh).
ControlMeshDraw prepareControlMesh(const Mesh& mesh);

} // namespace limn::render
