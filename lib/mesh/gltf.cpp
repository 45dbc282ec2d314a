#include "mesh/gltf.h"
#include "mesh/gltf_parts.h"

#include "base/error.h"
#include "base/io.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
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

// The morph target weights of an instance: the node's, else the mesh's (glTF 2.0, 3.7.2.2).
const std::vector<double>& morphWeights(const tinygltf::Node& node, const tinygltf::Mesh& mesh) {
    return node.weights.empty() ? mesh.weights : node.weights;
}

} // namespace

namespace {

// What tinygltf's file callbacks may do: read files (noting each in `filesRead`), or none at all.
struct FileAccess {
    std::vector<std::string>* filesRead = nullptr;
    bool allowed = true;
};

// Without file access nothing is looked up: every name "exists", so that the read is refused with
// the reason (not "file not found"), and tinygltf's path expansion (wordexp) is not run either:
// untrusted bytes reach neither the file system nor the shell's expansion rules.
bool fileExists(const std::string& path, void* user) {
    return !static_cast<FileAccess*>(user)->allowed || tinygltf::FileExists(path, nullptr);
}
std::string expandPath(const std::string& path, void* user) {
    return static_cast<FileAccess*>(user)->allowed ? tinygltf::ExpandFilePath(path, nullptr) : path;
}

// Reads a file the asset names (buffers, images) for tinygltf, noting each (the depfile lists them).
bool readAndRecord(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
    const FileAccess& access = *static_cast<FileAccess*>(user);
    if (!access.allowed) {
        if (err) *err += path + ": this reader reads embedded data only (a GLB buffer or a data: URI)\n";
        return false;
    }
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
    if (access.filesRead) access.filesRead->push_back(path);
    return true;
}

} // namespace

