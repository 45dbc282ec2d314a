#include "export/mesh_export.h"

#include "base/bytes.h"
#include "base/error.h"
#include "mesh/text_format.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace limn::exporting {

namespace {

void checkIndices(const DrawnMesh& mesh) {
    if (mesh.triangles.size() % 3 != 0)
        throw Error(ErrorKind::BadInput, "internal: the drawn triangle list is not a multiple of 3");
    for (uint32_t i : mesh.triangles)
        if (i >= mesh.vertices.size())
            throw Error(ErrorKind::BadInput, "internal: a drawn triangle names vertex " +
                                                 std::to_string(i) + " of " +
                                                 std::to_string(mesh.vertices.size()));
}

// Numbers each distinct bit pattern of N floats once, in order of first use (1-based, as OBJ).
template <size_t N>
class Distinct {
public:
    uint32_t add(const std::array<float, N>& value, std::string& lines, const char* tag) {
        std::array<uint32_t, N> key;
        for (size_t k = 0; k < N; ++k) key[k] = std::bit_cast<uint32_t>(value[k]);
        auto [it, inserted] = ids_.try_emplace(key, static_cast<uint32_t>(ids_.size() + 1));
        if (inserted) {
            lines += tag;
            for (float f : value) {
                lines += ' ';
                appendShortest(lines, f);
            }
            lines += '\n';
        }
        return it->second;
    }

private:
    std::map<std::array<uint32_t, N>, uint32_t> ids_;
};

// Appends a bufferView over bytes [offset, end of buffer) and an accessor of `count` elements.
int addAccessor(tinygltf::Model& model, size_t offset, int target, int componentType, int type,
                size_t count) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = model.buffers[0].data.size() - offset;
    view.target = target;
    model.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = static_cast<int>(model.bufferViews.size() - 1);
    a.byteOffset = 0;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size() - 1);
}

// OBJ has no per-vertex attribute: the `v` of the vertices drawn where the surface is approximate
// (DrawnVertex::approximate) are listed in comments, 1-based like OBJ's indices, ascending,
// sixteen a line, after a line with their count. Nothing when no vertex is approximate.
std::string objApproximateComments(const DrawnMesh& mesh, const std::vector<std::array<uint32_t, 3>>& ids) {
    std::vector<uint32_t> approximate;
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        if (mesh.vertices[i].approximate) approximate.push_back(ids[i][0]);
    if (approximate.empty()) return {};
    std::sort(approximate.begin(), approximate.end());
    approximate.erase(std::unique(approximate.begin(), approximate.end()), approximate.end());
    std::string out = "# approximate: " + std::to_string(approximate.size()) +
                      " positions are drawn where the surface is not the limit surface (bilinear within "
                      "2^-K of an extraordinary corner; limn-tables --irregular-levels)\n";
    for (size_t i = 0; i < approximate.size(); ++i) {
        out += i % 16 == 0 ? "# approximate v" : "";
        out += ' ' + std::to_string(approximate[i]);
        if (i % 16 == 15 || i + 1 == approximate.size()) out += '\n';
    }
    return out;
}

} // namespace

std::optional<ExportFormat> exportFormatFromPath(const std::string& path) {
    if (path == "-") return ExportFormat::Ply;
    const auto slash = path.find_last_of('/');
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::nullopt;
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : char(c); });
    if (ext == "ply") return ExportFormat::Ply;
    if (ext == "obj") return ExportFormat::Obj;
    if (ext == "gltf") return ExportFormat::Gltf;
    if (ext == "glb") return ExportFormat::Glb;
    return std::nullopt;
}

std::vector<uint8_t> encodeObj(const DrawnMesh& mesh) {
    checkIndices(mesh);
    std::string v, vt, vn, f;
    Distinct<3> positions, normals;
    Distinct<2> uvs;
    std::vector<std::array<uint32_t, 3>> ids(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const DrawnVertex& d = mesh.vertices[i];
        ids[i][0] = positions.add({d.x, d.y, d.z}, v, "v");
        ids[i][1] = mesh.hasTexCoords ? uvs.add({d.s, d.t}, vt, "vt") : 0;
        ids[i][2] = normals.add({d.nx, d.ny, d.nz}, vn, "vn");
    }
    for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
        f += 'f';
        for (size_t k = 0; k < 3; ++k) {
            const auto& id = ids[mesh.triangles[t + k]];
            f += ' ' + std::to_string(id[0]) + '/';
            if (mesh.hasTexCoords) f += std::to_string(id[1]);
            f += '/' + std::to_string(id[2]);
        }
        f += '\n';
    }
    std::string out = "# limn-render: the triangles as drawn\n";
    out += objApproximateComments(mesh, ids);
    out += v;
    out += vt;
    out += vn;
    out += f;
    return {out.begin(), out.end()};
}

