#include "mesh/gltf.h"

#include "base/error.h"
#include "base/io.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <map>

namespace limn {

namespace {

// Images are not decoded here (lib/image is a layer below this one, and a texture that is never
// drawn should cost nothing): each image's file bytes are kept as they are, by image index, for
// the material's base colour texture.
using ImageBytes = std::map<int, std::vector<uint8_t>>;
bool keepImageBytes(tinygltf::Image*, const int index, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void* user) {
    if (user && bytes && size > 0)
        (*static_cast<ImageBytes*>(user))[index].assign(bytes, bytes + size);
    return true;
}

// A file name whose extension names the image's format for the image reader: by the bytes'
// signature (PNG, JPEG), else the URI's extension, else the MIME type.
std::string imageFormatName(const std::vector<uint8_t>& bytes, const tinygltf::Image& image) {
    static const uint8_t png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), png, 8) == 0) return "texture.png";
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF)
        return "texture.jpg";
    if (image.uri.rfind("data:", 0) != 0) {
        const size_t dot = image.uri.find_last_of('.');
        if (dot != std::string::npos && image.uri.find('/', dot) == std::string::npos)
            return "texture" + image.uri.substr(dot);
    }
    if (image.mimeType == "image/jpeg") return "texture.jpg";
    if (image.mimeType == "image/png") return "texture.png";
    return "texture";
}

// A bounds-checked view of one accessor's elements.
class AccessorView {
public:
    AccessorView(const tinygltf::Model& model, int index, const std::string& what) : what_(what) {
        if (index < 0 || index >= static_cast<int>(model.accessors.size()))
            throwBadInput(what + ": accessor " + std::to_string(index) + " does not exist");
        const auto& a = model.accessors[index];
        if (a.sparse.isSparse) throwBadInput(what + ": sparse accessors are not supported");
        if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
            throwBadInput(what + ": accessor " + std::to_string(index) + " has no buffer view");
        const auto& view = model.bufferViews[a.bufferView];
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
            throwBadInput(what + ": buffer view refers to a missing buffer");
        const auto& buffer = model.buffers[view.buffer].data;
        components_ = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
        componentSize_ = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
        if (components_ <= 0 || componentSize_ <= 0)
            throwBadInput(what + ": unsupported accessor type");
        componentType_ = a.componentType;
        normalized_ = a.normalized;
        count_ = a.count;
        size_t elementSize = size_t(components_) * size_t(componentSize_);
        stride_ = view.byteStride ? view.byteStride : elementSize;
        if (stride_ < elementSize) throwBadInput(what + ": byte stride smaller than an element");
        if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
            throwBadInput(what + ": buffer view runs past its buffer");
        if (a.byteOffset > view.byteLength)
            throwBadInput(what + ": accessor offset runs past its buffer view");
        size_t avail = view.byteLength - a.byteOffset;
        if (count_ > 0 && (count_ - 1 > (avail - std::min(avail, elementSize)) / stride_ ||
                           avail < elementSize))
            throwBadInput(what + ": " + std::to_string(count_) +
                          " elements run past the end of the buffer view");
        base_ = buffer.data() + view.byteOffset + a.byteOffset;
    }

    size_t count() const { return count_; }
    int components() const { return components_; }

    double component(size_t element, int c) const {
        const uint8_t* p = base_ + element * stride_ + size_t(c) * size_t(componentSize_);
        switch (componentType_) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized_ ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            auto v = static_cast<int8_t>(p[0]);
            return normalized_ ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized_ ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized_ ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default: throwBadInput(what_ + ": unsupported component type");
        }
    }

    uint32_t index(size_t element) const {
        if (componentType_ != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            componentType_ != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            componentType_ != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throwBadInput(what_ + ": indices must be unsigned integers");
        return static_cast<uint32_t>(component(element, 0));
    }

private:
    std::string what_;
    const uint8_t* base_ = nullptr;
    size_t count_ = 0, stride_ = 0;
    int components_ = 0, componentSize_ = 0, componentType_ = 0;
    bool normalized_ = false;
};

