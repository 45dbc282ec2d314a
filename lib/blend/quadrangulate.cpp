#include "blend/quadrangulate.h"

#include <algorithm>
#include <map>
#include <unordered_map>

namespace limn::blend {

bool isQuadMesh(const Mesh& mesh) {
    for (size_t f = 0; f < mesh.faceCount(); ++f)
        if (mesh.faceSize(f) != 4) return false;
    return true;
}

Mesh quadrangulateLinear(const Mesh& mesh, const Topology& topo) {
    const uint32_t V = topo.vertexCount(), E = topo.edgeCount(), F = topo.faceCount();
    Mesh out;
    out.tags = mesh.tags;
    out.positions = mesh.positions;
    out.positions.reserve(size_t(V) + E + F);
    for (uint32_t e = 0; e < E; ++e) {
        auto [a, b] = topo.edgeVertices(e);
        out.positions.push_back((mesh.positions[a] + mesh.positions[b]) * 0.5);
    }
    for (uint32_t f = 0; f < F; ++f) {
        glm::dvec3 sum(0.0);
        for (uint32_t v : mesh.face(f)) sum += mesh.positions[v];
        out.positions.push_back(sum / double(mesh.faceSize(f)));
    }
    auto edgePoint = [&](uint32_t h) { return V + topo.edge(h); };

    const bool uv = mesh.hasUVs();
    if (uv) out.uvs = mesh.uvs;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> uvMid; // UV pair -> midpoint UV
    auto uvMidpoint = [&](uint32_t a, uint32_t b) {
        auto key = std::minmax(a, b);
        auto [it, inserted] = uvMid.try_emplace({key.first, key.second},
                                                static_cast<uint32_t>(out.uvs.size()));
        if (inserted) out.uvs.push_back((mesh.uvs[a] + mesh.uvs[b]) * 0.5);
        return it->second;
    };

    for (uint32_t f = 0; f < F; ++f) {
        const uint32_t first = topo.faceHalfedge(f), n = topo.faceSize(f);
        uint32_t centreUV = 0;
        if (uv) {
            glm::dvec2 sum(0.0);
            for (uint32_t h = first; h < first + n; ++h) sum += mesh.uvs[mesh.uvIndices[h]];
            centreUV = static_cast<uint32_t>(out.uvs.size());
            out.uvs.push_back(sum / double(n));
        }
        for (uint32_t h = first; h < first + n; ++h) {
            uint32_t p = topo.prev(h);
            uint32_t quad[4] = {topo.vertex(h), edgePoint(h), V + E + f, edgePoint(p)};
            out.addFace(quad);
            if (uv) {
                const auto& ix = mesh.uvIndices;
                uint32_t uvs[4] = {ix[h], uvMidpoint(ix[h], ix[topo.next(h)]), centreUV,
                                   uvMidpoint(ix[p], ix[h])};
                out.uvIndices.insert(out.uvIndices.end(), uvs, uvs + 4);
            }
        }
    }

    // Tags follow the split: creases onto both halves, holes onto every child.
    if (!mesh.tags.creases.empty()) {
        std::unordered_map<uint64_t, uint32_t> edgeOf;
        for (uint32_t e = 0; e < E; ++e) {
            auto [a, b] = topo.edgeVertices(e);
            edgeOf[(uint64_t(std::min(a, b)) << 32) | std::max(a, b)] = e;
        }
        out.tags.creases.clear();
        for (const auto& c : mesh.tags.creases) {
            auto it = edgeOf.find((uint64_t(std::min(c.v0, c.v1)) << 32) | std::max(c.v0, c.v1));
            if (it == edgeOf.end()) continue; // names no edge: dropped (limn-classify warned)
            out.tags.creases.push_back({c.v0, V + it->second, c.sharpness});
            out.tags.creases.push_back({V + it->second, c.v1, c.sharpness});
        }
    }
    out.tags.holes.clear();
    for (uint32_t f : mesh.tags.holes)
        for (uint32_t h = topo.faceHalfedge(f); h < topo.faceHalfedge(f) + topo.faceSize(f); ++h)
            out.tags.holes.push_back(h);
    return out;
}

} // namespace limn::blend
