// Reads the binary PLY that `limn-render --mesh-out` writes (export/ply.cpp; layout in its
// --help): per vertex float x y z nx ny nz, int ptex, float u v, float s t when the header
// declares them (meshes with UVs), uchar approximate when it declares it; per face a uchar 3 and three int indices. Written here from the documented layout, not with limn's encoder.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace limn::test {

struct PlyVertex {
    float p[3], n[3];
    int32_t ptex;
    float uv[2];
    float st[2] = {0, 0}; // the texture UV, when the PLY has s, t
    uint8_t approximate = 0; // when the PLY has the property
};

struct Drawn {
    std::vector<PlyVertex> vertices;
    std::vector<std::array<int32_t, 3>> triangles;
    bool hasST = false;
    bool hasApproximate = false;
};

inline Drawn parsePly(const std::string& bytes) {
    Drawn d;
    auto end = bytes.find("end_header\n");
    if (end == std::string::npos) throw std::runtime_error("no PLY header");
    std::istringstream header(bytes.substr(0, end));
    size_t vertices = 0, faces = 0;
    for (std::string line; std::getline(header, line);) {
        if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
        if (line.rfind("element face ", 0) == 0) faces = std::stoul(line.substr(13));
        if (line == "property float t") d.hasST = true; // after "property float s"
        if (line == "property uchar approximate") d.hasApproximate = true; // the last one
    }
    const size_t stride = (d.hasST ? 44 : 36) + (d.hasApproximate ? 1 : 0);
    const char* p = bytes.data() + end + 11;
    if (bytes.size() - (end + 11) != vertices * stride + faces * 13)
        throw std::runtime_error("PLY size");
    d.vertices.resize(vertices);
    for (auto& v : d.vertices) {
        std::memcpy(v.p, p, 12);
        std::memcpy(v.n, p + 12, 12);
        std::memcpy(&v.ptex, p + 24, 4);
        std::memcpy(v.uv, p + 28, 8);
        if (d.hasST) std::memcpy(v.st, p + 36, 8);
        if (d.hasApproximate) v.approximate = uint8_t(p[stride - 1]);
        p += stride;
    }
    for (size_t f = 0; f < faces; ++f) {
        if (*p != 3) throw std::runtime_error("PLY face without 3 corners");
        std::array<int32_t, 3> t;
        std::memcpy(t.data(), p + 1, 12);
        d.triangles.push_back(t);
        p += 13;
    }
    return d;
}

// Welds the drawn vertices by exact position (bit-equal floats) and counts how often each welded
// edge is used: a closed watertight surface has every edge in exactly two triangles.
struct WeldedEdges {
    size_t open = 0;      // edges in one triangle: cracks (or the boundary of an open surface)
    size_t over = 0;      // edges in more than two triangles
    size_t collapsed = 0; // triangles that lost an edge when welded
};

inline WeldedEdges weldedEdges(const Drawn& d) {
    std::map<std::array<float, 3>, int> weld;
    std::vector<int> id(d.vertices.size());
    for (size_t i = 0; i < d.vertices.size(); ++i) {
        const float* p = d.vertices[i].p;
        id[i] = weld.try_emplace({p[0], p[1], p[2]}, int(weld.size())).first->second;
    }
    std::map<std::pair<int, int>, int> uses;
    WeldedEdges w;
    for (const auto& tri : d.triangles)
        for (int k = 0; k < 3; ++k) {
            int a = id[tri[k]], b = id[tri[(k + 1) % 3]];
            if (a == b) {
                ++w.collapsed;
                continue;
            }
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    for (const auto& [e, n] : uses) w.open += n == 1, w.over += n > 2;
    return w;
}

} // namespace limn::test
