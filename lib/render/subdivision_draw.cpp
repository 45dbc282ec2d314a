#include "render/subdivision_draw.h"

#include "base/error.h"
#include "subdiv/fvar_surface.h"
#include "tess/chart_uvs.h"
#include "tess/tessellation.h"
#include "topology/ptex.h"
#include "topology/topology.h"

#include <glm/common.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <cstdio>
#include <cstring>
#include <set>
#include <stdexcept>

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

namespace {

// The UVs a vertex samples the displacement at, from its element's seam record (paper 000,
// Figures 8 and 9): a corner takes every face around it, an edge point both sides' UVs
// interpolated along the edge, an interior point its own face's, in the order the seams list
// them (increasing face), so copies of a point compute the same average.
void sideUVsOf(const ElementSeams& es, const Seams& seams, const TessVertex& tv, std::vector<glm::vec2>& out) {
    out.clear();
    const bool s0 = tv.s == 0, s1 = tv.s == kTessParamOne, t0 = tv.t == 0, t1 = tv.t == kTessParamOne;
    const double s = double(tv.s) / kTessParamOne, t = double(tv.t) / kTessParamOne;
    if ((s0 || s1) && (t0 || t1)) {
        int k = s0 ? (t0 ? 0 : 3) : (t0 ? 1 : 2);
        for (uint32_t i = 0; i < es.cornerCount[k]; ++i) out.push_back(seams.uvs[es.cornerFirst[k] + i]);
        return;
    }
    int edge = -1;
    double x = 0;
    if (t0) edge = 0, x = s;
    else if (s1) edge = 1, x = t;
    else if (t1) edge = 2, x = 1 - s;
    else if (s0) edge = 3, x = 1 - t;
    if (edge >= 0) {
        for (uint32_t i = 0; i < es.edgeSides[edge]; ++i) {
            glm::dvec2 a(seams.uvs[es.edgeFirst[edge] + 2 * i]), b(seams.uvs[es.edgeFirst[edge] + 2 * i + 1]);
            out.push_back(glm::vec2(a + x * (b - a)));
        }
        return;
    }
    const glm::dvec2 c[4] = {glm::dvec2(es.own[0]), glm::dvec2(es.own[1]), glm::dvec2(es.own[2]), glm::dvec2(es.own[3])};
    out.push_back(glm::vec2((1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3]));
}

} // namespace

