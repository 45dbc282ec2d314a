#include "subdiv/evaluate.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace limn {

void gatherControlPoints(const Patch& p, std::span<const glm::dvec3> V, glm::dvec3 P[4][4]) {
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) P[i][j] = V[p.cv[4 * j + i]];
    // Phantom columns first, then phantom rows over all columns (overwriting the corners), so a
    // corner phantom is 4 P11 - 2 P21 - 2 P12 + P22.
    for (int j = 0; j < 4; ++j) {
        if (p.boundary & kBoundaryU0) P[0][j] = 2.0 * P[1][j] - P[2][j];
        if (p.boundary & kBoundaryU1) P[3][j] = 2.0 * P[2][j] - P[1][j];
    }
    for (int i = 0; i < 4; ++i) {
        if (p.boundary & kBoundaryV0) P[i][0] = 2.0 * P[i][1] - P[i][2];
        if (p.boundary & kBoundaryV1) P[i][3] = 2.0 * P[i][2] - P[i][1];
    }
}

namespace {

glm::dvec3 apply(const StencilTable& table, size_t row, std::span<const glm::dvec3> V) {
    glm::dvec3 sum(0.0);
    for (uint32_t i = table.start[row]; i < table.start[row + 1]; ++i)
        sum += double(table.weights[i]) * V[table.indices[i]];
    return sum;
}

} // namespace

std::vector<glm::dvec3> evaluateVertices(const Tables& t, std::span<const glm::dvec3> control) {
    std::vector<glm::dvec3> V(t.totalVertices);
    for (size_t i = 0; i < t.levels[0].count(); ++i) V[i] = control[i];
    for (uint32_t l = 1; l < t.levels.size(); ++l) { // with the irregular faces' extra levels
        const LevelInfo& info = t.levels[l];
        const StencilTable& faces = t.facePoints[l - 1];
        uint32_t out = info.first;
        for (size_t r = 0; r < faces.rows(); ++r) {
            glm::dvec3 sum(0.0);
            uint32_t n = faces.start[r + 1] - faces.start[r];
            for (uint32_t i = faces.start[r]; i < faces.start[r + 1]; ++i) sum += V[faces.indices[i]];
            V[out++] = sum / double(n);
        }
        for (size_t r = 0; r < t.edgePoints[l - 1].rows(); ++r) V[out++] = apply(t.edgePoints[l - 1], r, V);
        for (size_t r = 0; r < t.vertexPoints[l - 1].rows(); ++r)
            V[out++] = apply(t.vertexPoints[l - 1], r, V);
    }
    return V;
}

