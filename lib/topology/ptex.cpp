#include "topology/ptex.h"

#include <algorithm>

namespace limn {

namespace {

enum KeyKind : uint64_t { kInterior = 0, kVertex = 1, kEdge = 2, kSpoke = 3, kCentroid = 4 };

uint64_t makeKey(uint64_t kind, uint64_t id, uint64_t a, uint64_t b) {
    return kind << 61 | (id & 0x7FFFFFFull) << 34 | (a & 0x1FFFF) << 17 | (b & 0x1FFFF);
}

glm::dvec2 bilinear(const glm::dvec2 c[4], double u, double v) {
    return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
}

} // namespace

PtexMap::PtexMap(const Mesh& mesh, const Topology& topo, uint32_t resolution)
    : mesh_(mesh), topo_(topo), R_(resolution) {
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        firstPtex_.push_back(static_cast<uint32_t>(ptex_.size()));
        uint32_t n = mesh.faceSize(f);
        if (n == 4)
            ptex_.push_back({f, -1});
        else
            for (uint32_t k = 0; k < n; ++k) ptex_.push_back({f, int32_t(k)});
    }
    // Each n-gon's UV centroid once: every point of its n sub-faces uses it, so summing it per
    // point made an n-gon of thousands of sides cost its square.
    if (mesh.hasUVs()) {
        centroidUV_.resize(mesh.faceCount());
        for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
            const auto uvi = mesh.faceUVs(f);
            if (uvi.size() == 4) continue;
            glm::dvec2 sum(0.0);
            for (uint32_t i : uvi) sum += mesh.uvs[i];
            centroidUV_[f] = sum / double(uvi.size());
        }
    }
}

bool PtexMap::isBaseVertexKey(uint64_t key) { return key >> 61 == kVertex; }

uint64_t PtexMap::onEdge(uint32_t a, uint32_t b, uint32_t t) const {
    if (t == 0) return makeKey(kVertex, a, 0, 0);
    if (t == 2 * R_) return makeKey(kVertex, b, 0, 0);
    uint32_t e = topo_.findEdge(a, b);
    if (a > b) t = 2 * R_ - t;
    return makeKey(kEdge, e, t, 0);
}

uint64_t PtexMap::key(uint32_t p, uint32_t U, uint32_t V) const {
    const PtexFace pf = ptex_[p];
    auto fv = mesh_.face(pf.face);
    if (U > 0 && U < R_ && V > 0 && V < R_) return makeKey(kInterior, p, U, V);
    if (pf.sub < 0) {
        // Corners c0 (0,0), c1 (1,0), c2 (1,1), c3 (0,1); positions along edges at 2R.
        if (V == 0) return onEdge(fv[0], fv[1], 2 * U);
        if (U == R_) return onEdge(fv[1], fv[2], 2 * V);
        if (V == R_) return onEdge(fv[3], fv[2], 2 * U);
        return onEdge(fv[0], fv[3], 2 * V);
    }
    const uint32_t n = static_cast<uint32_t>(fv.size()), k = uint32_t(pf.sub);
    if (V == 0) return onEdge(fv[k], fv[(k + 1) % n], U); // half of base edge (k, k+1)
    if (U == 0) return onEdge(fv[k], fv[(k + n - 1) % n], V);
    if (U == R_ && V == R_) return makeKey(kCentroid, pf.face, 0, 0);
    if (U == R_) return makeKey(kSpoke, pf.face, k, V);  // mid(k, k+1) -> centre
    return makeKey(kSpoke, pf.face, (k + n - 1) % n, U); // mid(k-1, k) -> centre
}

glm::dvec2 PtexMap::cornerUV(uint32_t h) const { return mesh_.uvs[mesh_.uvIndices[h]]; }

glm::dvec2 PtexMap::ownUV(uint32_t p, double u, double v) const {
    const PtexFace pf = ptex_[p];
    auto uvi = mesh_.faceUVs(pf.face);
    const uint32_t n = static_cast<uint32_t>(uvi.size());
    glm::dvec2 c[4];
    if (pf.sub < 0) {
        for (int i = 0; i < 4; ++i) c[i] = mesh_.uvs[uvi[i]];
    } else {
        const uint32_t k = uint32_t(pf.sub);
        c[0] = mesh_.uvs[uvi[k]];
        c[1] = 0.5 * (mesh_.uvs[uvi[k]] + mesh_.uvs[uvi[(k + 1) % n]]);
        c[2] = centroidUV_[pf.face];
        c[3] = 0.5 * (mesh_.uvs[uvi[(k + n - 1) % n]] + mesh_.uvs[uvi[k]]);
    }
    return bilinear(c, u, v);
}

void PtexMap::charts(uint32_t p, uint32_t U, uint32_t V, std::vector<ChartUV>& out) const {
    out.clear();
    const PtexFace pf = ptex_[p];
    auto fv = mesh_.face(pf.face);
    const double u = double(U) / R_, v = double(V) / R_;
    const bool inside = U > 0 && U < R_ && V > 0 && V < R_;
    // Which base vertex or base edge the point is on, as (a, b, fraction from a).
    uint32_t a = kNone, b = kNone;
    double t = 0;
    if (!inside) {
        if (pf.sub < 0) {
            if (V == 0)
                a = fv[0], b = fv[1], t = u;
            else if (U == R_)
                a = fv[1], b = fv[2], t = v;
            else if (V == R_)
                a = fv[3], b = fv[2], t = u;
            else
                a = fv[0], b = fv[3], t = v;
        } else {
            const uint32_t n = static_cast<uint32_t>(fv.size()), k = uint32_t(pf.sub);
            if (V == 0)
                a = fv[k], b = fv[(k + 1) % n], t = u / 2;
            else if (U == 0)
                a = fv[k], b = fv[(k + n - 1) % n], t = v / 2;
        }
    }
    if (a == kNone) { // inside the base face (or on an n-gon's spokes): one chart
        out.push_back({pf.face, ownUV(p, u, v)});
        return;
    }
    if (t == 0 || t == 1) { // a base vertex: every face around it
        uint32_t vtx = t == 0 ? a : b;
        for (uint32_t h : topo_.vertexOutgoing(vtx)) out.push_back({topo_.face(h), cornerUV(h)});
    } else { // a base edge: its one or two faces
        uint32_t e = topo_.findEdge(a, b);
        uint32_t h = topo_.edgeHalfedge(e);
        for (uint32_t hh : {h, topo_.twin(h)}) {
            if (hh == kNone) continue;
            // hh runs from one end to the other in its face: the corners of a and b there.
            const bool fromA = topo_.vertex(hh) == a;
            const glm::dvec2 uvA = cornerUV(fromA ? hh : topo_.next(hh)), uvB = cornerUV(fromA ? topo_.next(hh) : hh);
            out.push_back({topo_.face(hh), (1 - t) * uvA + t * uvB});
        }
    }
    std::sort(out.begin(), out.end(),
              [](const ChartUV& x, const ChartUV& y) { return x.face < y.face; });
}

} // namespace limn
