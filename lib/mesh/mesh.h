// The control mesh every tool works on: positions, faces of any size, face-varying UVs and the
// OpenSubdiv-style tags (creases, corners, holes, boundary and face-varying rules). Plain data;
// importers fill it, the container codec (mesh_chunks.h) stores it losslessly.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace limn {

// Numbered as OpenSubdiv's Sdc::Options::VtxBoundaryInterpolation. Note that OpenSubdiv's OBJ tag
// `t interpolateboundary` uses 1 for edge-and-corner and 2 for edge-only (mesh/obj.cpp maps it).
enum class BoundaryRule : uint8_t { None = 0, EdgeOnly = 1, EdgeAndCorner = 2 };
// Numbered as Sdc::Options::FVarLinearInterpolation (= the OBJ tag values).
enum class FVarRule : uint8_t {
    LinearNone = 0,
    CornersOnly = 1,
    CornersPlus1 = 2,
    CornersPlus2 = 3,
    Boundaries = 4,
    All = 5
};
enum class CreaseMethod : uint8_t { Uniform = 0, Chaikin = 1 };
enum class TriangleSubdivision : uint8_t { Catmark = 0, Smooth = 1 };

// Sharpness at or above this is infinitely sharp (Sdc::Crease::SHARPNESS_INFINITE).
inline constexpr float kInfiniteSharpness = 10.0f;

struct EdgeCrease {
    uint32_t v0 = 0, v1 = 0;
    float sharpness = 0;
    bool operator==(const EdgeCrease&) const = default;
};

struct VertexCorner {
    uint32_t vertex = 0;
    float sharpness = 0;
    bool operator==(const VertexCorner&) const = default;
};

struct Tags {
    // Unset means "not given by the input"; limn-classify resolves the boundary rule.
    std::optional<BoundaryRule> boundary;
    std::optional<FVarRule> fvar;
    std::optional<CreaseMethod> creaseMethod;
    std::optional<TriangleSubdivision> triangles;
    std::vector<EdgeCrease> creases;
    std::vector<VertexCorner> corners;
    std::vector<uint32_t> holes; // face indices
    bool operator==(const Tags&) const = default;
};

struct Mesh {
    std::vector<glm::dvec3> positions;
    // Face f has corners faceOffsets[f] .. faceOffsets[f+1]-1 in faceVertices.
    std::vector<uint32_t> faceOffsets{0};
    std::vector<uint32_t> faceVertices;
    // Face-varying UVs: one index per corner into uvs. Either empty or faceVertices.size() long.
    std::vector<glm::dvec2> uvs;
    std::vector<uint32_t> uvIndices;
    Tags tags;

    size_t vertexCount() const { return positions.size(); }
    size_t faceCount() const { return faceOffsets.size() - 1; }
    size_t cornerCount() const { return faceVertices.size(); }
    bool hasUVs() const { return !uvIndices.empty(); }
    uint32_t faceSize(size_t f) const { return faceOffsets[f + 1] - faceOffsets[f]; }
    std::span<const uint32_t> face(size_t f) const {
        return {faceVertices.data() + faceOffsets[f], faceSize(f)};
    }
    std::span<const uint32_t> faceUVs(size_t f) const {
        return {uvIndices.data() + faceOffsets[f], faceSize(f)};
    }
    void addFace(std::span<const uint32_t> vertices) {
        faceVertices.insert(faceVertices.end(), vertices.begin(), vertices.end());
        faceOffsets.push_back(static_cast<uint32_t>(faceVertices.size()));
    }
    bool operator==(const Mesh&) const = default;
};

// The axis-aligned box of the positions (both corners 0 for a mesh without vertices).
struct MeshBox {
    glm::dvec3 lo{0.0}, hi{0.0};
    double diagonal() const;
};
MeshBox boundingBox(const Mesh& mesh);

// Checks every invariant a consumer relies on and throws Error(BadInput) naming the first
// offending face, corner, vertex or tag: at least one face, faces of >= 3 distinct vertices,
// indices in range, finite positions and UVs that the GPU's float can carry (|x| <= 1e18, an
// extent float resolves), UV indices per corner, tag indices in range,
// sharpness finite and >= 0. Non-manifold topology is the topology layer's business.
void validateMesh(const Mesh& mesh);

} // namespace limn