namespace {

// The base colour texture's KHR_texture_transform as the matrix its specification gives
// (translation * rotation * scale, on glTF's UVs), or nothing when the texture has none.
std::optional<glm::dmat3> textureTransform(const tinygltf::Model& model, int materialIndex) {
    if (materialIndex < 0 || materialIndex >= static_cast<int>(model.materials.size())) return {};
    const auto& ext = model.materials[materialIndex].pbrMetallicRoughness.baseColorTexture.extensions;
    auto it = ext.find("KHR_texture_transform");
    if (it == ext.end() || !it->second.IsObject()) return {};
    const tinygltf::Value& t = it->second;
    auto number = [&](const tinygltf::Value& v, const std::string& what) {
        if (!v.IsNumber()) throwBadInput("glTF: KHR_texture_transform " + what + " is not a number");
        const double d = v.GetNumberAsDouble();
        if (!std::isfinite(d)) throwBadInput("glTF: KHR_texture_transform " + what + " is not finite");
        return d;
    };
    auto pair = [&](const char* key, glm::dvec2 fallback) {
        if (!t.Has(key)) return fallback;
        const auto& v = t.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2) throwBadInput(std::string("glTF: KHR_texture_transform ") + key + " is not two numbers");
        return glm::dvec2(number(v.Get(0), key), number(v.Get(1), key));
    };
    const glm::dvec2 offset = pair("offset", {0, 0}), scale = pair("scale", {1, 1});
    const double r = t.Has("rotation") ? number(t.Get("rotation"), "rotation") : 0.0;
    const glm::dmat3 translation(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
    const glm::dmat3 rotation(std::cos(r), std::sin(r), 0, -std::sin(r), std::cos(r), 0, 0, 0, 1);
    const glm::dmat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
    return translation * rotation * scaling;
}

// The texture coordinate set KHR_texture_transform's texCoord names instead of the texture's.
int transformTexCoord(const tinygltf::TextureInfo& ref) {
    auto it = ref.extensions.find("KHR_texture_transform");
    if (it != ref.extensions.end() && it->second.IsObject() && it->second.Has("texCoord") &&
        it->second.Get("texCoord").IsInt())
        return it->second.Get("texCoord").GetNumberAsInt();
    return ref.texCoord;
}

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
    if (transformTexCoord(ref) != 0) {
        warnings.add("the base colour texture uses TEXCOORD_" + std::to_string(transformTexCoord(ref)) +
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

namespace gltf {

Loaded load(std::span<const uint8_t> bytes, bool binary, const std::string* baseDir, Warnings& warnings,
            std::vector<std::string>* filesRead, std::map<int, std::vector<uint8_t>>* images) {
    Loaded out;
    FileAccess access{filesRead, baseDir != nullptr};
    const std::string dir = baseDir ? *baseDir : std::string();
    refuseDeepJson(binary ? glbJson(bytes) : bytes);
    out.pre = gltf::prepass(bytes, binary, warnings);
    if (!out.pre.rewritten.empty()) bytes = out.pre.rewritten;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageBytes, images);
    loader.SetFsCallbacks({&fileExists, &expandPath, &readAndRecord, &tinygltf::WriteWholeFile, &access});
    tinygltf::Model& model = out.model;
    std::string err, warn;
    bool ok;
    if (binary)
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                         static_cast<unsigned int>(bytes.size()), dir);
    else
        ok = loader.LoadASCIIFromString(&model, &err, &warn,
                                        reinterpret_cast<const char*>(bytes.data()),
                                        static_cast<unsigned int>(bytes.size()), dir);
    if (!ok) {
        while (!err.empty() && err.back() == '\n') err.pop_back();
        throwBadInput("glTF: " + (err.empty() ? std::string("cannot parse") : err));
    }
    std::vector<int>& roots = out.roots;
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
    // The node graph is checked before any buffer is decoded.
    out.instances = gltf::sceneInstances(model, roots, warnings);
    gltf::decodeMeshopt(model, out.pre);
    return out;
}

} // namespace gltf

gltf::PrimitiveData gltf::primitiveData(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                         const gltf::Prepass& pre, std::pair<int, int> key,
                                         const std::vector<double>& weights, const std::string& what) {
    gltf::PrimitiveData d;
    if (auto draco = pre.draco.find(key); draco != pre.draco.end()) {
        gltf::decodeDraco(model, draco->second, what, d);
    } else {
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) throwBadInput(what + " has no POSITION attribute");
        const gltf::AccessorData p = gltf::readAccessor(model, pos->second, what + " POSITION");
        if (p.components != 3) throwBadInput(what + " POSITION is not a 3-vector");
        d.positions.resize(p.count);
        for (size_t i = 0; i < p.count; ++i) d.positions[i] = {p.at(i, 0), p.at(i, 1), p.at(i, 2)};
        if (auto tc = prim.attributes.find("TEXCOORD_0"); tc != prim.attributes.end()) {
            const gltf::AccessorData t = gltf::readAccessor(model, tc->second, what + " TEXCOORD_0");
            if (t.components != 2 || t.count != p.count) throwBadInput(what + " TEXCOORD_0 does not match POSITION");
            d.texcoords.resize(t.count);
            for (size_t i = 0; i < t.count; ++i) d.texcoords[i] = {t.at(i, 0), t.at(i, 1)};
        }
        if (prim.indices >= 0) {
            d.indices = gltf::readIndices(model, prim.indices, what + " indices");
            d.hasIndices = true;
        } else if (auto iv = pre.indicesWithoutView.find(key); iv != pre.indicesWithoutView.end()) {
            d.indices = gltf::readIndices(model, iv->second, what + " indices");
            d.hasIndices = true;
        }
    }
    // Morph targets (glTF 2.0, 3.7.2.2): position = base + sum of weight * displacement.
    if (!prim.targets.empty() && !weights.empty()) {
        if (weights.size() != prim.targets.size())
            throwBadInput(what + " has " + std::to_string(prim.targets.size()) + " morph targets but " +
                          std::to_string(weights.size()) + " weights");
        for (size_t t = 0; t < prim.targets.size(); ++t) {
            if (weights[t] == 0.0) continue;
            const std::string target = what + " morph target " + std::to_string(t);
            if (auto a = prim.targets[t].find("POSITION"); a != prim.targets[t].end()) {
                const gltf::AccessorData delta = gltf::readAccessor(model, a->second, target + " POSITION");
                if (delta.components != 3 || delta.count != d.positions.size())
                    throwBadInput(target + " POSITION does not match the primitive's POSITION");
                for (size_t i = 0; i < delta.count; ++i)
                    d.positions[i] += weights[t] * glm::dvec3(delta.at(i, 0), delta.at(i, 1), delta.at(i, 2));
            }
            if (auto a = prim.targets[t].find("TEXCOORD_0"); a != prim.targets[t].end() && !d.texcoords.empty()) {
                const gltf::AccessorData delta = gltf::readAccessor(model, a->second, target + " TEXCOORD_0");
                if (delta.components != 2 || delta.count != d.texcoords.size())
                    throwBadInput(target + " TEXCOORD_0 does not match the primitive's TEXCOORD_0");
                for (size_t i = 0; i < delta.count; ++i)
                    d.texcoords[i] += weights[t] * glm::dvec2(delta.at(i, 0), delta.at(i, 1));
            }
        }
    }
    return d;
}

