// The glTF JSON read once before tinygltf (nlohmann's parser, the one tinygltf itself uses):
// extensionsRequired is checked first, so that a file limn cannot draw correctly is refused by
// name instead of failing later with a message about a buffer view; and the two constructs of
// compressed files that tinygltf 2.7 refuses are taken out of the JSON it sees.
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <set>

namespace limn::gltf {

namespace {

using Json = nlohmann::json;

// The extensions limn reads. KHR_mesh_quantization only widens the accessor types, which the
// accessor reader takes; FB_ngon_encoding only orders triangles (limn-classify --quads).
const std::set<std::string> kRead = {
    "KHR_mesh_quantization",   "KHR_draco_mesh_compression", "EXT_meshopt_compression",
    "KHR_meshopt_compression", "KHR_texture_transform",      "FB_ngon_encoding"};

std::string list(const std::vector<std::string>& names) {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
    return out;
}

std::vector<std::string> strings(const Json& doc, const char* key) {
    std::vector<std::string> out;
    auto it = doc.find(key);
    if (it == doc.end() || !it->is_array()) return out;
    for (const auto& s : *it)
        if (s.is_string()) out.push_back(s.get<std::string>());
    return out;
}

// A non-negative integer member, or `fallback` when absent; anything else is refused.
uint64_t count(const Json& o, const char* key, const std::string& what, std::optional<uint64_t> fallback = {}) {
    auto it = o.find(key);
    if (it == o.end()) {
        if (fallback) return *fallback;
        throwBadInput("glTF: " + what + " has no " + key);
    }
    if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<int64_t>() >= 0))
        throwBadInput("glTF: " + what + " " + key + " is not a non-negative integer");
    return it->get<uint64_t>();
}

int indexOf(const Json& o, const char* key, const std::string& what) {
    const uint64_t v = count(o, key, what);
    if (v > uint64_t(std::numeric_limits<int>::max())) throwBadInput("glTF: " + what + " " + key + " is out of range");
    return static_cast<int>(v);
}

void readDraco(Json& doc, Prepass& out) {
    auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array()) return;
    auto accessors = doc.find("accessors");
    for (size_t m = 0; m < meshes->size(); ++m) {
        auto& mesh = (*meshes)[m];
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        auto& primitives = mesh["primitives"];
        for (size_t p = 0; p < primitives.size(); ++p) {
            auto& prim = primitives[p];
            if (!prim.is_object()) continue;
            const auto key = std::make_pair(int(m), int(p));
            const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            if (prim.contains("extensions") && prim["extensions"].is_object()) {
                const auto& ext = prim["extensions"];
                if (ext.contains("FB_ngon_encoding")) out.ngonEncoding = true;
                if (ext.contains("KHR_draco_mesh_compression")) {
                    const auto& d = ext["KHR_draco_mesh_compression"];
                    if (!d.is_object()) throwBadInput("glTF: " + what + " KHR_draco_mesh_compression is not an object");
                    DracoPrimitive draco;
                    draco.bufferView = indexOf(d, "bufferView", what + " KHR_draco_mesh_compression");
                    if (!d.contains("attributes") || !d["attributes"].is_object())
                        throwBadInput("glTF: " + what + " KHR_draco_mesh_compression has no attributes");
                    for (const auto& [name, id] : d["attributes"].items()) {
                        if (!id.is_number_integer() || id.get<int64_t>() < 0 || id.get<int64_t>() > 1'000'000)
                            throwBadInput("glTF: " + what + " KHR_draco_mesh_compression attribute " + name +
                                          " is not a Draco attribute id");
                        draco.attributes[name] = static_cast<int>(id.get<int64_t>());
                    }
                    out.draco[key] = std::move(draco);
                }
            }
            // An index accessor without a buffer view (Draco's, or zeros with a sparse
            // substitution) is read by limn, not by tinygltf.
            auto indices = prim.find("indices");
            if (indices != prim.end() && indices->is_number_integer() && accessors != doc.end() &&
                accessors->is_array()) {
                const int64_t a = indices->get<int64_t>();
                if (a >= 0 && size_t(a) < accessors->size() && (*accessors)[size_t(a)].is_object() &&
                    !(*accessors)[size_t(a)].contains("bufferView")) {
                    out.indicesWithoutView[key] = static_cast<int>(a);
                    prim.erase("indices");
                }
            }
        }
    }
}

// Every buffer view within its buffer's byteLength (glTF 2.0, 3.6.2.2: offset + length at most
// the buffer's length). tinygltf 2.7 hands an image's buffer view to the image loader unchecked,
// so a view past its buffer's end read past tinygltf's copy of the buffer (found by fuzz_gltf).
void checkBufferViews(const Json& doc) {
    auto views = doc.find("bufferViews");
    auto buffers = doc.find("buffers");
    if (views == doc.end() || !views->is_array() || buffers == doc.end() || !buffers->is_array()) return;
    for (size_t v = 0; v < views->size(); ++v) {
        const auto& view = (*views)[v];
        if (!view.is_object() || !view.contains("buffer")) continue; // tinygltf names the fault
        const std::string what = "buffer view " + std::to_string(v);
        const uint64_t b = count(view, "buffer", what);
        if (b >= buffers->size() || !(*buffers)[b].is_object()) continue; // as above
        const uint64_t size = count((*buffers)[b], "byteLength", "buffer " + std::to_string(b));
        const uint64_t offset = count(view, "byteOffset", what, 0), length = count(view, "byteLength", what);
        if (offset > size || length > size - offset)
            throwBadInput("glTF: " + what + " (" + std::to_string(length) + " bytes at " + std::to_string(offset) +
                          ") runs past the end of buffer " + std::to_string(b) + " (" + std::to_string(size) +
                          " bytes)");
    }
}

