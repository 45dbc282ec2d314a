// Readers of the meshes limn-render exports (--mesh-out), independent of lib/export: glTF through
// tinygltf's reader, OBJ parsed here (PLY: drawn_ply.h); and the faces of the input models, read
// the same way. They check the file's structure with GoogleTest expectations as they read.
#pragma once

#include "test_support.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <array>
#include <bit>
#include <map>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace limn::test {

// ---- glTF, through tinygltf's reader ----

struct GltfMesh {
    std::vector<std::array<float, 3>> positions, normals;
    std::vector<std::array<float, 2>> uvs; // empty without TEXCOORD_0
    std::vector<uint32_t> indices;
    std::vector<double> min, max; // POSITION's
    std::vector<float> approximate; // _APPROXIMATE, when the file has it
};

template <size_t N>
std::vector<std::array<float, N>> floats(const tinygltf::Model& m, int accessor, int type) {
    const auto& a = m.accessors.at(size_t(accessor));
    EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(a.type, type);
    const auto& view = m.bufferViews.at(size_t(a.bufferView));
    EXPECT_EQ(view.target, TINYGLTF_TARGET_ARRAY_BUFFER);
    const auto& buf = m.buffers.at(size_t(view.buffer)).data;
    const size_t stride = size_t(a.ByteStride(view));
    EXPECT_LE(view.byteOffset + a.byteOffset + stride * (a.count - 1) + N * 4,
              view.byteOffset + view.byteLength);
    EXPECT_LE(view.byteOffset + view.byteLength, buf.size());
    std::vector<std::array<float, N>> out(a.count);
    for (size_t i = 0; i < a.count; ++i)
        std::memcpy(out[i].data(), buf.data() + view.byteOffset + a.byteOffset + i * stride, N * 4);
    return out;
}

inline GltfMesh readGltf(const std::string& bytes, bool binary) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    std::string err, warn;
    bool ok = binary ? loader.LoadBinaryFromMemory(&m, &err, &warn,
                                                   reinterpret_cast<const unsigned char*>(bytes.data()),
                                                   static_cast<unsigned>(bytes.size()))
                     : loader.LoadASCIIFromString(&m, &err, &warn, bytes.data(),
                                                  static_cast<unsigned>(bytes.size()), "");
    EXPECT_TRUE(ok) << err;
    EXPECT_EQ(warn, "");
    GltfMesh g;
    EXPECT_EQ(m.asset.version, "2.0");
    EXPECT_EQ(m.asset.generator, "limn-render");
    if (!ok || m.meshes.size() != 1 || m.meshes[0].primitives.size() != 1) {
        ADD_FAILURE() << "expected one mesh with one primitive";
        return g;
    }
    if (m.buffers.size() == 1 && !binary) {
        EXPECT_EQ(m.buffers[0].uri.rfind("data:application/octet-stream;base64,", 0), 0u);
    }
    const auto& prim = m.meshes[0].primitives[0];
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    g.positions = floats<3>(m, prim.attributes.at("POSITION"), TINYGLTF_TYPE_VEC3);
    g.normals = floats<3>(m, prim.attributes.at("NORMAL"), TINYGLTF_TYPE_VEC3);
    if (prim.attributes.count("TEXCOORD_0"))
        g.uvs = floats<2>(m, prim.attributes.at("TEXCOORD_0"), TINYGLTF_TYPE_VEC2);
    if (prim.attributes.count("_APPROXIMATE"))
        for (const auto& a : floats<1>(m, prim.attributes.at("_APPROXIMATE"), TINYGLTF_TYPE_SCALAR))
            g.approximate.push_back(a[0]);
    const auto& pa = m.accessors[size_t(prim.attributes.at("POSITION"))];
    g.min = pa.minValues;
    g.max = pa.maxValues;
    const auto& ia = m.accessors.at(size_t(prim.indices));
    EXPECT_EQ(ia.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    const auto& iv = m.bufferViews.at(size_t(ia.bufferView));
    EXPECT_EQ(iv.target, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    g.indices.resize(ia.count);
    std::memcpy(g.indices.data(), m.buffers[size_t(iv.buffer)].data.data() + iv.byteOffset + ia.byteOffset,
                ia.count * 4);
    return g;
}

// ---- OBJ, parsed here ----

struct ObjCorner {
    int v, vt, vn; // 0-based; vt -1 when absent
};
struct ObjMesh {
    std::vector<std::array<float, 3>> v, vn;
    std::vector<std::array<float, 2>> vt;
    std::vector<std::array<ObjCorner, 3>> triangles;
    // From the comments "# approximate: N positions ..." and "# approximate v i j ..." (0-based).
    size_t approximateCount = 0;
    std::vector<int> approximateV;
};

inline float parseFloat(const std::string& s) {
    float f = 0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), f);
    EXPECT_TRUE(ec == std::errc() && p == s.data() + s.size()) << s;
    return f;
}