glm::dmat4 nodeMatrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
    glm::dmat4 m(1.0);
    if (n.translation.size() == 3)
        m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4) // glTF stores x, y, z, w
        m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
    if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

struct Welder {
    Mesh mesh;
    std::map<std::array<double, 3>, uint32_t> positionIndex;
    std::map<std::array<double, 2>, uint32_t> uvIndex;
    bool anyUV = false, anyWithoutUV = false;
    size_t degenerate = 0, skippedPrimitives = 0;
    int material = -1;           // the first triangle primitive's material
    bool otherMaterials = false; // a later primitive has another one

    uint32_t weldPosition(const glm::dvec3& p) {
        auto [it, inserted] = positionIndex.try_emplace({p.x, p.y, p.z},
                                                         static_cast<uint32_t>(mesh.positions.size()));
        if (inserted) mesh.positions.push_back(p);
        return it->second;
    }
    uint32_t weldUV(const glm::dvec2& uv) {
        auto [it, inserted] = uvIndex.try_emplace({uv.x, uv.y}, static_cast<uint32_t>(mesh.uvs.size()));
        if (inserted) mesh.uvs.push_back(uv);
        return it->second;
    }

    void addPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                      const glm::dmat4& transform, const std::string& what) {
        int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            ++skippedPrimitives;
            return;
        }
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) throwBadInput(what + " has no POSITION attribute");
        if (prim.material >= 0) {
            if (material < 0) material = prim.material;
            else if (prim.material != material) otherMaterials = true;
        }
        AccessorView positions(model, pos->second, what + " POSITION");
        if (positions.components() != 3) throwBadInput(what + " POSITION is not a 3-vector");
        std::vector<uint32_t> welded(positions.count());
        for (size_t i = 0; i < positions.count(); ++i) {
            glm::dvec4 p(positions.component(i, 0), positions.component(i, 1),
                         positions.component(i, 2), 1.0);
            const glm::dvec3 q(transform * p);
            // A NaN would also break the welding map's ordering; refuse it like Inf.
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                throwBadInput(what + " POSITION " + std::to_string(i) +
                              " is not finite (NaN or Inf), after the node transforms");
            welded[i] = weldPosition(q);
        }
        std::vector<uint32_t> uvs;
        auto tc = prim.attributes.find("TEXCOORD_0");
        if (tc != prim.attributes.end()) {
            AccessorView texcoords(model, tc->second, what + " TEXCOORD_0");
            if (texcoords.components() != 2 || texcoords.count() != positions.count())
                throwBadInput(what + " TEXCOORD_0 does not match POSITION");
            uvs.resize(texcoords.count());
            for (size_t i = 0; i < texcoords.count(); ++i) {
                const double u = texcoords.component(i, 0), v = texcoords.component(i, 1);
                if (!std::isfinite(u) || !std::isfinite(v))
                    throwBadInput(what + " TEXCOORD_0 " + std::to_string(i) + " is not finite");
                uvs[i] = weldUV({u, 1.0 - v});
            }
            anyUV = true;
        } else {
            anyWithoutUV = true;
        }
        std::vector<uint32_t> corners;
        if (prim.indices >= 0) {
            AccessorView indices(model, prim.indices, what + " indices");
            corners.resize(indices.count());
            for (size_t i = 0; i < indices.count(); ++i) {
                corners[i] = indices.index(i);
                if (corners[i] >= positions.count())
                    throwBadInput(what + " index " + std::to_string(corners[i]) +
                                  " is past the " + std::to_string(positions.count()) +
                                  " vertices");
            }
        } else {
            corners.resize(positions.count());
            for (size_t i = 0; i < corners.size(); ++i) corners[i] = static_cast<uint32_t>(i);
        }
        // Strips and fans as the triangles glTF 2.0 (3.7.2.1) defines: strip triangle i is
        // {v_i, v_i+(1+i%2), v_i+(2-i%2)}, fan triangle i is {v_i+1, v_i+2, v_0}.
        if (mode != TINYGLTF_MODE_TRIANGLES) {
            std::vector<uint32_t> list;
            for (size_t i = 0; i + 2 < corners.size(); ++i) {
                if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                    list.insert(list.end(), {corners[i], corners[i + 1 + i % 2], corners[i + 2 - i % 2]});
                else
                    list.insert(list.end(), {corners[i + 1], corners[i + 2], corners[0]});
            }
            corners = std::move(list);
        }
        if (corners.size() % 3) throwBadInput(what + " index count is not a multiple of 3");
        for (size_t t = 0; t < corners.size(); t += 3) {
            uint32_t a = welded[corners[t]], b = welded[corners[t + 1]], c = welded[corners[t + 2]];
            if (a == b || b == c || a == c) { // collapsed by welding or degenerate in the file
                ++degenerate;
                continue;
            }
            uint32_t tri[3] = {a, b, c};
            mesh.addFace(tri);
            for (int k = 0; k < 3; ++k)
                mesh.uvIndices.push_back(uvs.empty() ? ~0u : uvs[corners[t + k]]);
        }
    }

    void addNode(const tinygltf::Model& model, int nodeIndex, const glm::dmat4& parent, int depth) {
        if (nodeIndex < 0 || nodeIndex >= static_cast<int>(model.nodes.size()))
            throwBadInput("node " + std::to_string(nodeIndex) + " does not exist");
        if (depth > 256) throwBadInput("node hierarchy deeper than 256 (a cycle?)");
        const auto& node = model.nodes[nodeIndex];
        glm::dmat4 transform = parent * nodeMatrix(node);
        if (node.mesh >= 0) {
            if (node.mesh >= static_cast<int>(model.meshes.size()))
                throwBadInput("node " + std::to_string(nodeIndex) + " refers to a missing mesh");
            const auto& m = model.meshes[node.mesh];
            for (size_t p = 0; p < m.primitives.size(); ++p)
                addPrimitive(model, m.primitives[p], transform,
                             "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
        }
        for (int child : node.children) addNode(model, child, transform, depth + 1);
    }
};

} // namespace

