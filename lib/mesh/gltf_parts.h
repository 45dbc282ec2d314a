// The pieces of the glTF reader (gltf.cpp), private to lib/mesh: the JSON pre-pass that checks
// extensions and prepares compressed files for tinygltf (gltf_prepass.cpp), accessors with
// sparse substitution and zeros (gltf_accessor.cpp), the two compression extensions decoded
// through their own libraries (gltf_draco.cpp, gltf_meshopt.cpp), and the node graph
// (gltf_scene.cpp), and the welding of primitives into one mesh (gltf_weld.cpp).
#pragma once

#include "base/warnings.h"
#include "mesh/gltf.h"
#include "mesh/mesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <array>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace limn::gltf {

// KHR_draco_mesh_compression on a primitive: the buffer view holding the Draco bitstream and the
// Draco attribute id of each glTF attribute.
struct DracoPrimitive {
    int bufferView = -1;
    std::map<std::string, int> attributes;
};

// EXT_meshopt_compression or KHR_meshopt_compression on a buffer view: where the compressed
// bytes are and how they decode into the view.
struct MeshoptView {
    std::string extension;
    int buffer = -1;
    uint64_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
    std::string mode, filter;
};

// What the pre-pass learned from the JSON before tinygltf parses it. tinygltf 2.7 (Debian 12)
// refuses an index accessor without a buffer view (Draco's) and a buffer without a URI (a meshopt
// fallback buffer): those are taken out of the JSON it sees, and noted here.
struct Prepass {
    std::vector<uint8_t> rewritten; // the file tinygltf reads instead; empty: the original
    std::map<std::pair<int, int>, DracoPrimitive> draco; // by (mesh, primitive)
    std::map<std::pair<int, int>, int> indicesWithoutView; // (mesh, primitive) -> accessor
    std::map<int, MeshoptView> meshopt;                  // by buffer view
    std::map<int, uint64_t> placeholderBuffers;          // buffer -> its byteLength
    bool ngonEncoding = false;                           // some primitive has FB_ngon_encoding
};

// Refuses a required extension limn does not read (naming it), warns about optional ones it
// ignores. A JSON that does not parse is left to tinygltf, which names the fault.
Prepass prepass(std::span<const uint8_t> bytes, bool binary, Warnings& warnings);

// Fills placeholder buffers and decodes every meshopt-compressed buffer view in place.
void decodeMeshopt(tinygltf::Model& model, const Prepass& prepass);

// A primitive's vertex data, from accessors or from a Draco bitstream.
struct PrimitiveData {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec2> texcoords; // glTF's convention (v down); empty without TEXCOORD_0
    std::vector<uint32_t> indices;     // empty without indices
    bool hasIndices = false;
};
void decodeDraco(const tinygltf::Model& model, const DracoPrimitive& draco, const std::string& what,
                 PrimitiveData& out);
// POSITION, TEXCOORD_0 and indices of a primitive (`key`: mesh and primitive index), from
// accessors or Draco, with morph targets applied with `weights` (glTF 2.0, 3.7.2.2).
PrimitiveData primitiveData(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Prepass& pre,
                            std::pair<int, int> key, const std::vector<double>& weights, const std::string& what);

// An accessor's elements as doubles (normalized integers mapped to [0, 1] or [-1, 1]), with a
// sparse accessor's substitutions applied and zeros where there is no buffer view.
struct AccessorData {
    size_t count = 0;
    int components = 0;
    std::vector<double> values; // count * components
    double at(size_t element, int component) const { return values[element * size_t(components) + size_t(component)]; }
};
AccessorData readAccessor(const tinygltf::Model& model, int index, const std::string& what);
// Index accessors: unsigned integers only.
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& what);

// One drawn node: the node and its world transform, in depth-first order of the scene.
struct NodeInstance {
    int node = -1;
    glm::dmat4 transform{1.0};
};
// The scene's node instances. Refuses, before any other work, a node graph with a cycle or one
// that would draw more than kMaxNodeInstances instances (a node listed as the child of several
// nodes is drawn once per path, which grows exponentially); warns about nodes with several
// parents (glTF 2.0, 3.5.3, requires a strict tree).
inline constexpr uint64_t kMaxNodeInstances = 1'000'000;
std::vector<NodeInstance> sceneInstances(const tinygltf::Model& model, const std::vector<int>& roots,
                                         Warnings& warnings);

// A parsed file: tinygltf's model with every meshopt view decoded, the pre-pass, the scene's
// roots and its node instances (the node graph checked). `images` (optional) gets each image's
// file bytes.
struct Loaded {
    tinygltf::Model model;
    Prepass pre;
    std::vector<int> roots;
    std::vector<NodeInstance> instances;
};
// `baseDir` nullptr: no file is read (readGltfEmbedded).
Loaded load(std::span<const uint8_t> bytes, bool binary, const std::string* baseDir, Warnings& warnings,
            std::vector<std::string>* filesRead, std::map<int, std::vector<uint8_t>>* images);
// One mesh welded from glTF primitives (gltf_weld.cpp): positions and texture coordinates
// equal to the bit are one vertex, so that faces meet along shared edges.
struct Welder {
    Mesh mesh;
    std::map<std::array<double, 3>, uint32_t> positionIndex;
    std::map<std::array<double, 2>, uint32_t> uvIndex;
    bool anyUV = false, anyWithoutUV = false;
    size_t degenerate = 0, skippedPrimitives = 0, mirrored = 0, ngons = 0;
    bool rebuildNgons = false;
    int material = -1;           // the first triangle primitive's material
    bool otherMaterials = false; // a later primitive has another one

    uint32_t weldPosition(const glm::dvec3& p);
    uint32_t weldUV(const glm::dvec2& uv);
    // Adds a triangle primitive's faces (strips and fans as triangles; FB_ngon_encoding's fans
    // as their polygons with rebuildNgons), placed by `transform`; other modes are skipped.
    void addPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Prepass& pre,
                      std::pair<int, int> key, const std::vector<double>& weights,
                      const glm::dmat4& transform, const std::string& what);
};

// readGltf, or with `baseDir` nullptr readGltfEmbedded.
Mesh readFrom(std::span<const uint8_t> bytes, bool binary, const std::string* baseDir, Warnings& warnings,
              std::vector<std::string>* filesRead, std::optional<MeshMaterial>* material, GltfPolygons* polygons);

} // namespace limn::gltf