inline ObjMesh parseObj(const std::string& text) {
    ObjMesh o;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::istringstream ls(line);
        std::string tag, a, b, c;
        ls >> tag;
        if (tag == "v" || tag == "vn") {
            ls >> a >> b >> c;
            (tag == "v" ? o.v : o.vn).push_back({parseFloat(a), parseFloat(b), parseFloat(c)});
        } else if (tag == "vt") {
            ls >> a >> b;
            o.vt.push_back({parseFloat(a), parseFloat(b)});
        } else if (tag == "f") {
            std::array<ObjCorner, 3> t;
            for (auto& corner : t) {
                std::string w;
                ls >> w;
                auto s1 = w.find('/'), s2 = w.find('/', s1 + 1);
                corner.v = std::stoi(w.substr(0, s1)) - 1;
                std::string vt = w.substr(s1 + 1, s2 - s1 - 1);
                corner.vt = vt.empty() ? -1 : std::stoi(vt) - 1;
                corner.vn = std::stoi(w.substr(s2 + 1)) - 1;
            }
            std::string extra;
            EXPECT_FALSE(ls >> extra) << "not a triangle: " << line;
            o.triangles.push_back(t);
        } else if (tag == "#" && line.rfind("# approximate: ", 0) == 0) {
            o.approximateCount = std::stoul(line.substr(15));
        } else if (tag == "#" && line.rfind("# approximate v ", 0) == 0) {
            std::string word;
            ls >> word; // "approximate"
            ls >> word; // "v"
            for (int i; ls >> i;) o.approximateV.push_back(i - 1);
        } else {
            EXPECT_TRUE(tag.empty() || tag[0] == '#') << line;
        }
    }
    return o;
}

// The UVs of a quad OBJ: per face its corners' (vertex, uv) from the text.
struct ObjUVs {
    std::vector<std::array<float, 2>> vt;
    std::vector<std::vector<std::pair<int, int>>> faces; // (v, vt), 0-based
    size_t vertices = 0;
};

inline ObjUVs readObjUVs(const std::string& text) {
    ObjUVs o;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::istringstream ls(line);
        std::string tag;
        ls >> tag;
        if (tag == "v") ++o.vertices;
        if (tag == "vt") {
            double u, v;
            ls >> u >> v;
            o.vt.push_back({float(u), float(v)});
        }
        if (tag == "f") {
            std::vector<std::pair<int, int>> f;
            for (std::string w; ls >> w;) {
                auto s1 = w.find('/');
                auto s2 = w.find('/', s1 + 1);
                f.push_back({std::stoi(w.substr(0, s1)) - 1,
                             std::stoi(w.substr(s1 + 1, s2 == std::string::npos ? s2 : s2 - s1 - 1)) - 1});
            }
            o.faces.push_back(f);
        }
    }
    return o;
}

// A model's OBJ faces (vertex ids, 0-based).
inline std::vector<std::vector<int>> objFaces(const std::string& path) {
    std::vector<std::vector<int>> faces;
    for (const auto& f : readObjUVs(readFile(path)).faces) {
        faces.emplace_back();
        for (auto [v, vt] : f) faces.back().push_back(v);
    }
    return faces;
}

// A glTF model's triangles, its split vertices welded by position (as limn-classify does).
inline std::vector<std::vector<int>> gltfFaces(const std::string& path) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int,
                             const unsigned char*, int, void*) { return true; },
                          nullptr);
    tinygltf::Model m;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadASCIIFromFile(&m, &err, &warn, path)) << err;
    std::vector<std::vector<int>> faces;
    for (const auto& mesh : m.meshes)
        for (const auto& prim : mesh.primitives) {
            auto pos = floats<3>(m, prim.attributes.at("POSITION"), TINYGLTF_TYPE_VEC3);
            std::map<std::array<uint32_t, 3>, int> weld;
            std::vector<int> id;
            for (const auto& p : pos)
                id.push_back(weld.try_emplace({std::bit_cast<uint32_t>(p[0]), std::bit_cast<uint32_t>(p[1]),
                                               std::bit_cast<uint32_t>(p[2])},
                                              int(weld.size()))
                                 .first->second);
            const auto& a = m.accessors.at(size_t(prim.indices));
            const auto& v = m.bufferViews.at(size_t(a.bufferView));
            const unsigned char* d = m.buffers.at(size_t(v.buffer)).data.data() + v.byteOffset + a.byteOffset;
            for (size_t t = 0; t + 2 < a.count; t += 3) {
                faces.emplace_back();
                for (size_t k = 0; k < 3; ++k) {
                    uint32_t i = 0;
                    if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
                        uint16_t s16;
                        std::memcpy(&s16, d + 2 * (t + k), 2);
                        i = s16;
                    } else {
                        EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
                        std::memcpy(&i, d + 4 * (t + k), 4);
                    }
                    faces.back().push_back(id.at(i));
                }
            }
        }
    return faces;
}

} // namespace limn::test