Mesh readGltf(std::span<const uint8_t> bytes, bool binary, const std::string& baseDir,
              Warnings& warnings, std::vector<std::string>* filesRead, std::optional<MeshMaterial>* material,
              GltfPolygons* polygons) {
    return gltf::readFrom(bytes, binary, &baseDir, warnings, filesRead, material, polygons);
}

Mesh readGltfEmbedded(std::span<const uint8_t> bytes, bool binary, Warnings& warnings,
                      std::optional<MeshMaterial>* material) {
    return gltf::readFrom(bytes, binary, nullptr, warnings, nullptr, material, nullptr);
}

Mesh gltf::readFrom(std::span<const uint8_t> bytes, bool binary, const std::string* baseDir, Warnings& warnings,
                    std::vector<std::string>* filesRead, std::optional<MeshMaterial>* material,
                    GltfPolygons* polygons) {
    ImageBytes images;
    gltf::Loaded loaded = gltf::load(bytes, binary, baseDir, warnings, filesRead, material ? &images : nullptr);
    const tinygltf::Model& model = loaded.model;
    const gltf::Prepass& pre = loaded.pre;
    const std::vector<gltf::NodeInstance>& instances = loaded.instances;
    gltf::Welder w;
    w.rebuildNgons = polygons && polygons->rebuildNgons;
    for (const auto& instance : instances) {
        const auto& node = model.nodes[instance.node];
        if (node.mesh < 0) continue;
        if (node.mesh >= static_cast<int>(model.meshes.size()))
            throwBadInput("glTF: node " + std::to_string(instance.node) + " refers to a missing mesh");
        const auto& m = model.meshes[node.mesh];
        for (size_t p = 0; p < m.primitives.size(); ++p)
            w.addPrimitive(model, m.primitives[p], pre, {node.mesh, int(p)}, morphWeights(node, m),
                           instance.transform,
                           "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
    }
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
    // The UVs address the base colour texture as a viewer shows it (limn draws one texture).
    if (w.mesh.hasUVs() && w.material >= 0 && size_t(w.material) < model.materials.size() &&
        transformTexCoord(model.materials[size_t(w.material)].pbrMetallicRoughness.baseColorTexture) == 0)
        if (const auto t = textureTransform(model, w.material))
            for (auto& uv : w.mesh.uvs) {
                const glm::dvec3 g = *t * glm::dvec3(uv.x, 1.0 - uv.y, 1.0); // limn's v is up
                uv = {g.x, 1.0 - g.y};
            }
    validateMesh(w.mesh);
    if (material && w.material >= 0) {
        *material = baseColor(model, w.material, images, warnings);
        if (w.otherMaterials)
            warnings.add("the primitives use more than one material; limn draws the first one's "
                         "base colour on the whole mesh");
    }
    if (polygons) {
        polygons->fileHasNgonEncoding = pre.ngonEncoding;
        polygons->ngonsRebuilt = w.ngons;
    }
    return std::move(w.mesh);
}

} // namespace limn