void bsplineBasis(double t, double b[4], double d[4]) {
    double t2 = t * t, t3 = t2 * t, s = 1 - t;
    b[0] = s * s * s / 6;
    b[1] = (3 * t3 - 6 * t2 + 4) / 6;
    b[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
    b[3] = t3 / 6;
    d[0] = -s * s / 2;
    d[1] = (9 * t2 - 12 * t) / 6;
    d[2] = (-9 * t2 + 6 * t + 3) / 6;
    d[3] = t2 / 2;
}

void creaseBasis(double t, double sharpness, double b[4], double d[4]) {
    // M: the current 4 control points as combinations of Q0..Q3. Each step halves the segment
    // [Q1', Q2'] by the curve rules: edge points are midpoints, the vertex point of the crease
    // vertex blends its sharp rule (itself) and its smooth rule (Q0 + 6 Q1 + Q2) / 8 by
    // w = min(s, 1) (uniform creasing, Sdc), the others are smooth. Once the segment no longer
    // starts at the crease vertex (t >= 1/2), or s has decayed to 0, it is a uniform B-spline.
    double M[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    double s = sharpness, scale = 1;
    auto step = [&](bool left) {
        const double w = std::min(s, 1.0);
        const double crease[4] = {(1 - w) / 8, w + (1 - w) * 6 / 8, (1 - w) / 8, 0};
        const double e01[4] = {0.5, 0.5, 0, 0}, e12[4] = {0, 0.5, 0.5, 0}, e23[4] = {0, 0, 0.5, 0.5};
        const double v2[4] = {0, 1.0 / 8, 6.0 / 8, 1.0 / 8};
        const double* rows[4] = {e01, crease, e12, v2};
        const double* right[4] = {crease, e12, v2, e23};
        double N[4][4];
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                N[r][c] = 0;
                for (int k = 0; k < 4; ++k) N[r][c] += (left ? rows : right)[r][k] * M[k][c];
            }
        std::memcpy(M, N, sizeof M);
        s -= 1;
        scale *= 2;
        t = left ? 2 * t : 2 * t - 1;
    };
    while (s > 0 && t < 0.5) step(true);
    if (s > 0) step(false);
    double bt[4], dt[4];
    bsplineBasis(t, bt, dt);
    for (int c = 0; c < 4; ++c) {
        b[c] = d[c] = 0;
        for (int k = 0; k < 4; ++k) {
            b[c] += bt[k] * M[k][c];
            d[c] += scale * dt[k] * M[k][c];
        }
    }
}

namespace {


} // namespace

namespace {

// The basis along one patch direction at x: the uniform B-spline, or for a single-crease patch
// across its crease the crease basis, mirrored when the crease is at the far end (the curve's
// points reversed, its derivative negated). `lowBit`/`highBit`: the patch edges at x = 0 / 1.
void directionBasis(const Patch& p, double x, uint8_t lowBit, uint8_t highBit, double b[4], double d[4]) {
    if (!(p.crease & (lowBit | highBit))) {
        bsplineBasis(x, b, d);
        return;
    }
    const bool atEnd = p.crease & highBit;
    double cb[4], cd[4];
    creaseBasis(atEnd ? 1 - x : x, double(p.sharpness), cb, cd);
    for (int k = 0; k < 4; ++k) {
        b[k] = atEnd ? cb[3 - k] : cb[k];
        d[k] = atEnd ? -cd[3 - k] : cd[k];
    }
}

} // namespace

SurfacePoint evaluatePatch(const Patch& p, std::span<const glm::dvec3> V, double s, double t) {
    glm::dvec3 P[4][4];
    gatherControlPoints(p, V, P);
    double bu[4], du[4], bv[4], dv[4];
    directionBasis(p, s, kBoundaryU0, kBoundaryU1, bu, du);
    directionBasis(p, t, kBoundaryV0, kBoundaryV1, bv, dv);
    SurfacePoint r{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            r.position += bu[i] * bv[j] * P[i][j];
            r.du += du[i] * bv[j] * P[i][j];
            r.dv += bu[i] * dv[j] * P[i][j];
        }
    r.du /= double(p.size);
    r.dv /= double(p.size);
    r.normal = glm::normalize(glm::cross(r.du, r.dv));
    return r;
}

void patchPositions(const Patch& p, std::span<const glm::dvec3> V, std::span<const double> params,
                    std::vector<glm::dvec3>& out) {
    glm::dvec3 P[4][4];
    gatherControlPoints(p, V, P);
    double bu[4], du[4], bv[4], dv[4];
    for (double s : params) {
        directionBasis(p, s, kBoundaryU0, kBoundaryU1, bu, du);
        for (double t : params) {
            directionBasis(p, t, kBoundaryV0, kBoundaryV1, bv, dv);
            glm::dvec3 position(0.0); // summed in evaluatePatch's order: the same bits
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) position += bu[i] * bv[j] * P[i][j];
            out.push_back(position);
        }
    }
}

std::vector<LimitPoint> evaluateLimitPoints(const Tables& t, std::span<const glm::dvec3> V) {
    std::vector<LimitPoint> out(t.limitPosition.rows());
    for (size_t i = 0; i < out.size(); ++i) {
        out[i].position = apply(t.limitPosition, i, V);
        out[i].tangent1 = apply(t.limitTangent1, i, V);
        out[i].tangent2 = apply(t.limitTangent2, i, V);
        out[i].normal = glm::normalize(glm::cross(out[i].tangent1, out[i].tangent2));
    }
    return out;
}

namespace {

} // namespace

