#include "render/subdivision_draw.h"

#include "tess/tessellation.h"
#include "topology/ptex.h"
#include "topology/topology.h"

#include <glm/common.hpp>

#include <algorithm>
#include <set>

namespace limn::render {

namespace {

// Appends a table's rows to concatenated arrays; returns the row where they start.
uint32_t appendRows(const StencilTable& t, std::vector<uint32_t>& starts, std::vector<uint32_t>& indices,
                    std::vector<float>* weights) {
    const uint32_t firstRow = static_cast<uint32_t>(starts.size());
    const uint32_t base = static_cast<uint32_t>(indices.size());
    for (uint32_t s : t.start) starts.push_back(base + s);
    indices.insert(indices.end(), t.indices.begin(), t.indices.end());
    if (weights) weights->insert(weights->end(), t.weights.begin(), t.weights.end());
    return firstRow;
}

} // namespace

SubdivisionDraw prepareSubdivision(const Mesh& mesh, const Tables& t, uint32_t tessCap) {
    SubdivisionDraw d;
    d.baseVertices = t.levels[0].count();
    d.totalVertices = t.totalVertices;
    for (uint32_t l = 1; l <= t.depth; ++l) {
        const LevelInfo& L = t.levels[l];
        LevelPasses p{};
        p.level = l;
        p.faceFirstOut = L.first;
        p.faceCount = L.facePoints;
        p.faceFirstRow = appendRows(t.facePoints[l - 1], d.faceStarts, d.faceIndices, nullptr);
        p.edgeFirstOut = L.first + L.facePoints;
        p.edgeCount = L.edgePoints;
        p.edgeFirstRow = appendRows(t.edgePoints[l - 1], d.stencilStarts, d.stencilIndices, &d.stencilWeights);
        p.vertexFirstOut = L.first + L.facePoints + L.edgePoints;
        p.vertexCount = L.vertexPoints;
        p.vertexFirstRow = appendRows(t.vertexPoints[l - 1], d.stencilStarts, d.stencilIndices, &d.stencilWeights);
        d.levels.push_back(p);
    }
    d.limitCount = static_cast<uint32_t>(t.limitPosition.rows());
    for (const StencilTable* table : {&t.limitPosition, &t.limitTangent1, &t.limitTangent2})
        appendRows(*table, d.limitStarts, d.limitIndices, &d.limitWeights);

    for (const Patch& p : t.patches) {
        GpuPatch g{};
        std::copy(std::begin(p.cv), std::end(p.cv), g.cv);
        g.ptex = p.ptex;
        g.u0 = p.u0, g.v0 = p.v0, g.size = p.size;
        g.levelBoundary = uint32_t(p.level) | uint32_t(p.boundary) << 8;
        d.patches.push_back(g);
    }
    for (const IrregularFace& q : t.irregular) {
        GpuIrregularFace g{};
        std::copy(std::begin(q.corner), std::end(q.corner), g.corner);
        g.ptex = q.ptex;
        g.u0 = q.u0, g.v0 = q.v0, g.size = q.size;
        d.irregular.push_back(g);
    }

    Tessellation tess = buildTessellation(mesh, t, tessCap);
    d.stitchedEdges = tess.stitchedEdges;
    d.hasUVs = mesh.hasUVs();
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    PtexMap ptex(mesh, topo, 1u << t.depth);
    d.tessVertices.reserve(tess.vertices.size());
    for (const TessVertex& v : tess.vertices) {
        GpuTessVertex g{v.element, uint32_t(v.s) | uint32_t(v.t) << 16, 0, 0};
        if (d.hasUVs) {
            PtexPoint pp = ptexOf(t, v);
            glm::dvec2 uv = ptex.ownUV(pp.ptex, pp.u, pp.v);
            g.u = static_cast<float>(uv.x);
            g.v = static_cast<float>(uv.y);
        }
        d.tessVertices.push_back(g);
    }
    d.triangles = std::move(tess.indices);
    // Per triangle: the level of the element that made it (triangles are emitted element by
    // element, in element order).
    const uint32_t P = static_cast<uint32_t>(t.patches.size());
    d.triangleLevels.reserve(d.triangles.size() / 3);
    for (uint32_t e = 0; e < tess.triangleCounts.size(); ++e)
        d.triangleLevels.insert(d.triangleLevels.end(), tess.triangleCounts[e],
                                e < P ? t.patches[e].level : 255u);
    // Element outlines for --wire, each segment once.
    std::set<std::pair<uint32_t, uint32_t>> seen;
    for (size_t i = 0; i + 1 < tess.outline.size(); i += 2) {
        uint32_t a = tess.outline[i], b = tess.outline[i + 1];
        if (seen.insert({std::min(a, b), std::max(a, b)}).second) {
            d.wireLines.push_back(a);
            d.wireLines.push_back(b);
        }
    }
    glm::dvec3 lo(mesh.positions[0]), hi(mesh.positions[0]);
    for (const auto& q : mesh.positions) lo = glm::min(lo, q), hi = glm::max(hi, q);
    d.bounds = {lo, hi};
    return d;
}

} // namespace limn::render