namespace {

// The seam records of seams.h (same layout and order: corners' distinct UVs and edges' distinct
// end-UV pairs per face, in increasing face order) with the smooth UVs of `charts`; `own` the
// corners in the element's own chart. Without `full`, only `own`.
Seams smoothSeamRecords(const Tables& t, ChartUVs& charts, bool full) {
    Seams s;
    const uint32_t R = 1u << t.depth;
    std::vector<glm::vec2> list;
    std::vector<std::pair<glm::vec2, glm::vec2>> pairs;
    auto add = [&](uint32_t ptex, float u0, float v0, float size) {
        ElementSeams es{};
        const uint32_t U0 = uint32_t(double(u0) * R), V0 = uint32_t(double(v0) * R), W = uint32_t(double(size) * R);
        const uint32_t cu[4] = {U0, U0 + W, U0 + W, U0}, cv[4] = {V0, V0, V0 + W, V0 + W};
        for (int k = 0; k < 4; ++k) {
            es.own[k] = charts.own(ptex, cu[k], cv[k], U0 + 0.5 * W, V0 + 0.5 * W);
            if (!full) continue;
            charts.sides(ptex, cu[k], cv[k], list);
            es.cornerFirst[k] = static_cast<uint32_t>(s.uvs.size());
            es.cornerCount[k] = static_cast<uint32_t>(list.size());
            s.uvs.insert(s.uvs.end(), list.begin(), list.end());
        }
        for (int k = 0; full && k < 4; ++k) {
            charts.edgeSides(ptex, cu[k], cv[k], cu[(k + 1) % 4], cv[(k + 1) % 4], pairs);
            es.edgeFirst[k] = static_cast<uint32_t>(s.uvs.size());
            es.edgeSides[k] = static_cast<uint32_t>(pairs.size());
            for (const auto& [a, b] : pairs) s.uvs.push_back(a), s.uvs.push_back(b);
        }
        s.elements.push_back(es);
    };
    for (const Patch& p : t.patches) add(p.ptex, p.u0, p.v0, p.size);
    for (const IrregularFace& q : t.irregular) add(q.ptex, q.u0, q.v0, q.size);
    return s;
}

// Refuses, before any work, a fixed tessellation whose buffers would not fit 128 MiB: the
// segments per side of each element as buildTessellation will choose them.
void checkFixedSize(const Tables& t, uint32_t tessCap) {
    const uint32_t N = t.depth, cap = std::bit_floor(std::max(tessCap, 1u));
    uint64_t triangles = 0, points = 0;
    auto add = [&](float size, uint32_t level) {
        const uint64_t W = uint64_t(double(size) * (1u << N));
        const uint64_t S = std::min<uint64_t>(std::min<uint64_t>(1ull << (N - level), cap), std::max<uint64_t>(W, 1));
        triangles += 2 * S * S;
        points += S * S;
    };
    for (const Patch& p : t.patches) add(p.size, p.level);
    for (const IrregularFace& q : t.irregular) add(q.size, N);
    const uint64_t limit = uint64_t(128) << 20;
    const uint64_t indexBytes = triangles * 12, vertexBytes = points * 16;
    if (indexBytes <= limit && vertexBytes <= limit) return;
    char msg[512];
    std::snprintf(msg, sizeof msg,
                  "the fixed tessellation (--edge-pixels 0) would draw about %llu triangles: GPU buffer "
                  "'%s' would need about %.1f MiB, over WebGPU's 128 MiB storage-buffer limit; use the "
                  "view-adaptive tessellation (--edge-pixels P > 0, the default), a lower --tess, or "
                  "tables of lower depth (limn-tables --depth)",
                  static_cast<unsigned long long>(triangles),
                  indexBytes > limit ? "triangle indices" : "tessellation vertices",
                  double(std::max(indexBytes, vertexBytes)) / (1 << 20));
    throw Error(ErrorKind::BadInput, msg);
}

// Refuses, before anything is built, tables whose own GPU buffers (vertices of every level,
// the concatenated stencil and limit tables) would pass 128 MiB, whatever the tessellation.
void checkTableSize(const Tables& t) {
    const uint64_t limit = uint64_t(128) << 20;
    struct Sized {
        const char* name;
        uint64_t bytes;
    };
    uint64_t face = 0, stencil = 0;
    for (const auto& s : t.facePoints) face += s.indices.size();
    for (const auto* v : {&t.edgePoints, &t.vertexPoints})
        for (const auto& s : *v) stencil += s.indices.size();
    const Sized sized[] = {{"table vertices", uint64_t(t.totalVertices) * 16},
                           {"face-point indices", face * 4},
                           {"stencil indices", stencil * 4},
                           {"limit points", uint64_t(t.limitPosition.rows()) * 32},
                           {"patches", (uint64_t(t.patches.size()) + t.irregular.size() + t.irregularNodes.size() +
                                        t.subPatches.size()) * 96}};
    for (const Sized& z : sized)
        if (z.bytes > limit) {
            char msg[400];
            std::snprintf(msg, sizeof msg,
                          "GPU buffer '%s' would need %.1f MiB, over WebGPU's 128 MiB storage-buffer "
                          "limit, whatever the tessellation; use feature-adaptive tables (limn-tables "
                          "without --uniform) or a lower --depth",
                          z.name, double(z.bytes) / (1 << 20));
            throw Error(ErrorKind::BadInput, msg);
        }
}

} // namespace

std::vector<LimitChunk> limitChunks(const SubdivisionDraw& d, uint64_t maxBytes) {
    const uint32_t rows = d.limitCount, stride = rows + 1;
    const uint64_t budget = std::max<uint64_t>(maxBytes / 4, 1);
    auto rowEntries = [&](uint32_t r) {
        uint64_t n = 0;
        for (uint32_t k = 0; k < 3; ++k) n += d.limitStarts[k * stride + r + 1] - d.limitStarts[k * stride + r];
        return n;
    };
    std::vector<LimitChunk> out;
    for (uint32_t r0 = 0; r0 < rows;) {
        uint32_t r1 = r0;
        uint64_t entries = 0;
        while (r1 < rows && (r1 == r0 || entries + rowEntries(r1) <= budget)) entries += rowEntries(r1++);
        LimitChunk c;
        c.firstRow = r0, c.rows = r1 - r0;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t b = d.limitStarts[k * stride + r0], e = d.limitStarts[k * stride + r1];
            const uint32_t base = static_cast<uint32_t>(c.indices.size());
            for (uint32_t r = r0; r <= r1; ++r) c.starts.push_back(base + d.limitStarts[k * stride + r] - b);
            c.indices.insert(c.indices.end(), d.limitIndices.begin() + b, d.limitIndices.begin() + e);
            c.weights.insert(c.weights.end(), d.limitWeights.begin() + b, d.limitWeights.begin() + e);
        }
        out.push_back(std::move(c));
        r0 = r1;
    }
    return out;
}