namespace {

// Reads a file the asset names (buffers, images) for tinygltf, noting each (the depfile lists them).
bool readAndRecord(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
    // limn's reader, not tinygltf's: a directory named as a buffer gave "out of memory" with no
    // name; this one names the file and refuses directories and endless inputs.
    if (isStdio(path)) { // readInput's name for standard input
        if (err) *err += "a buffer or image has an empty name or '-'\n";
        return false;
    }
    try {
        *out = readInput(path);
    } catch (const Error& e) {
        if (err) *err += path + ": " + e.what() + "\n";
        return false;
    }
    if (user) static_cast<std::vector<std::string>*>(user)->push_back(path);
    return true;
}

} // namespace

namespace {

// The base colour of material `index` (glTF 2.0, 3.9.2: pbrMetallicRoughness.baseColorFactor
// and baseColorTexture).
MeshMaterial baseColor(const tinygltf::Model& model, int index, ImageBytes& images,
                       Warnings& warnings) {
    if (index >= static_cast<int>(model.materials.size()))
        throwBadInput("glTF: a primitive refers to material " + std::to_string(index) +
                      ", which does not exist");
    const auto& pbr = model.materials[index].pbrMetallicRoughness;
    MeshMaterial m;
    if (pbr.baseColorFactor.size() == 4) {
        for (int c = 0; c < 4; ++c) {
            const double v = pbr.baseColorFactor[c];
            if (!(v >= 0 && v <= 1))
                throwBadInput("glTF: material " + std::to_string(index) +
                              " baseColorFactor component " + std::to_string(c) +
                              " is not within 0 to 1");
            m.baseColorFactor[c] = v;
        }
    }
    const auto& ref = pbr.baseColorTexture;
    if (ref.index < 0) return m;
    if (ref.index >= static_cast<int>(model.textures.size()))
        throwBadInput("glTF: material " + std::to_string(index) + " refers to texture " +
                      std::to_string(ref.index) + ", which does not exist");
    const int source = model.textures[ref.index].source;
    if (source < 0 || source >= static_cast<int>(model.images.size()))
        throwBadInput("glTF: texture " + std::to_string(ref.index) + " has no image");
    if (ref.texCoord != 0) {
        warnings.add("the base colour texture uses TEXCOORD_" + std::to_string(ref.texCoord) +
                     ", limn keeps only TEXCOORD_0; texture dropped");
        return m;
    }
    auto it = images.find(source);
    if (it == images.end() || it->second.empty())
        throwBadInput("glTF: image " + std::to_string(source) + " of the base colour texture is empty");
    m.textureFormat = imageFormatName(it->second, model.images[source]);
    m.textureBytes = std::move(it->second);
    return m;
}

// tinygltf's JSON parser recurses once per nesting level: a 40 KB file of 15,000 nested '['
// overflows the stack (SIGSEGV). Real glTF nests about ten levels (extras included); anything
// past kMaxJsonDepth is refused before the parser sees it. Strings are skipped, escapes included.
constexpr int kMaxJsonDepth = 256;

void refuseDeepJson(std::span<const uint8_t> json) {
    int depth = 0;
    bool inString = false;
    for (size_t i = 0; i < json.size(); ++i) {
        const uint8_t c = json[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throwBadInput("glTF: the JSON nests deeper than " + std::to_string(kMaxJsonDepth) +
                              " levels (at byte " + std::to_string(i) + ")");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

// The JSON of a .glb: its first chunk (header: magic, version, length; chunk: length, type).
// A header too short or a length past the end is left to tinygltf, which names the fault.
std::span<const uint8_t> glbJson(std::span<const uint8_t> bytes) {
    if (bytes.size() < 20) return {};
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return bytes.subspan(20, std::min<size_t>(length, bytes.size() - 20));
}

} // namespace

Mesh readGltf(std::span<const uint8_t> bytes, bool binary, const std::string& baseDir,
              Warnings& warnings, std::vector<std::string>* filesRead, std::optional<MeshMaterial>* material) {
    refuseDeepJson(binary ? glbJson(bytes) : bytes);
    tinygltf::TinyGLTF loader;
    ImageBytes images;
    loader.SetImageLoader(keepImageBytes, material ? &images : nullptr);
    loader.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readAndRecord,
                           &tinygltf::WriteWholeFile, filesRead});
    tinygltf::Model model;
    std::string err, warn;
    bool ok;
    if (binary)
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                         static_cast<unsigned int>(bytes.size()), baseDir);
    else
        ok = loader.LoadASCIIFromString(&model, &err, &warn,
                                        reinterpret_cast<const char*>(bytes.data()),
                                        static_cast<unsigned int>(bytes.size()), baseDir);
    if (!ok) {
        while (!err.empty() && err.back() == '\n') err.pop_back();
        throwBadInput("glTF: " + (err.empty() ? std::string("cannot parse") : err));
    }
    Welder w;
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (scene >= static_cast<int>(model.scenes.size()))
            throwBadInput("glTF: default scene does not exist");
        roots = model.scenes[scene].nodes;
    } else { // no scene: every node that is nobody's child
        std::vector<bool> isChild(model.nodes.size());
        for (const auto& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && c < static_cast<int>(isChild.size())) isChild[c] = true;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    for (int root : roots) w.addNode(model, root, glm::dmat4(1.0), 0);
    if (w.skippedPrimitives) {
        const std::string skipped = std::to_string(w.skippedPrimitives) + " point or line primitives";
        if (w.mesh.faceCount() == 0) throwBadInput("glTF: no triangles to subdivide, only " + skipped);
        warnings.add(skipped + " skipped");
    }
    if (w.degenerate)
        warnings.add(std::to_string(w.degenerate) +
                     " degenerate triangles (two corners at the same position) dropped");
    if (w.anyUV && w.anyWithoutUV) {
        warnings.add("some primitives have TEXCOORD_0 and some do not; UVs dropped");
        w.mesh.uvs.clear();
        w.mesh.uvIndices.clear();
    } else if (!w.anyUV) {
        w.mesh.uvIndices.clear();
    }
    validateMesh(w.mesh);
    if (material && w.material >= 0) {
        *material = baseColor(model, w.material, images, warnings);
        if (w.otherMaterials)
            warnings.add("the primitives use more than one material; limn draws the first one's "
                         "base colour on the whole mesh");
    }
    return std::move(w.mesh);
}

} // namespace limn