void smoothSubPatchControlPoints(const Tables& t, uint32_t smooth, std::span<const glm::dvec3> V, uint32_t k,
                                 uint32_t q, glm::dvec3 P[4][4]) {
    const Tables::SmoothIrregular& f = t.smoothIrregular[smooth];
    const IrregularBasis& b = t.irregularBases[f.basis];
    if (!b.hasWeights())
        throw std::logic_error("tables built without their bases' weights (TablesOptions::basisWeights) evaluated");
    const uint32_t M = b.supportSize();
    const float* w = b.weights.data() + (size_t(k - 1) * 3 + (q - 1)) * 16 * M;
    // Relative to the first support point, as the shader's derivatives are: a row's float weights
    // sum to 1 only to a float step, and that step times the points' distance from the origin
    // moved each control point differently (catmark_bishop d3 beside its valence-24 poles, whose
    // bands are a few 1e-7 across: normals 2 degrees off; translated by 10 units, 4 degrees).
    const glm::dvec3 origin = V[t.smoothPoints[f.first]];
    for (int j = 0; j < 16; ++j) {
        glm::dvec3 c(0.0);
        for (uint32_t i = 0; i < M; ++i) c += double(w[size_t(j) * M + i]) * (V[t.smoothPoints[f.first + i]] - origin);
        P[j % 4][j / 4] = origin + c;
    }
}

namespace {

// A smooth irregular face's band-k sub-patch in quadrant q at its local (s, t): its control
// points from the basis weights of the face's support (irregular_basis.h).
SurfacePoint basisPatch(const Tables& t, uint32_t smooth, std::span<const glm::dvec3> V,
                        uint32_t k, uint32_t q, double s, double tt) {
    glm::dvec3 P[4][4];
    smoothSubPatchControlPoints(t, smooth, V, k, q, P);
    // A decaying-crease chain's band may be a single-crease patch (its bits in the canonical
    // frame); every other basis sub-patch is a B-spline (a boundary's phantoms are in the weights).
    const IrregularBasis& b = t.irregularBases[t.smoothIrregular[smooth].basis];
    Patch kind{};
    if (!b.kinds.empty()) {
        const CreaseBandKind& c = b.kinds[size_t(k - 1) * 3 + (q - 1)];
        kind.crease = c.crease;
        kind.sharpness = c.sharpness;
    }
    double bu[4], du[4], bv[4], dv[4];
    directionBasis(kind, s, kBoundaryU0, kBoundaryU1, bu, du);
    directionBasis(kind, tt, kBoundaryV0, kBoundaryV1, bv, dv);
    SurfacePoint r{};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            r.position += bu[i] * bv[j] * P[i][j];
            r.du += du[i] * bv[j] * P[i][j];
            r.dv += bu[i] * dv[j] * P[i][j];
        }
    r.normal = glm::normalize(glm::cross(r.du, r.dv));
    return r;
}

// A smooth irregular face at its (s, t): turned so that the extraordinary corner is at (0, 0)
// (a rotation, so normals keep their sign), then its band k = the number of halvings until
// max(s, t) >= 1/2, at most `bands`; within 2^-bands of the corner, the bilinear blend of the
// corner's limit point and the three last-band points around it. A smooth face `depth` levels
// below its irregular face (a decayed crease) uses the basis's first levels - depth bands; its
// extraordinary vertex is the irregular face's corner of the same index (every extraordinary
// vertex below level N is one of level N), whose limit point it shares.
SurfacePoint evaluateSmooth(const Tables& t, std::span<const glm::dvec3> V, std::span<const LimitPoint> limits,
                            uint32_t face, uint32_t smooth, uint32_t depth, double s, double tt, bool* exact) {
    const Tables::SmoothIrregular& f = t.smoothIrregular[smooth];
    const IrregularBasis& b = t.irregularBases[f.basis];
    const uint32_t bands = b.levels > depth ? b.levels - depth : 1;
    double a, c;
    switch (f.corner) {
    case 0: a = s, c = tt; break;
    case 1: a = tt, c = 1 - s; break;
    case 2: a = 1 - s, c = 1 - tt; break;
    default: a = 1 - tt, c = s; break;
    }
    const LimitPoint& ev = limits[t.irregular[face].corner[f.corner]];
    SurfacePoint r{};
    if (a == 0 && c == 0) {
        r.position = ev.position;
        r.normal = ev.normal;
        return r;
    }
    uint32_t k = 1;
    while (std::max(a, c) < 0.5 && k < bands) a *= 2, c *= 2, ++k;
    if (std::max(a, c) >= 0.5) {
        const uint32_t qu = a >= 0.5 ? 1 : 0, qv = c >= 0.5 ? 1 : 0;
        const uint32_t q = qu && !qv ? 1 : qu && qv ? 2 : 3;
        return basisPatch(t, smooth, V, k, q, 2 * a - qu, 2 * c - qv);
    }
    if (exact) *exact = false;
    const SurfacePoint c1 = basisPatch(t, smooth, V, k, 1, 0, 0), c2 = basisPatch(t, smooth, V, k, 2, 0, 0),
                       c3 = basisPatch(t, smooth, V, k, 3, 0, 0);
    const double x = 2 * a, y = 2 * c;
    const double w[4] = {(1 - x) * (1 - y), x * (1 - y), x * y, (1 - x) * y};
    r.position = w[0] * ev.position + w[1] * c1.position + w[2] * c2.position + w[3] * c3.position;
    const glm::dvec3 n = w[0] * ev.normal + w[1] * c1.normal + w[2] * c2.normal + w[3] * c3.normal;
    r.normal = glm::normalize(n);
    return r;
}

} // namespace

