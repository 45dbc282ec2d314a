#include "subdiv/evaluate.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstring>

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
    for (uint32_t l = 1; l <= t.depth; ++l) {
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

} // namespace limn
