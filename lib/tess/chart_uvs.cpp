#include "tess/chart_uvs.h"

#include <algorithm>

namespace limn {

ChartUVs::ChartUVs(const Mesh& mesh, const FaceVaryingSurface& surface, uint32_t resolution)
    : mesh_(mesh), topo_(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices),
      keys_(mesh, topo_, 2 * resolution), surface_(surface), Q_(2 * resolution) {
    uint32_t p = 0;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        firstPtex_.push_back(p);
        p += mesh.faceSize(f) == 4 ? 1 : mesh.faceSize(f);
    }
}

glm::vec2 ChartUVs::interior(uint32_t ptex, double u, double v) const {
    return glm::vec2(surface_.uvAt(ptex, u, v, 0.5, 0.5));
}

glm::vec2 ChartUVs::own(uint32_t ptex, uint32_t U, uint32_t V, double towardU, double towardV) {
    return ownQ(ptex, 2 * U, 2 * V, 2 * towardU, 2 * towardV);
}

glm::vec2 ChartUVs::ownQ(uint32_t ptex, uint32_t X, uint32_t Y, double tx, double ty) {
    auto& faces = memo_[keys_.key(ptex, X, Y)];
    const uint32_t face = keys_.baseFace(ptex);
    auto it = faces.find(face);
    if (it != faces.end()) return it->second;
    const double q = Q_;
    glm::vec2 uv(surface_.uvAt(ptex, X / q, Y / q, tx / q, ty / q));
    faces.emplace(face, uv);
    return uv;
}

ChartUVs::Located ChartUVs::inFace(uint32_t f, uint32_t a, uint32_t b, uint32_t t) const {
    auto fv = mesh_.face(f);
    const uint32_t n = static_cast<uint32_t>(fv.size());
    uint32_t i = 0;
    while (i < n && fv[i] != a) ++i;
    const bool forward = fv[(i + 1) % n] == b;
    const uint32_t Q = Q_, first = firstPtex_[f];
    if (n == 4) {
        static constexpr uint32_t cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
        const uint32_t j = forward ? (i + 1) % 4 : (i + 3) % 4;
        // t is even for every point on the R lattice: (2Q - t) / 2 and t / 2 are exact.
        const uint32_t X = (cu[i] * (2 * Q - t) + cu[j] * t) / 2, Y = (cv[i] * (2 * Q - t) + cv[j] * t) / 2;
        return {f, first, X, Y};
    }
    if (t == 0) return {f, first + i, 0, 0};
    if (forward) return t <= Q ? Located{f, first + i, t, 0} : Located{f, first + (i + 1) % n, 0, 2 * Q - t};
    return t <= Q ? Located{f, first + i, 0, t} : Located{f, first + (i + n - 1) % n, 2 * Q - t, 0};
}

void ChartUVs::locate(uint32_t p, uint32_t X, uint32_t Y, std::vector<Located>& out) const {
    out.clear();
    const uint32_t Q = Q_, face = keys_.baseFace(p);
    const int32_t sub = keys_.subFace(p);
    auto fv = mesh_.face(face);
    uint32_t a = kNone, b = kNone, t = 0;
    if (sub < 0) {
        if (Y == 0) a = fv[0], b = fv[1], t = 2 * X;
        else if (X == Q) a = fv[1], b = fv[2], t = 2 * Y;
        else if (Y == Q) a = fv[3], b = fv[2], t = 2 * X;
        else if (X == 0) a = fv[0], b = fv[3], t = 2 * Y;
    } else {
        const uint32_t n = static_cast<uint32_t>(fv.size()), k = uint32_t(sub);
        if (Y == 0) a = fv[k], b = fv[(k + 1) % n], t = X;
        else if (X == 0) a = fv[k], b = fv[(k + n - 1) % n], t = Y;
    }
    if (a == kNone) { // inside the face, or on an n-gon's spokes: its one chart
        out.push_back({face, p, X, Y});
        return;
    }
    if (t == 2 * Q) std::swap(a, b), t = 0;
    if (t == 0) {
        for (uint32_t h : topo_.vertexOutgoing(a)) out.push_back(inFace(topo_.face(h), a, a, 0));
    } else {
        const uint32_t h = topo_.edgeHalfedge(topo_.findEdge(a, b));
        for (uint32_t hh : {h, topo_.twin(h)})
            if (hh != kNone) out.push_back(inFace(topo_.face(hh), a, b, t));
    }
    // A hole (or a face without a limit surface) has no UV surface and is not drawn: nothing
    // there to sample or to agree with.
    std::erase_if(out, [&](const Located& l) { return !surface_.hasElements(l.ptex); });
    std::sort(out.begin(), out.end(), [](const Located& x, const Located& y) { return x.face < y.face; });
}

void ChartUVs::sides(uint32_t ptex, uint32_t U, uint32_t V, std::vector<glm::vec2>& out) {
    out.clear();
    locate(ptex, 2 * U, 2 * V, located_);
    for (const Located& l : located_) {
        glm::vec2 uv = ownQ(l.ptex, l.U, l.V, 0.5 * Q_, 0.5 * Q_);
        if (std::find(out.begin(), out.end(), uv) == out.end()) out.push_back(uv);
    }
}

} // namespace limn

namespace limn {

void ChartUVs::edgeSides(uint32_t ptex, uint32_t Ua, uint32_t Va, uint32_t Ub, uint32_t Vb,
                         std::vector<std::pair<glm::vec2, glm::vec2>>& out) {
    out.clear();
    locate(ptex, Ua + Ub, Va + Vb, located_); // the midpoint, in Q units: the faces along the edge
    locate(ptex, 2 * Ua, 2 * Va, ends_[0]);
    locate(ptex, 2 * Ub, 2 * Vb, ends_[1]);
    for (const Located& side : located_) {
        glm::vec2 uv[2];
        for (int end = 0; end < 2; ++end)
            for (const Located& l : ends_[end])
                if (l.face == side.face) uv[end] = ownQ(l.ptex, l.U, l.V, 0.5 * Q_, 0.5 * Q_);
        const std::pair<glm::vec2, glm::vec2> pair{uv[0], uv[1]};
        if (std::find(out.begin(), out.end(), pair) == out.end()) out.push_back(pair);
    }
}

} // namespace limn
