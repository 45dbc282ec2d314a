#include "tess/tessellation.h"

#include "base/error.h"
#include "tess/chart_uvs.h"
#include "topology/ptex.h"
#include "topology/topology.h"

#include <algorithm>
#include <bit>
#include <map>
#include <unordered_map>

namespace limn {

namespace {

struct Element {
    uint32_t ptex;
    uint32_t U0, V0, W; // domain in units of 1/R
    uint32_t S;         // own segments per side
};

} // namespace

PtexPoint ptexOf(const Tables& t, const TessVertex& v) {
    uint32_t P = static_cast<uint32_t>(t.patches.size());
    float u0, v0, size;
    uint32_t ptex;
    if (v.element < P) {
        const Patch& p = t.patches[v.element];
        ptex = p.ptex, u0 = p.u0, v0 = p.v0, size = p.size;
    } else {
        const IrregularFace& q = t.irregular[v.element - P];
        ptex = q.ptex, u0 = q.u0, v0 = q.v0, size = q.size;
    }
    return {ptex, u0 + double(v.s) / kTessParamOne * size, v0 + double(v.t) / kTessParamOne * size};
}

Tessellation buildTessellation(const Mesh& mesh, const Tables& t, uint32_t cap, bool splitUVSeams,
                               ChartUVs* smooth) {
    if (cap < 1) throw Error(ErrorKind::Usage, "the tessellation cap must be at least 1");
    // The fixed grids of neighbours must meet vertex to vertex, so every element's segment count
    // divides its neighbours': a cap that is not a power of two (--tess 3, 12) is rounded down to
    // one (a grid of 3 on a side of width 64 left points off the 1/R lattice, and the stitching
    // walked off an empty list).
    cap = std::bit_floor(cap);
    if (splitUVSeams && !mesh.hasUVs())
        throw Error(ErrorKind::BadInput, "the mesh has no texture coordinates to split seams by");
    const bool withUV = mesh.hasUVs();
    const uint32_t N = t.depth, R = 1u << N;
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    PtexMap keys(mesh, topo, R);

    std::vector<Element> elements;
    auto addElement = [&](uint32_t ptex, float u0, float v0, float size, uint32_t level) {
        Element e;
        e.ptex = ptex;
        e.U0 = uint32_t(double(u0) * R);
        e.V0 = uint32_t(double(v0) * R);
        e.W = uint32_t(double(size) * R);
        e.S = std::min(std::min<uint32_t>(1u << (N - level), cap), e.W);
        elements.push_back(e);
    };
    for (const auto& p : t.patches) addElement(p.ptex, p.u0, p.v0, p.size, p.level);
    for (const auto& q : t.irregular) addElement(q.ptex, q.u0, q.v0, q.size, N);

    Tessellation out;
    std::unordered_map<uint64_t, uint32_t> owner;  // geometric point -> its first vertex
    std::unordered_map<uint64_t, bool> onUVSeam;   // geometric point -> its faces disagree on UV
    std::map<std::pair<uint64_t, std::pair<float, float>>, uint32_t> copies; // (point, UV) -> copy
    owner.reserve(elements.size() * 8);
    std::vector<PtexMap::ChartUV> charts;
    auto uvOf = [&](const Element& e, uint32_t U, uint32_t V) {
        if (smooth) return smooth->own(e.ptex, U, V, e.U0 + 0.5 * e.W, e.V0 + 0.5 * e.W);
        return glm::vec2(keys.ownUV(e.ptex, double(U) / R, double(V) / R));
    };
    auto seamPoint = [&](const Element& e, uint32_t U, uint32_t V, uint64_t k) {
        auto [it, inserted] = onUVSeam.try_emplace(k, false);
        if (inserted && (k >> 61) != 0) { // base vertices and edges only; interiors have one chart
            keys.charts(e.ptex, U, V, charts);
            for (const auto& c : charts) it->second |= glm::vec2(c.uv) != glm::vec2(charts[0].uv);
        }
        return it->second;
    };
    // The vertex element `e` uses at (U, V): the point's own vertex, or at a UV seam the copy for
    // e's chart (made on first use, sharing the first vertex's geometry).
    auto vertexFor = [&](uint32_t ei, uint32_t U, uint32_t V, bool create) -> uint32_t {
        const Element& e = elements[ei];
        uint64_t k = keys.key(e.ptex, U, V);
        auto it = owner.find(k);
        if (it == owner.end()) {
            if (!create) return kNone;
            uint32_t unit = kTessParamOne / e.W; // e.W is a power of two <= R <= 2^16
            it = owner.emplace(k, static_cast<uint32_t>(out.vertices.size())).first;
            out.vertices.push_back({ei, uint16_t((U - e.U0) * unit), uint16_t((V - e.V0) * unit)});
            out.geometry.push_back(it->second);
            if (withUV) {
                out.uvs.push_back(uvOf(e, U, V));
                out.uvSources.push_back(out.vertices.back());
            }
        }
        if (!splitUVSeams || !seamPoint(e, U, V, k)) return it->second;
        glm::vec2 uv = uvOf(e, U, V);
        const uint32_t first = it->second;
        if (out.uvs[first] == uv) return first;
        auto [c, inserted] = copies.try_emplace({k, {uv.x, uv.y}}, static_cast<uint32_t>(out.vertices.size()));
        if (inserted) {
            out.vertices.push_back(out.vertices[first]);
            out.geometry.push_back(first);
            out.uvs.push_back(uv);
            const uint32_t unit = kTessParamOne / e.W;
            out.uvSources.push_back({ei, uint16_t((U - e.U0) * unit), uint16_t((V - e.V0) * unit)});
        }
        return c->second;
    };
    auto visit = [&](uint32_t ei, uint32_t i, uint32_t j, uint32_t step) {
        const Element& e = elements[ei];
        return vertexFor(ei, e.U0 + i * step, e.V0 + j * step, true);
    };
    uint32_t current = 0; // the element being triangulated (pass 2)
    auto find = [&](const Element&, uint32_t U, uint32_t V) -> uint32_t {
        return vertexFor(current, U, V, false);
    };

    // Pass 1: every element registers its own grid points (owners in element order).
    for (uint32_t ei = 0; ei < elements.size(); ++ei) {
        const Element& e = elements[ei];
        uint32_t step = e.W / e.S;
        for (uint32_t j = 0; j <= e.S; ++j)
            for (uint32_t i = 0; i <= e.S; ++i) visit(ei, i, j, step);
        out.segments.push_back(e.S);
    }

    // Pass 2: triangulate. Each element edge gathers every point registered along it (its own and
    // finer neighbours'); boundary cells are fanned from an inner corner, or from the cell centre
    // when the element is a single cell, so no triangle is degenerate.
    std::vector<uint32_t> ring;
    for (uint32_t ei = 0; ei < elements.size(); ++ei) {
        const Element e = elements[ei];
        current = ei;
        const uint32_t S = e.S, step = e.W / S;
        // Points along each edge, in counter-clockwise order around the element, at unit spacing.
        auto edgePoints = [&](int side, uint32_t from, uint32_t to, std::vector<uint32_t>& pts) {
            pts.clear();
            for (uint32_t x = from; x <= to; ++x) {
                uint32_t U = 0, V = 0;
                switch (side) {
                case 0: U = e.U0 + x, V = e.V0; break;                 // v = 0, u increasing
                case 1: U = e.U0 + e.W, V = e.V0 + x; break;           // u = 1, v increasing
                case 2: U = e.U0 + e.W - x, V = e.V0 + e.W; break;     // v = 1, u decreasing
                case 3: U = e.U0, V = e.V0 + e.W - x; break;           // u = 0, v decreasing
                }
                uint32_t id = find(e, U, V);
                if (id != kNone) pts.push_back(id);
            }
        };
        bool stitched[4] = {false, false, false, false};
        std::vector<uint32_t> sidePts[4];
        const size_t firstIndex = out.indices.size();
        for (int side = 0; side < 4; ++side) {
            edgePoints(side, 0, e.W, sidePts[side]);
            stitched[side] = sidePts[side].size() != S + 1;
            out.stitchedEdges += stitched[side];
            for (size_t k = 0; k + 1 < sidePts[side].size(); ++k) {
                out.outline.push_back(sidePts[side][k]);
                out.outline.push_back(sidePts[side][k + 1]);
            }
        }
        auto grid = [&](uint32_t i, uint32_t j) { return find(e, e.U0 + i * step, e.V0 + j * step); };
        auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
            out.indices.insert(out.indices.end(), {a, b, c});
        };
        for (uint32_t j = 0; j < S; ++j)
            for (uint32_t i = 0; i < S; ++i) {
                bool onBoundary[4] = {j == 0 && stitched[0], i + 1 == S && stitched[1],
                                      j + 1 == S && stitched[2], i == 0 && stitched[3]};
                if (!onBoundary[0] && !onBoundary[1] && !onBoundary[2] && !onBoundary[3]) {
                    uint32_t a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
                    tri(a, b, c);
                    tri(a, c, d);
                    continue;
                }
                // The cell's boundary, counter-clockwise, with every point registered on it.
                ring.clear();
                std::vector<uint32_t> pts;
                const uint32_t x0 = i * step, x1 = (i + 1) * step, y0 = j * step, y1 = (j + 1) * step;
                edgePoints(0, x0, x1, pts);
                if (j == 0) ring.insert(ring.end(), pts.begin(), pts.end() - 1);
                else ring.push_back(grid(i, j));
                if (i + 1 == S) {
                    edgePoints(1, y0, y1, pts);
                    ring.insert(ring.end(), pts.begin(), pts.end() - 1);
                } else {
                    ring.push_back(grid(i + 1, j));
                }
                if (j + 1 == S) {
                    edgePoints(2, e.W - x1, e.W - x0, pts);
                    ring.insert(ring.end(), pts.begin(), pts.end() - 1);
                } else {
                    ring.push_back(grid(i + 1, j + 1));
                }
                if (i == 0) {
                    edgePoints(3, e.W - y1, e.W - y0, pts);
                    ring.insert(ring.end(), pts.begin(), pts.end() - 1);
                } else {
                    ring.push_back(grid(i, j + 1));
                }
                if (S == 1) {
                    // A single cell touching every side: fan from a new centre point, owned here.
                    uint32_t centre = static_cast<uint32_t>(out.vertices.size());
                    out.vertices.push_back({ei, uint16_t(kTessParamOne / 2), uint16_t(kTessParamOne / 2)});
                    out.geometry.push_back(centre);
                    const double cu = (e.U0 + 0.5 * e.W) / R, cv = (e.V0 + 0.5 * e.W) / R;
                    if (withUV) {
                        out.uvs.push_back(smooth ? smooth->interior(e.ptex, cu, cv)
                                                 : glm::vec2(keys.ownUV(e.ptex, cu, cv)));
                        out.uvSources.push_back(out.vertices.back());
                    }
                    for (size_t r = 0; r < ring.size(); ++r) tri(centre, ring[r], ring[(r + 1) % ring.size()]);
                    continue;
                }
                // Fan from an inner corner (one not on the element's boundary).
                uint32_t apex = i + 1 < S && j + 1 < S ? grid(i + 1, j + 1)
                                : i > 0 && j + 1 < S  ? grid(i, j + 1)
                                : i > 0 && j > 0      ? grid(i, j)
                                                      : grid(i + 1, j);
                size_t a = std::find(ring.begin(), ring.end(), apex) - ring.begin();
                for (size_t r = 1; r + 1 < ring.size(); ++r)
                    tri(apex, ring[(a + r) % ring.size()], ring[(a + r + 1) % ring.size()]);
            }
        out.triangleCounts.push_back(static_cast<uint32_t>((out.indices.size() - firstIndex) / 3));
    }
    return out;
}

} // namespace limn

#include "subdiv/evaluate.h"

#include <glm/geometric.hpp>

namespace limn {

std::vector<TessPoint> evaluateTessellation(const Tables& t, const Tessellation& tess,
                                            std::span<const glm::dvec3> V,
                                            std::span<const LimitPoint> limits) {
    std::vector<TessPoint> out(tess.vertices.size());
    const uint32_t P = static_cast<uint32_t>(t.patches.size());
    for (size_t i = 0; i < out.size(); ++i) {
        const TessVertex& tv = tess.vertices[i];
        double s = double(tv.s) / kTessParamOne, u = double(tv.t) / kTessParamOne;
        if (tv.element < P) {
            SurfacePoint p = evaluatePatch(t.patches[tv.element], V, s, u);
            out[i] = {p.position, p.normal};
            continue;
        }
        SurfacePoint p = evaluateIrregular(t, V, limits, tv.element - P, s, u);
        out[i] = {p.position, p.normal};
    }
    return out;
}

} // namespace limn
