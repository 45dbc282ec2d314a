#include "subdiv/tables.h"

#include "container/container.h"
#include "subdiv/tables_build.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

namespace limn {

uint64_t topologyHash(const Mesh& mesh, const SchemeOptions& options) {
    auto bytesOf = [](const auto& v) {
        return std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(v.data()),
                                        v.size() * sizeof(v[0]));
    };
    uint64_t h = hashBytes(bytesOf(mesh.faceOffsets));
    h = hashBytes(bytesOf(mesh.faceVertices), h);
    uint8_t opts[4] = {uint8_t(options.boundary), uint8_t(options.creaseMethod),
                       uint8_t(options.triangles), uint8_t(options.fvar)};
    h = hashBytes(opts, h);
    for (const auto& c : mesh.tags.creases) {
        uint32_t w[3] = {c.v0, c.v1, 0};
        std::memcpy(&w[2], &c.sharpness, 4);
        h = hashBytes({reinterpret_cast<const uint8_t*>(w), 12}, h);
    }
    for (const auto& c : mesh.tags.corners) {
        uint32_t w[2] = {c.vertex, 0};
        std::memcpy(&w[1], &c.sharpness, 4);
        h = hashBytes({reinterpret_cast<const uint8_t*>(w), 8}, h);
    }
    h = hashBytes(bytesOf(mesh.tags.holes), h);
    uint32_t vcount = static_cast<uint32_t>(mesh.vertexCount());
    return hashBytes({reinterpret_cast<const uint8_t*>(&vcount), 4}, h);
}

IrregularSurfaceCounts irregularSurfaceCounts(const Tables& t) {
    IrregularSurfaceCounts c;
    uint32_t most = kMaxDepth + 1;
    for (size_t i = 0; i < t.irregular.size(); ++i) {
        const uint32_t code = i < t.irregularNodes.size() ? t.irregularNodes[i][0] : kNodeNone;
        if (code == kNodeNone) {
            ++c.bilinear;
        } else if ((code & ~kNodeIndexMask) == kNodeBasis) {
            ++c.basis;
            const auto& f = t.smoothIrregular[code & kNodeIndexMask];
            most = std::min(most, t.irregularBases[f.basis].levels);
            c.boundaryBasis += t.irregularBases[f.basis].configuration.boundary;
            c.creaseChain += !t.irregularBases[f.basis].kinds.empty();
        } else {
            ++c.subPatches;
            most = std::min(most, t.irregularLevels);
        }
    }
    for (size_t i = 0; i < t.irregularNodes.size(); ++i)
        if (!(i < t.irregular.size() && smoothRoot(t.irregularNodes[i])))
            for (uint32_t code : t.irregularNodes[i])
                c.basisBelow += code != kNodeNone && (code & ~kNodeIndexMask) == kNodeBasis;
    c.exactLevels = most > uint32_t(kMaxDepth) ? 0 : most;
    return c;
}

uint64_t uniformTableVertices(const Mesh& mesh, int depth) {
    const uint64_t corners = mesh.cornerCount();
    // Edges: each interior edge is shared by two corners; count the distinct ones exactly.
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    edges.reserve(corners);
    for (size_t f = 0; f < mesh.faceCount(); ++f) {
        auto face = mesh.face(f);
        for (size_t k = 0; k < face.size(); ++k) {
            uint32_t a = face[k], b = face[(k + 1) % face.size()];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    double E = double(std::unique(edges.begin(), edges.end()) - edges.begin());
    double V = double(mesh.vertexCount()), F = double(mesh.faceCount()), total = V;
    for (int l = 1; l <= depth; ++l) {
        const double faceCorners = l == 1 ? double(corners) : 4 * F;
        const double nextV = V + E + F, nextE = 2 * E + faceCorners, nextF = faceCorners;
        V = nextV, E = nextE, F = nextF;
        total += V;
        if (total > 1e18) return uint64_t(1e18);
    }
    return static_cast<uint64_t>(total);
}

Tables buildTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                   Warnings& warnings) {
    // The phases are in tables_build.h.
    checkTablesOptions(mesh, opts);
    Topology baseTopo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    checkTablesTopology(baseTopo, opts);
    return assembleTables(mesh, options, opts,
                          refineAdaptive(mesh, std::move(baseTopo), options, opts, warnings));
}

} // namespace limn