std::vector<uint8_t> encodeGltf(const DrawnMesh& mesh, bool binary) {
    checkIndices(mesh);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "limn-render";
    const size_t n = mesh.vertices.size();
    // glTF accessors hold at least one element: nothing drawn is an asset with no scene.
    if (n > 0 && !mesh.triangles.empty()) {
        model.buffers.emplace_back();
        auto& data = model.buffers[0].data;
        data.reserve(n * (mesh.hasTexCoords ? 36 : 28) + mesh.triangles.size() * 4);
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;

        std::array<double, 3> lo, hi;
        lo.fill(0), hi.fill(0);
        for (size_t i = 0; i < n; ++i) {
            const DrawnVertex& d = mesh.vertices[i];
            const float p[3] = {d.x, d.y, d.z};
            for (int k = 0; k < 3; ++k) {
                appendRaw(data, p[k]);
                lo[k] = i ? std::min(lo[k], double(p[k])) : double(p[k]);
                hi[k] = i ? std::max(hi[k], double(p[k])) : double(p[k]);
            }
        }
        int position = addAccessor(model, 0, TINYGLTF_TARGET_ARRAY_BUFFER,
                                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
        model.accessors[position].minValues.assign(lo.begin(), lo.end());
        model.accessors[position].maxValues.assign(hi.begin(), hi.end());
        prim.attributes["POSITION"] = position;

        size_t offset = data.size();
        for (const DrawnVertex& d : mesh.vertices)
            for (float c : {d.nx, d.ny, d.nz}) appendRaw(data, c);
        prim.attributes["NORMAL"] = addAccessor(model, offset, TINYGLTF_TARGET_ARRAY_BUFFER,
                                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
        if (mesh.hasTexCoords) {
            offset = data.size();
            for (const DrawnVertex& d : mesh.vertices) {
                appendRaw(data, d.s);
                appendRaw(data, 1.0f - d.t); // glTF: origin at the top left of the image
            }
            prim.attributes["TEXCOORD_0"] =
                addAccessor(model, offset, TINYGLTF_TARGET_ARRAY_BUFFER,
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
        }
        // An application-specific attribute (glTF 2.0 3.7.2.1: names starting with "_"): 1 where
        // the surface is approximate (DrawnVertex::approximate), only when some vertex is.
        if (std::any_of(mesh.vertices.begin(), mesh.vertices.end(),
                        [](const DrawnVertex& d) { return d.approximate != 0; })) {
            offset = data.size();
            for (const DrawnVertex& d : mesh.vertices) appendRaw(data, d.approximate ? 1.0f : 0.0f);
            prim.attributes["_APPROXIMATE"] =
                addAccessor(model, offset, TINYGLTF_TARGET_ARRAY_BUFFER,
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, n);
        }
        offset = data.size();
        for (uint32_t i : mesh.triangles) appendRaw(data, i);
        prim.indices = addAccessor(model, offset, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                   mesh.triangles.size());

        tinygltf::Mesh m;
        m.name = "limn-render";
        m.primitives.push_back(prim);
        model.meshes.push_back(m);
        tinygltf::Node node;
        node.mesh = 0;
        model.nodes.push_back(node);
        model.scenes.emplace_back();
        model.scenes[0].nodes.push_back(0);
        model.defaultScene = 0;
    }
    std::ostringstream stream(std::ios::binary);
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/true, binary))
        throw Error(ErrorKind::BadInput, "could not encode the glTF");
    const std::string bytes = stream.str();
    return {bytes.begin(), bytes.end()};
}

std::vector<uint8_t> encodeMesh(const DrawnMesh& mesh, ExportFormat format, bool plyAscii) {
    // Input within every reader's range can still overflow the GPU's float on the way (huge but
    // finite weights, displacement scales); a NaN in a mesh file is a lie (glTF's min/max would
    // be null), so the file is refused instead.
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const DrawnVertex& v = mesh.vertices[i];
        for (float x : {v.x, v.y, v.z, v.nx, v.ny, v.nz, v.u, v.v, v.s, v.t})
            if (!std::isfinite(x))
                throw Error(ErrorKind::BadInput,
                            "drawn vertex " + std::to_string(i) +
                                " is not finite (NaN or Inf): the input's numbers overflow the GPU's "
                                "float arithmetic; no mesh written");
    }
    switch (format) {
    case ExportFormat::Ply: return encodePly(mesh, plyAscii);
    case ExportFormat::Obj: return encodeObj(mesh);
    case ExportFormat::Gltf: return encodeGltf(mesh, false);
    case ExportFormat::Glb: return encodeGltf(mesh, true);
    }
    throw Error(ErrorKind::BadInput, "internal: unknown mesh format");
}

} // namespace limn::exporting