// The quadtree codes of tables.h made absolute indices into the GPU buffers (surface_eval.glsl):
// nodes and sub-patches into the patches buffer, leaves into the irregular faces'. Every
// irregular face gets a root node, with no children where the tables have no quadtree.
namespace {
// A patch as surface_eval.glsl reads it: a regular patch, or an irregular face's sub-patch.
GpuPatch gpuPatch(const Patch& p) {
    GpuPatch g{};
    std::copy(std::begin(p.cv), std::end(p.cv), g.cv);
    g.ptex = p.ptex;
    g.u0 = p.u0, g.v0 = p.v0, g.size = p.size;
    g.levelBoundary = uint32_t(p.level) | uint32_t(p.boundary) << 8 | uint32_t(p.crease) << 16;
    g.sharpness = p.sharpness;
    return g;
}

void packIrregularQuadtrees(const Tables& t, SubdivisionDraw& d) {
    const uint32_t P = static_cast<uint32_t>(t.patches.size()), I = static_cast<uint32_t>(t.irregular.size());
    const uint32_t nodes = std::max<uint32_t>(I, static_cast<uint32_t>(t.irregularNodes.size()));
    // After the sub-patches: per smooth face a header (its support size M: 2n + 8 for a
    // per-valence basis, a boundary configuration's own; corner, its basis's first record, its
    // bands, the corner's limit point, the levels below its irregular face: 0 for a root, whose
    // codes are read before halving) and its support points, 16 a record; then
    // per basis, per band and quadrant, per support point a record of its 16 weights (the first
    // one of a decaying-crease chain's block also its band's crease bits and sharpness).
    std::vector<uint32_t> header(t.smoothIrregular.size()), basisFirst(t.irregularBases.size());
    uint32_t next = P + nodes + static_cast<uint32_t>(t.subPatches.size());
    for (size_t i = 0; i < t.smoothIrregular.size(); ++i) {
        header[i] = next;
        next += 1 + (t.irregularBases[t.smoothIrregular[i].basis].supportSize() + 15) / 16;
    }
    for (size_t b = 0; b < t.irregularBases.size(); ++b) {
        if (!t.irregularBases[b].hasWeights())
            throw std::logic_error("tables built without their bases' weights (TablesOptions::basisWeights) drawn");
        basisFirst[b] = next;
        next += t.irregularBases[b].levels * 3 * t.irregularBases[b].supportSize();
    }
    // Per node its irregular face and depth (children come after their parents); per smooth
    // face the irregular face whose corner it shares, and its levels below that face.
    std::vector<uint32_t> faceOf(t.smoothIrregular.size(), 0), below(t.smoothIrregular.size(), 0);
    std::vector<uint32_t> rootOf(t.irregularNodes.size(), 0), depthOf(t.irregularNodes.size(), 0);
    for (uint32_t i = 0; i < nodes; ++i) {
        GpuPatch g{};
        std::fill(std::begin(g.cv), std::end(g.cv), kNodeNone);
        if (i < t.irregularNodes.size()) {
            if (i < I) rootOf[i] = i;
            const bool root = i < I && smoothRoot(t.irregularNodes[i]);
            for (int q = 0; q < 4; ++q) {
                const uint32_t c = t.irregularNodes[i][q], kind = c & ~kNodeIndexMask, x = c & kNodeIndexMask;
                if (c != kNodeNone && kind == kNodeChild) rootOf[x] = rootOf[i], depthOf[x] = depthOf[i] + 1;
                if (c != kNodeNone && kind == kNodeBasis) faceOf[x] = rootOf[i], below[x] = root ? 0 : depthOf[i] + 1;
                g.cv[q] = c == kNodeNone       ? kNodeNone
                          : kind == kNodeBasis ? kNodeBasis | header[x]
                          : kind == kNodeChild ? kNodeChild | (P + x)
                          : kind == kNodeLeaf  ? kNodeLeaf | (I + x)
                                               : kNodeSubPatch | (P + nodes + x);
            }
        }
        d.irregularNodes.push_back(g);
    }
    for (const Patch& p : t.subPatches) d.irregularNodes.push_back(gpuPatch(p));
    for (size_t i = 0; i < t.smoothIrregular.size(); ++i) {
        const Tables::SmoothIrregular& f = t.smoothIrregular[i];
        const IrregularBasis& b = t.irregularBases[f.basis];
        GpuPatch h{};
        h.cv[0] = b.supportSize(), h.cv[1] = f.corner, h.cv[2] = basisFirst[f.basis];
        h.cv[3] = b.levels > below[i] ? b.levels - below[i] : 1;
        h.cv[4] = t.irregular[faceOf[i]].corner[f.corner];
        h.cv[5] = below[i];
        d.irregularNodes.push_back(h);
        for (uint32_t k = 0; k < b.supportSize(); k += 16) {
            GpuPatch g{};
            for (uint32_t j = 0; j < 16 && k + j < b.supportSize(); ++j) g.cv[j] = t.smoothPoints[f.first + k + j];
            d.irregularNodes.push_back(g);
        }
    }
    for (const IrregularBasis& b : t.irregularBases) {
        const uint32_t M = b.supportSize();
        for (uint32_t block = 0; block < b.levels * 3; ++block)
            for (uint32_t i = 0; i < M; ++i) {
                GpuPatch g{};
                // A chain's band kind (basisPatchPoint reads it from the block's first record).
                if (i == 0 && !b.kinds.empty()) {
                    g.levelBoundary = uint32_t(b.kinds[block].crease) << 16;
                    g.sharpness = b.kinds[block].sharpness;
                }
                for (uint32_t j = 0; j < 16; ++j) std::memcpy(&g.cv[j], &b.weights[(size_t(block) * 16 + j) * M + i], 4);
                d.irregularNodes.push_back(g);
            }
    }
}
} // namespace

