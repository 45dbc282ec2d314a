#include "loop/refine.h"

#include "base/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace limn::loop {

double compactness(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    glm::dvec3 ab = b - a, bc = c - b, ca = a - c;
    double l2 = glm::dot(ab, ab) + glm::dot(bc, bc) + glm::dot(ca, ca);
    if (!(l2 > 0)) return 0;
    double area = 0.5 * glm::length(glm::cross(ab, -ca));
    return 4.0 * std::sqrt(3.0) * area / l2;
}

namespace {

// Face-varying values of the odd vertices: one per (edge, UV at its first end, UV at its second
// end), so both sides of an edge share a value unless the edge is a UV seam (linear
// interpolation, OpenSubdiv's FVAR_LINEAR_ALL). At most two entries per edge (manifold).
class OddUVs {
public:
    OddUVs(std::vector<glm::dvec2>& uvs, uint32_t edges) : uvs_(uvs), slots_(edges) {}
    // `u0`, `u1`: the UV indices at the edge's first and second vertex (edgeVertices order).
    uint32_t get(uint32_t e, uint32_t u0, uint32_t u1) {
        for (const Slot& s : slots_[e])
            if (s.used && s.u0 == u0 && s.u1 == u1) return s.value;
        for (Slot& s : slots_[e])
            if (!s.used) {
                s = {true, u0, u1, static_cast<uint32_t>(uvs_.size())};
                uvs_.push_back(0.5 * (uvs_[u0] + uvs_[u1]));
                return s.value;
            }
        throwBadInput("internal error: more than two faces at an edge");
    }

private:
    struct Slot {
        bool used = false;
        uint32_t u0 = 0, u1 = 0, value = 0;
    };
    std::vector<glm::dvec2>& uvs_;
    std::vector<std::array<Slot, 2>> slots_;
};

} // namespace

void appendTemplate(const Tri& corner, const Tri& mid, const std::vector<glm::dvec3>& P,
                    TriMesh& out, const Tri* uvCorner, const Tri* uvMid) {
    const bool uv = uvCorner != nullptr;
    int count = 0;
    for (uint32_t m : mid) count += m != kNone ? 1 : 0;
    // Rotation r: x = corner r, y = corner r+1, z = corner r+2; edge i joins corner i and i+1.
    auto emit = [&](int r, std::initializer_list<int> codes) {
        // Codes: 0..2 = x, y, z; 3..5 = m_xy, m_yz, m_zx.
        Tri t{}, tuv{};
        int j = 0;
        for (int c : codes) {
            int idx = (r + c % 3) % 3;
            t[j] = c < 3 ? corner[idx] : mid[idx];
            if (uv) tuv[j] = c < 3 ? (*uvCorner)[idx] : (*uvMid)[idx];
            ++j;
        }
        out.triangles.push_back(t);
        if (uv) out.uvTriangles.push_back(tuv);
    };
    enum { X = 0, Y = 1, Z = 2, MXY = 3, MYZ = 4, MZX = 5 };
    if (count == 0) {
        emit(0, {X, Y, Z});
    } else if (count == 3) {
        emit(0, {X, MXY, MZX});
        emit(0, {MXY, Y, MYZ});
        emit(0, {MZX, MYZ, Z});
        emit(0, {MXY, MYZ, MZX});
    } else if (count == 1) {
        int r = 0;
        while (mid[r] == kNone) ++r; // the split edge becomes xy
        emit(r, {X, MXY, Z});
        emit(r, {MXY, Y, Z});
    } else {
        int u = 0;
        while (mid[u] != kNone) ++u; // the unsplit edge becomes zx: rotation r = u + 1
        int r = (u + 1) % 3;
        uint32_t x = corner[r], z = corner[(r + 2) % 3], mxy = mid[r], myz = mid[(r + 1) % 3];
        // Diagonal by the larger minimum compactness on the new positions; ties take A.
        double qa = std::min(compactness(P[x], P[mxy], P[myz]), compactness(P[x], P[myz], P[z]));
        double qb = std::min(compactness(P[x], P[mxy], P[z]), compactness(P[mxy], P[myz], P[z]));
        emit(r, {MXY, Y, MYZ});
        if (qa >= qb) {
            emit(r, {X, MXY, MYZ}); // A: diagonal x–m_yz
            emit(r, {X, MYZ, Z});
        } else {
            emit(r, {X, MXY, Z}); // B: diagonal m_xy–z
            emit(r, {MXY, MYZ, Z});
        }
    }
}