SurfacePoint evaluateIrregular(const Tables& t, std::span<const glm::dvec3> V,
                               std::span<const LimitPoint> limits, uint32_t face, double s,
                               double tt, bool* exact) {
    // Descend the face's quadtree (docs/irregular.md): each step halves the domain, exactly in
    // binary floating point, as the shader does in 1/32768 fixed point.
    const IrregularFace* q = &t.irregular[face];
    if (exact) *exact = true;
    if ((s == 0 || s == 1) && (tt == 0 || tt == 1)) { // a corner: its limit point, as the fixed grids draw it
        const LimitPoint& c = limits[q->corner[s == 0 ? (tt == 0 ? 0 : 3) : (tt == 0 ? 1 : 2)]];
        SurfacePoint r{};
        r.position = c.position;
        r.normal = c.normal;
        return r;
    }
    if (face < t.irregularNodes.size()) {
        uint32_t node = face;
        for (uint32_t level = 0; level <= t.irregularLevels; ++level) {
            const int qu = s >= 0.5 ? 1 : 0, qv = tt >= 0.5 ? 1 : 0;
            s = 2 * s - qu, tt = 2 * tt - qv;
            const uint32_t code = t.irregularNodes[node][qu | qv << 1];
            const uint32_t kind = code & ~kNodeIndexMask, index = code & kNodeIndexMask;
            if (code == kNodeNone) break;
            if (kind == kNodeBasis && level == 0 && smoothRoot(t.irregularNodes[node])) // (s, t) not yet halved
                return evaluateSmooth(t, V, limits, face, index, 0, (s + qu) / 2, (tt + qv) / 2, exact);
            if (kind == kNodeBasis) // the child in this quadrant, level + 1 below the face
                return evaluateSmooth(t, V, limits, face, index, level + 1, s, tt, exact);
            if (kind == kNodeSubPatch) {
                return evaluatePatch(t.subPatches[index], V, s, tt); // derivatives per ptex unit
            }
            if (kind == kNodeLeaf) {
                q = &t.irregularLeaves[index];
                break;
            }
            node = index;
        }
    }
    // A leaf (or a face without a quadtree): the bilinear blend of its corners' limit points,
    // exact only at the corners.
    const double w[4] = {(1 - s) * (1 - tt), s * (1 - tt), s * tt, (1 - s) * tt};
    SurfacePoint r{};
    glm::dvec3 N(0.0);
    for (int k = 0; k < 4; ++k) {
        r.position += w[k] * limits[q->corner[k]].position;
        N += w[k] * limits[q->corner[k]].normal;
    }
    const glm::dvec3 c[4] = {limits[q->corner[0]].position, limits[q->corner[1]].position,
                             limits[q->corner[2]].position, limits[q->corner[3]].position};
    r.du = ((1 - tt) * (c[1] - c[0]) + tt * (c[2] - c[3])) / double(q->size);
    r.dv = ((1 - s) * (c[3] - c[0]) + s * (c[2] - c[1])) / double(q->size);
    r.normal = glm::length(N) > 0 ? glm::normalize(N) : N;
    if (exact) *exact = (s == 0 || s == 1) && (tt == 0 || tt == 1);
    return r;
}

} // namespace limn