std::vector<GpuPatch> SubdivisionDraw::patchBuffer() const {
    std::vector<GpuPatch> out = patches;
    out.insert(out.end(), irregularNodes.begin(), irregularNodes.end());
    return out;
}

std::vector<GpuIrregularFace> SubdivisionDraw::irregularBuffer() const {
    std::vector<GpuIrregularFace> out = irregular;
    out.insert(out.end(), irregularLeaves.begin(), irregularLeaves.end());
    return out;
}

SubdivisionDraw prepareSubdivision(const Mesh& mesh, const Tables& t, uint32_t tessCap,
                                   const DisplacementPlan* displacement, bool adaptive) {
    checkTableSize(t);
    if (!adaptive) checkFixedSize(t, tessCap);
    SubdivisionDraw d;
    d.baseVertices = t.levels[0].count();
    d.totalVertices = t.totalVertices;
    for (uint32_t l = 1; l < t.levels.size(); ++l) { // with the irregular faces' extra levels
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

    for (const Patch& p : t.patches) d.patches.push_back(gpuPatch(p));
    auto irregularFace = [](const IrregularFace& q) {
        GpuIrregularFace g{};
        std::copy(std::begin(q.corner), std::end(q.corner), g.corner);
        g.ptex = q.ptex;
        g.u0 = q.u0, g.v0 = q.v0, g.size = q.size;
        return g;
    };
    for (const IrregularFace& q : t.irregular) d.irregular.push_back(irregularFace(q));
    packIrregularQuadtrees(t, d);
    for (const IrregularFace& q : t.irregularLeaves) d.irregularLeaves.push_back(irregularFace(q));

    d.hasUVs = mesh.hasUVs();
    d.bounds = boundsOf(mesh.positions); // the limit surface lies in the control points' hull
    if (adaptive) {
        if (displacement) {
            if (!d.hasUVs) throw Error(ErrorKind::BadInput, "displacement needs texture coordinates; the mesh has none");
            d.seams = displacement->seams;
            d.seamFix = displacement->seamFix;
        }
        d.adaptive = true;
        d.pieces = buildEdgePieces(mesh, t);
        if (d.hasUVs && t.options.fvar != FVarRule::All) {
            // Smooth UVs: the face-varying surface for the emit pass, per element its
            // ptex domain, its corners' smooth UVs (the displaced normals' bilinear estimate) and,
            // with displacement, the seam records of the smooth UVs.
            Warnings ignored; // the geometry's tables already reported the mesh's warnings
            const FaceVaryingSurface surface(mesh, t.options, t.depth, t.irregularLevels, ignored);
            FaceVaryingSurface::Gpu g = surface.gpu();
            d.fvarNodes = std::move(g.nodes);
            d.fvarRecords = std::move(g.records);
            d.fvarCell = std::ldexp(1.0f, -21); // 1/32 of the finest cell at depth 16, above float's step at 1
            auto domain = [](uint32_t ptex, float u0, float v0, float size) {
                float bits;
                std::memcpy(&bits, &ptex, 4);
                return glm::vec4(bits, u0, v0, size);
            };
            for (const Patch& p : t.patches) d.elementDomains.push_back(domain(p.ptex, p.u0, p.v0, p.size));
            for (const IrregularFace& q : t.irregular) d.elementDomains.push_back(domain(q.ptex, q.u0, q.v0, q.size));
            ChartUVs charts(mesh, surface, 1u << t.depth);
            d.smoothSeams = smoothSeamRecords(t, charts, displacement != nullptr);
            for (size_t e = 0; e < d.pieces.elements.size(); ++e)
                for (int k = 0; k < 4; ++k) d.pieces.elements[e].cornerUV[k] = d.smoothSeams.elements[e].own[k];
            if (!displacement) d.smoothSeams = Seams{};
        }
        d.closed = !d.pieces.pieces.empty();
        for (const EdgePiece& p : d.pieces.pieces) d.closed = d.closed && p.users[1] != kNoElement;
        d.orientation = surfaceOrientation(mesh, mesh.positions);
        return d;
    }
    // Smooth face-varying UVs for every rule but "all", whose linear charts stay
    // exactly as before.
    std::unique_ptr<FaceVaryingSurface> fvar;
    std::unique_ptr<ChartUVs> chartUVs;
    if (d.hasUVs && t.options.fvar != FVarRule::All) {
        Warnings ignored; // the tables of the geometry already reported the mesh's warnings
        fvar = std::make_unique<FaceVaryingSurface>(mesh, t.options, t.depth, t.irregularLevels, ignored);
        chartUVs = std::make_unique<ChartUVs>(mesh, *fvar, 1u << t.depth);
    }
    Tessellation tess = buildTessellation(mesh, t, tessCap, d.hasUVs, chartUVs.get());
    d.stitchedEdges = tess.stitchedEdges;
    d.tessVertices.reserve(tess.vertices.size());
    for (size_t i = 0; i < tess.vertices.size(); ++i) {
        const TessVertex& v = tess.vertices[i];
        GpuTessVertex g{v.element, uint32_t(v.s) | uint32_t(v.t) << 16, 0, 0};
        if (d.hasUVs) g.u = tess.uvs[i].x, g.v = tess.uvs[i].y;
        d.tessVertices.push_back(g);
    }
    if (displacement) {
        if (!d.hasUVs) throw Error(ErrorKind::BadInput, "displacement needs texture coordinates; the mesh has none");
        std::vector<glm::vec2> sides;
        for (size_t i = 0; i < tess.vertices.size(); ++i) {
            if (displacement->seamFix && chartUVs) {
                // The point's smooth UV in every face around it, in increasing face order.
                const PtexPoint p = ptexOf(t, tess.vertices[i]);
                const double R = double(1u << t.depth), U = p.u * R, V = p.v * R;
                if (U == std::floor(U) && V == std::floor(V))
                    chartUVs->sides(p.ptex, uint32_t(U), uint32_t(V), sides);
                else
                    sides.assign(1, tess.uvs[i]); // an element's centre: inside one face
            } else if (displacement->seamFix) {
                const TessVertex& v = tess.vertices[i];
                sideUVsOf(displacement->seams->elements[v.element], *displacement->seams, v, sides);
            } else {
                sides.assign(1, tess.uvs[i]);
            }
            d.sideRanges.push_back({uint32_t(d.sideUVs.size()), uint32_t(sides.size())});
            d.sideUVs.insert(d.sideUVs.end(), sides.begin(), sides.end());
        }
        // Triangles around each point (all copies of a seam point together), in index order.
        std::vector<uint32_t> count(tess.vertices.size() + 1, 0);
        for (uint32_t idx : tess.indices) ++count[tess.geometry[idx] + 1];
        for (size_t i = 0; i < tess.vertices.size(); ++i) count[i + 1] += count[i];
        d.incidentTriangles.resize(tess.indices.size());
        std::vector<uint32_t> fill(count.begin(), count.end() - 1);
        for (size_t k = 0; k < tess.indices.size(); ++k)
            d.incidentTriangles[fill[tess.geometry[tess.indices[k]]]++] = static_cast<uint32_t>(k / 3);
        for (size_t i = 0; i < tess.vertices.size(); ++i) {
            uint32_t g = tess.geometry[i];
            d.incidentRanges.push_back({count[g], count[g + 1] - count[g]});
        }
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
    return d;
}

float surfaceOrientation(const Mesh& mesh, const std::vector<glm::dvec3>& positions) {
    if (positions.empty()) return 0;
    glm::dvec3 lo(positions[0]), hi(positions[0]);
    for (const auto& q : positions) lo = glm::min(lo, q), hi = glm::max(hi, q);
    const glm::dvec3 c = 0.5 * (lo + hi);
    double volume = 0, scale = 0;
    for (size_t f = 0; f + 1 < mesh.faceOffsets.size(); ++f) {
        const uint32_t first = mesh.faceOffsets[f], n = mesh.faceOffsets[f + 1] - first;
        const glm::dvec3 a = positions[mesh.faceVertices[first]] - c;
        for (uint32_t k = 1; k + 1 < n; ++k) {
            const glm::dvec3 b = positions[mesh.faceVertices[first + k]] - c;
            const glm::dvec3 e = positions[mesh.faceVertices[first + k + 1]] - c;
            volume += glm::dot(a, glm::cross(b, e)) / 6;
            scale += std::abs(glm::dot(a, glm::cross(b, e))) / 6;
        }
    }
    return volume > 1e-6 * scale ? 1.0f : volume < -1e-6 * scale ? -1.0f : 0.0f;
}

bool drawnPointIsApproximate(const SubdivisionDraw& d, uint32_t element, uint32_t st) {
    const uint32_t P = static_cast<uint32_t>(d.patches.size());
    if (element < P) return false;
    const uint32_t face = element - P, full = 32768, half = 16384;
    uint32_t S = st & 0xFFFFu, T = st >> 16;
    auto corner = [&](uint32_t a, uint32_t b) { return (a == 0 || a == full) && (b == 0 || b == full); };
    if (corner(S, T)) return false;
    auto node = [&](uint32_t i) -> const GpuPatch& { return d.irregularNodes.at(i - P); };
    if (face >= d.irregularNodes.size()) return true; // no quadtree: bilinear
    uint32_t at = P + face;
    for (int k = 0; k < 17; ++k) {
        const uint32_t c = (S >= half ? 1u : 0u) | (T >= half ? 2u : 0u), code = node(at).cv[c];
        if (code == kNodeNone) break;
        const uint32_t kind = code & ~kNodeIndexMask, index = code & kNodeIndexMask;
        if (kind == kNodeBasis) { // a smooth face: bilinear only within 2^-bands of its corner
            const GpuPatch& h = node(index);
            if (h.cv[5] > 0) { // below the root: in the quadrant's halved (s, t)
                S = 2 * S - ((c & 1) ? full : 0);
                T = 2 * T - ((c & 2) ? full : 0);
            }
            const uint32_t r = h.cv[1], K = h.cv[3];
            uint32_t a = r == 0 ? S : r == 1 ? T : r == 2 ? full - S : full - T;
            uint32_t b = r == 0 ? T : r == 1 ? full - S : r == 2 ? full - T : S;
            if (a == 0 && b == 0) return false;
            for (uint32_t band = 1; std::max(a, b) < half && band < K; ++band) a *= 2, b *= 2;
            return std::max(a, b) < half;
        }
        S = 2 * S - ((c & 1) ? full : 0);
        T = 2 * T - ((c & 2) ? full : 0);
        if (kind == kNodeSubPatch) return false;
        if (kind == kNodeLeaf) return !corner(S, T);
        at = index;
    }
    // A face (or node) without children there: the face's corners' bilinear blend.
    return !corner(st & 0xFFFFu, st >> 16);
}

} // namespace limn::render