Refinement refine(const Level& level, std::span<const uint8_t> split, EvenUpdate update,
                  const std::vector<glm::dvec3>& even, const std::vector<glm::dvec3>& odd) {
    const Topology& topo = level.topology();
    const TriMesh& in = level.mesh();
    const uint32_t V = in.vertexCount(), E = topo.edgeCount();
    if (split.size() != E) throwBadInput("internal error: one split flag per edge expected");

    Refinement result;
    TriMesh& out = result.mesh;
    // Vertices (math.md B.7): even update, then the odd vertices of the split edges.
    std::vector<uint8_t> touched(V, update == EvenUpdate::All ? 1 : 0);
    std::vector<uint32_t> oddIndex(E, kNone);
    uint32_t next = V;
    for (uint32_t e = 0; e < E; ++e) {
        if (!split[e]) continue;
        auto [a, b] = topo.edgeVertices(e);
        touched[a] = touched[b] = 1;
        oddIndex[e] = next++;
        result.oddParents.push_back({a, b});
    }
    out.positions.resize(next);
    for (uint32_t v = 0; v < V; ++v) out.positions[v] = touched[v] ? even[v] : in.positions[v];
    for (uint32_t e = 0; e < E; ++e)
        if (split[e]) out.positions[oddIndex[e]] = odd[e];
    out.corners = in.corners;
    out.corners.resize(next, 0);
    // Sharp edges stay sharp, split ones in both halves.
    for (uint32_t e = 0; e < E; ++e) {
        if (!level.edgeSharp(e) || topo.edgeIsBoundary(e)) continue;
        auto [a, b] = topo.edgeVertices(e);
        if (split[e]) {
            out.creases.push_back({std::min(a, oddIndex[e]), std::max(a, oddIndex[e])});
            out.creases.push_back({std::min(b, oddIndex[e]), std::max(b, oddIndex[e])});
        } else {
            out.creases.push_back({std::min(a, b), std::max(a, b)});
        }
    }

    std::sort(out.creases.begin(), out.creases.end());

    const bool uv = in.hasUVs();
    if (uv) out.uvs = in.uvs;
    OddUVs oddUVs(out.uvs, uv ? E : 0);
    out.triangles.reserve(in.triangles.size() * 2);
    for (uint32_t f = 0; f < in.triangleCount(); ++f) {
        uint32_t h0 = topo.faceHalfedge(f);
        uint32_t hs[3] = {h0, topo.next(h0), topo.prev(h0)};
        Tri vs{}, mids{}, uvs{}, uvMids{};
        for (int i = 0; i < 3; ++i) {
            vs[i] = topo.vertex(hs[i]);
            mids[i] = oddIndex[topo.edge(hs[i])];
        }
        if (uv) {
            for (int i = 0; i < 3; ++i) uvs[i] = in.uvTriangles[f][topo.cornerIndex(hs[i])];
            for (int i = 0; i < 3; ++i) {
                uint32_t e = topo.edge(hs[i]);
                if (!split[e]) continue;
                bool forward = topo.edgeVertices(e)[0] == vs[i];
                uint32_t ua = uvs[i], ub = uvs[(i + 1) % 3];
                uvMids[i] = forward ? oddUVs.get(e, ua, ub) : oddUVs.get(e, ub, ua);
            }
        }
        appendTemplate(vs, mids, out.positions, out, uv ? &uvs : nullptr, uv ? &uvMids : nullptr);
    }
    return result;
}

} // namespace limn::loop