void readMeshopt(Json& doc, bool binary, Prepass& out) {
    auto views = doc.find("bufferViews");
    if (views != doc.end() && views->is_array()) {
        for (size_t v = 0; v < views->size(); ++v) {
            const auto& view = (*views)[v];
            if (!view.is_object() || !view.contains("extensions") || !view["extensions"].is_object()) continue;
            for (const char* name : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
                if (!view["extensions"].contains(name)) continue;
                const auto& e = view["extensions"][name];
                const std::string what = "buffer view " + std::to_string(v) + " " + name;
                if (!e.is_object()) throwBadInput("glTF: " + what + " is not an object");
                MeshoptView m;
                m.extension = name;
                m.buffer = indexOf(e, "buffer", what);
                m.byteOffset = count(e, "byteOffset", what, 0);
                m.byteLength = count(e, "byteLength", what);
                m.byteStride = count(e, "byteStride", what);
                m.count = count(e, "count", what);
                if (!e.contains("mode") || !e["mode"].is_string()) throwBadInput("glTF: " + what + " has no mode");
                m.mode = e["mode"].get<std::string>();
                m.filter = e.contains("filter") && e["filter"].is_string() ? e["filter"].get<std::string>() : "NONE";
                out.meshopt[int(v)] = m;
            }
        }
    }
    if (out.meshopt.empty()) return;
    // A buffer without a URI (other than a .glb's own binary chunk) is a fallback placeholder:
    // its bytes exist only once decoded. tinygltf gets a 4-byte stand-in.
    auto buffers = doc.find("buffers");
    if (buffers == doc.end() || !buffers->is_array()) return;
    for (size_t b = 0; b < buffers->size(); ++b) {
        auto& buffer = (*buffers)[b];
        if (!buffer.is_object() || buffer.contains("uri") || (binary && b == 0)) continue;
        out.placeholderBuffers[int(b)] = count(buffer, "byteLength", "buffer " + std::to_string(b));
        buffer["uri"] = "data:application/octet-stream;base64,AAAAAA==";
        buffer["byteLength"] = 4;
    }
}

void put32(std::vector<uint8_t>& out, size_t at, uint32_t v) { std::memcpy(out.data() + at, &v, 4); }

// The .glb with its JSON chunk replaced; the chunks after it are kept byte for byte.
std::vector<uint8_t> replaceGlbJson(std::span<const uint8_t> glb, std::string json) {
    uint32_t oldLength = 0;
    std::memcpy(&oldLength, glb.data() + 12, 4);
    while (json.size() % 4) json += ' ';
    const size_t rest = 20 + size_t(oldLength);
    std::vector<uint8_t> out(20 + json.size());
    std::memcpy(out.data(), glb.data(), 12);
    put32(out, 12, uint32_t(json.size()));
    std::memcpy(out.data() + 16, glb.data() + 16, 4);
    std::memcpy(out.data() + 20, json.data(), json.size());
    if (rest < glb.size()) out.insert(out.end(), glb.begin() + std::ptrdiff_t(rest), glb.end());
    put32(out, 8, uint32_t(out.size()));
    return out;
}

} // namespace

Prepass prepass(std::span<const uint8_t> bytes, bool binary, Warnings& warnings) {
    Prepass out;
    std::span<const uint8_t> text = bytes;
    if (binary) {
        if (bytes.size() < 20) return out; // tinygltf names the fault
        uint32_t length = 0;
        std::memcpy(&length, bytes.data() + 12, 4);
        if (length > bytes.size() - 20) return out;
        text = bytes.subspan(20, length);
    }
    Json doc = Json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (!doc.is_object()) return out;

    for (const auto& name : strings(doc, "extensionsRequired"))
        if (!kRead.count(name))
            throwBadInput("glTF: the file requires " + name + ", which limn does not read (limn reads " +
                          list({kRead.begin(), kRead.end()}) + ")");
    std::vector<std::string> ignored;
    for (const auto& name : strings(doc, "extensionsUsed"))
        if (!kRead.count(name) && std::find(ignored.begin(), ignored.end(), name) == ignored.end())
            ignored.push_back(name);
    if (!ignored.empty())
        warnings.add("the file uses " + list(ignored) + ", which limn does not read (optional; ignored)");

    checkBufferViews(doc);
    readDraco(doc, out);
    readMeshopt(doc, binary, out);
    if (out.indicesWithoutView.empty() && out.placeholderBuffers.empty()) return out;
    const std::string json = doc.dump();
    if (binary) {
        out.rewritten = replaceGlbJson(bytes, json);
    } else {
        out.rewritten.assign(json.begin(), json.end());
    }
    return out;
}

} // namespace limn::gltf
