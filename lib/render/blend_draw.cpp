#include "render/blend_draw.h"

#include "base/error.h"
#include "gpu/buffer.h"
#include "topology/topology.h"

#include <glm/common.hpp>

#include <string>

namespace limn::render {

namespace {

// Face parameters of the grid points on edge c (c_c -> c_{c+1}, A.1) at step m from c_c.
struct GridIJ {
    uint32_t i, j;
};
GridIJ edgePoint(uint32_t corner, uint32_t m, uint32_t K) {
    switch (corner) {
    case 0:
        return {m, 0}; // c0 (0,0) -> c1 (1,0)
    case 1:
        return {K, m}; // c1 (1,0) -> c2 (1,1)
    case 2:
        return {K - m, K}; // c2 (1,1) -> c3 (0,1)
    default:
        return {0, K - m}; // c3 (0,1) -> c0 (0,0)
    }
}

void requireFits(uint64_t count, uint64_t elementBytes, const char* what, uint32_t grid) {
    if (count > gpu::kMaxStorageBufferBytes / elementBytes)
        throwBadInput("--grid " + std::to_string(grid) +
                      " is too fine for this mesh: " + std::to_string(count) + " " + what +
                      " exceed the 128 MiB buffer limit; use a "
                      "smaller --grid");
}

} // namespace

BlendDraw prepareBlend(const Mesh& mesh, const blend::BlendSurface& s, uint32_t K) {
    if (K < 1 || K > kMaxBlendGrid)
        throw Error(ErrorKind::Usage, "--grid must be 1 to " + std::to_string(kMaxBlendGrid));
    const uint32_t V = static_cast<uint32_t>(mesh.vertexCount());
    const uint32_t F = static_cast<uint32_t>(mesh.faceCount());
    BlendDraw d;
    d.grid = K;
    d.weights = s.weights;

    // The BLND records, as the chunk stores them (f32, component-major coefficients).
    d.vertices.resize(V);
    for (uint32_t v = 0; v < V; ++v) {
        const blend::BlendVertex& bv = s.vertices[v];
        GpuBlendVertex& g = d.vertices[v];
        g.k = bv.chart.k;
        g.kind = static_cast<uint32_t>(bv.chart.kind);
        g.theta = static_cast<float>(bv.chart.theta);
        g.p = static_cast<float>(bv.chart.p);
        g.q = static_cast<float>(bv.chart.q);
        for (int c = 0; c < 3; ++c)
            for (int n = 0; n < 9; ++n) g.coef[9 * c + n] = static_cast<float>(bv.coef[n][c]);
    }
    d.faces.resize(F);
    for (uint32_t f = 0; f < F; ++f)
        for (int i = 0; i < 4; ++i) {
            d.faces[f].vertex[i] = s.faces[f].vertex[i];
            d.faces[f].ring[i] = s.faces[f].ring[i];
        }

    std::vector<uint8_t> hole(F, 0);
    for (uint32_t f : mesh.tags.holes)
        if (f < F) hole[f] = 1;
    for (uint32_t f = 0; f < F; ++f) d.drawnFaces += !hole[f];
    const uint64_t perFace = uint64_t(K + 1) * (K + 1);
    requireFits(d.drawnFaces * perFace, sizeof(GpuBlendDrawVertex), "grid vertices", K);
    requireFits(d.drawnFaces * uint64_t(K) * K * 6, sizeof(uint32_t), "triangle indices", K);

    // Owners: faces in order, each registering the points of its grid that no earlier face has
    // registered, so every shared point belongs to the lowest-numbered drawn face containing it.
    // Edge points are keyed by (edge, step from the edge's first vertex), which both faces of an
    // edge compute alike although they run along it in opposite directions.
    Topology topo(V, mesh.faceOffsets, mesh.faceVertices);
    std::vector<uint32_t> vertexPoint(V, kNone);
    std::vector<uint32_t> edgePoints(size_t(topo.edgeCount()) * (K - 1), kNone);
    std::vector<uint32_t> local(perFace);
    auto newPoint = [&](uint32_t f, uint32_t i, uint32_t j) {
        d.points.push_back({f, i | j << 16});
        return static_cast<uint32_t>(d.points.size() - 1);
    };
    std::vector<uint8_t> edgeDrawn(topo.edgeCount(), 0);
    d.drawVertices.reserve(d.drawnFaces * perFace);
    d.triangles.reserve(d.drawnFaces * size_t(K) * K * 6);
    for (uint32_t f = 0; f < F; ++f) {
        if (hole[f]) continue;
        const uint32_t h0 = topo.faceHalfedge(f);
        auto at = [&](uint32_t i, uint32_t j) -> uint32_t& { return local[j * (K + 1) + i]; };
        // Corners (A.1: c0 (0,0), c1 (1,0), c2 (1,1), c3 (0,1)).
        const GridIJ cornerIJ[4] = {{0, 0}, {K, 0}, {K, K}, {0, K}};
        for (uint32_t c = 0; c < 4; ++c) {
            uint32_t& p = vertexPoint[s.faces[f].vertex[c]];
            if (p == kNone) p = newPoint(f, cornerIJ[c].i, cornerIJ[c].j);
            at(cornerIJ[c].i, cornerIJ[c].j) = p;
        }
        // Edge points, excluding the corners.
        for (uint32_t c = 0; c < 4; ++c) {
            const uint32_t h = h0 + c, e = topo.edge(h);
            const bool forward = topo.vertex(h) == topo.edgeVertices(e)[0];
            for (uint32_t m = 1; m < K; ++m) {
                uint32_t& p = edgePoints[size_t(e) * (K - 1) + (forward ? m : K - m) - 1];
                GridIJ g = edgePoint(c, m, K);
                if (p == kNone) p = newPoint(f, g.i, g.j);
                at(g.i, g.j) = p;
            }
            if (!edgeDrawn[e]) { // --wire: the K segments of this edge, once
                edgeDrawn[e] = 1;
                for (uint32_t m = 0; m < K; ++m) {
                    GridIJ a = edgePoint(c, m, K), b = edgePoint(c, m + 1, K);
                    d.wireLines.push_back(at(a.i, a.j));
                    d.wireLines.push_back(at(b.i, b.j));
                }
            }
        }
        // Interior points belong to the face alone.
        for (uint32_t j = 1; j < K; ++j)
            for (uint32_t i = 1; i < K; ++i) at(i, j) = newPoint(f, i, j);

        const uint32_t base = static_cast<uint32_t>(d.drawVertices.size());
        for (uint32_t p : local) d.drawVertices.push_back({p, d.points[p].face, d.points[p].ij, f});
        for (uint32_t j = 0; j < K; ++j)
            for (uint32_t i = 0; i < K; ++i) {
                const uint32_t a = base + j * (K + 1) + i, b = a + 1, c = b + K + 1, e = a + K + 1;
                for (uint32_t idx : {a, b, c, a, c, e}) d.triangles.push_back(idx);
            }
    }

    d.hasUVs = mesh.hasUVs();
    if (d.hasUVs) {
        d.faceUVs.reserve(size_t(F) * 4);
        for (uint32_t f = 0; f < F; ++f)
            for (uint32_t uv : mesh.faceUVs(f))
                d.faceUVs.emplace_back(static_cast<float>(mesh.uvs[uv].x),
                                       static_cast<float>(mesh.uvs[uv].y));
    } else {
        d.faceUVs.emplace_back(0.0f, 0.0f);
    }
    if (!mesh.positions.empty()) {
        d.bounds = boundsOf(mesh.positions);
    }
    return d;
}

} // namespace limn::render
