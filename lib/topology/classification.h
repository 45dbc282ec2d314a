// Classification of a control mesh (paper 000, section 4.1): per vertex its valence and feature
// flags, per face whether it is a regular B-spline patch, plus edge counts; stored in the CLSF
// chunk (formats/limn.md).
#pragma once

#include "base/warnings.h"
#include "container/container.h"
#include "mesh/mesh.h"
#include "topology/features.h"
#include "topology/topology.h"

#include <cstdint>
#include <vector>

namespace limn {

inline constexpr FourCC kClassificationChunk{"CLSF"};

enum VertexFlag : uint32_t {
    kVertexBoundary = 1u << 0,
    kVertexNonManifold = 1u << 1,
    kVertexCorner = 1u << 2,        // rule corner (tagged, or sharpened boundary corner)
    kVertexCrease = 1u << 3,        // rule crease on an interior crease or a boundary
    kVertexDart = 1u << 4,          // exactly one sharp edge
    kVertexSemiSharp = 1u << 5,     // semi-sharp vertex or semi-sharp incident edge
    kVertexExtraordinary = 1u << 6, // not patch-regular (features.h)
    kVertexUVSeam = 1u << 7,        // has more than one UV value among its corners
    kVertexIsolated = 1u << 8,      // used by no face
    kVertexNonQuad = 1u << 9,       // touches a face that is not a quad
};

enum FaceFlag : uint32_t {
    kFaceRegular = 1u << 0, // a bicubic B-spline patch at level 0
    kFaceHole = 1u << 1,    // tagged hole
    kFaceNoLimit = 1u << 2, // hole, or no limit surface under boundary rule "none"
    kFaceNonQuad = 1u << 3,
    kFaceBoundary = 1u << 4,    // has a boundary edge
    kFaceNonManifold = 1u << 5, // has a non-manifold edge or vertex
};

struct Classification {
    SchemeOptions options;
    std::vector<uint32_t> vertexValence; // incident edges
    std::vector<uint32_t> vertexFlags;
    std::vector<uint32_t> faceFlags;
    uint32_t edges = 0, boundaryEdges = 0, nonManifoldEdges = 0, uvSeamEdges = 0;
    bool operator==(const Classification&) const = default;
};

Classification classifyMesh(const Mesh& mesh, const Topology& topo, const SchemeOptions& options,
                            Warnings& warnings);

Chunk encodeClassificationChunk(const Classification& c);

// A container from any input: a .limn as it is, or a mesh file (OBJ, glTF, PLY, OFF) imported and
// classified with the defaults, as limn-classify would make it, so that limn-tables, limn-seams
// and limn-blend take a mesh directly. `filesRead` gets a .gltf's buffers and images.
Container loadOrClassify(const std::string& path, Warnings& warnings,
                         std::vector<std::string>* filesRead = nullptr);
// Decodes CLSF and checks its sizes against the mesh it describes.
Classification decodeClassificationChunk(const Chunk& chunk, const Mesh& mesh);

} // namespace limn
