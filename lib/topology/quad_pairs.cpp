#include "topology/quad_pairs.h"

#include "topology/topology.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

namespace limn {

namespace {

using glm::dvec3;

double angleBetween(dvec3 a, dvec3 b) { // unit vectors; acos of a clamped dot
    return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

dvec3 normal(dvec3 a, dvec3 b, dvec3 c) {
    const dvec3 n = glm::cross(a - b, b - c);
    const double l = glm::length(n);
    return l > 0 ? n / l : dvec3(0.0);
}

double area(dvec3 a, dvec3 b, dvec3 c) { return 0.5 * glm::length(glm::cross(b - a, c - a)); }

// The quad v0 v1 v2 v3 folds over itself along one of its diagonals.
bool flipped(const dvec3 v[4]) {
    return glm::dot(normal(v[0], v[1], v[2]), normal(v[2], v[3], v[0])) < 0 ||
           glm::dot(normal(v[1], v[2], v[3]), normal(v[3], v[0], v[1])) < 0;
}

// Each corner's deviation from a right angle.
double worstCornerDeviation(const dvec3 v[4], double& sum) {
    double worst = 0;
    sum = 0;
    for (int i = 0; i < 4; ++i) {
        const dvec3 a = glm::normalize(v[i] - v[(i + 1) % 4]);
        const dvec3 b = glm::normalize(v[(i + 1) % 4] - v[(i + 2) % 4]);
        const double d = std::abs(angleBetween(a, b) - std::numbers::pi / 2);
        worst = std::max(worst, d);
        sum += d;
    }
    return worst;
}

// Blender's quad_calc_error: how far the two splits of the quad are from coplanar, its corners
// from right angles, and its two diagonal splits from equal areas. 0 for a planar rectangle.
double joinError(const dvec3 v[4], double cornerDeviationSum) {
    double error = 0;
    auto bend = [](dvec3 n1, dvec3 n2) { return n1 == n2 ? 0.0 : angleBetween(n1, n2); };
    error += (bend(normal(v[0], v[1], v[2]), normal(v[0], v[2], v[3])) +
              bend(normal(v[1], v[2], v[3]), normal(v[3], v[0], v[1]))) /
             (2 * std::numbers::pi);
    error += cornerDeviationSum / (2 * std::numbers::pi);
    const double a = area(v[0], v[1], v[2]) + area(v[0], v[2], v[3]);
    const double b = area(v[1], v[2], v[3]) + area(v[3], v[0], v[1]);
    const double hi = std::max(a, b);
    error += hi > 0 ? 1.0 - std::min(a, b) / hi : 1.0;
    return error;
}

} // namespace

QuadJoinReport joinTrianglePairs(Mesh& mesh, const QuadJoinOptions& options) {
    QuadJoinReport report;
    const size_t F = mesh.faceCount();
    for (size_t f = 0; f < F; ++f) report.trianglesBefore += mesh.faceSize(f) == 3;
    if (report.trianglesBefore < 2) {
        report.trianglesLeft = report.trianglesBefore;
        return report;
    }
    const Topology T(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    std::set<std::pair<uint32_t, uint32_t>> creased;
    for (const auto& c : mesh.tags.creases)
        if (c.sharpness > 0) creased.insert(std::minmax(c.v0, c.v1));
    std::vector<uint8_t> hole(F, 0);
    for (uint32_t h : mesh.tags.holes)
        if (h < F) hole[h] = 1;

    struct Candidate {
        bool consecutive; // the two triangles are neighbours in the face list
        double error;
        uint32_t edge, a, b; // a: the face of the edge's first half-edge
    };
    std::vector<Candidate> candidates;
    const double cosFace = std::cos(options.maxFaceAngle);
    for (uint32_t e = 0; e < T.edgeCount(); ++e) {
        const uint32_t h = T.edgeHalfedge(e), o = T.twin(h);
        if (o == kNone) continue; // boundary, non-manifold or misoriented
        const uint32_t fa = T.face(h), fb = T.face(o);
        if (fa == fb || T.faceSize(fa) != 3 || T.faceSize(fb) != 3 || hole[fa] != hole[fb]) continue;
        const uint32_t e0 = T.vertex(h), e1 = T.destination(h);
        if (creased.count(std::minmax(e0, e1))) continue;
        if (mesh.hasUVs()) { // the quad keeps one UV per corner
            const uint32_t uvA0 = mesh.uvIndices[h], uvA1 = mesh.uvIndices[T.next(h)];
            const uint32_t uvB1 = mesh.uvIndices[o], uvB0 = mesh.uvIndices[T.next(o)];
            if (uvA0 != uvB0 || uvA1 != uvB1) continue;
        }
        const uint32_t oppA = T.vertex(T.prev(h)), oppB = T.vertex(T.prev(o));
        const dvec3 v[4] = {mesh.positions[e0], mesh.positions[oppA], mesh.positions[e1], mesh.positions[oppB]};
        const dvec3 na = normal(v[0], v[2], v[1]), nb = normal(v[2], v[0], v[3]);
        if (glm::dot(na, nb) < cosFace) continue;
        // As in Blender, the shape limit includes convexity, and 180 degrees turns both off.
        double deviationSum = 0;
        const double deviation = worstCornerDeviation(v, deviationSum);
        if (options.maxShapeAngle < std::numbers::pi && (flipped(v) || deviation > options.maxShapeAngle)) continue;
        candidates.push_back({fa + 1 == fb || fb + 1 == fa, joinError(v, deviationSum), e, fa, fb});
    }
    // partner[f]: the triangle f is joined with (kNone: none); joinHalfedge[f] its half-edge
    // on the shared edge.
    std::vector<uint32_t> partner(F, kNone), joinHalfedge(F, kNone);
    auto join = [&](const Candidate& c) {
        partner[c.a] = c.b;
        partner[c.b] = c.a;
        joinHalfedge[c.a] = T.edgeHalfedge(c.edge);
        joinHalfedge[c.b] = T.twin(T.edgeHalfedge(c.edge));
        ++report.quadsMade;
    };
    // Exporters write the two triangles of a split quad one after the other (Blender's glTF and
    // OBJ exporters, spot_triangulated.obj), so pairs of neighbours in the face list go first.
    // Neighbouring candidates chain (f, f+1), (f+1, f+2), ...; in each chain the most pairs are
    // joined, and among as many, those of the least total error (a path's matching, by dynamic
    // programming).
    std::vector<int64_t> next(F, -1); // next[f]: the candidate joining f and f + 1
    for (size_t i = 0; i < candidates.size(); ++i)
        if (candidates[i].consecutive) next[std::min(candidates[i].a, candidates[i].b)] = int64_t(i);
    for (uint32_t start = 0; start < F; ++start) {
        if (next[start] < 0 || (start > 0 && next[start - 1] >= 0)) continue;
        uint32_t end = start; // the chain is next[start .. end]
        while (end + 1 < F && next[end + 1] >= 0) ++end;
        const size_t n = end - start + 1;
        // best[k]: (pairs, error) of the best matching of the first k links; took[k]: link k-1 used.
        std::vector<std::pair<size_t, double>> best(n + 1, {0, 0.0});
        std::vector<uint8_t> took(n + 1, 0);
        auto better = [](std::pair<size_t, double> x, std::pair<size_t, double> y) {
            return x.first != y.first ? x.first > y.first : x.second < y.second;
        };
        for (size_t k = 1; k <= n; ++k) {
            best[k] = best[k - 1];
            const auto& c = candidates[size_t(next[start + k - 1])];
            const auto with = std::pair{(k >= 2 ? best[k - 2].first : 0) + 1, (k >= 2 ? best[k - 2].second : 0.0) + c.error};
            if (better(with, best[k])) {
                best[k] = with;
                took[k] = 1;
            }
        }
        for (size_t k = n; k >= 1;) {
            if (took[k]) {
                join(candidates[size_t(next[start + k - 1])]);
                if (k < 2) break;
                k -= 2;
            } else {
                --k;
            }
        }
    }
    // Then the rest in Blender's order: the smallest error first, a triangle joined once.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& x, const Candidate& y) { return x.error < y.error; });
    for (const Candidate& c : candidates)
        if (partner[c.a] == kNone && partner[c.b] == kNone) join(c);
    report.trianglesLeft = report.trianglesBefore - 2 * report.quadsMade;
    if (report.quadsMade == 0) return report;

    Mesh out;
    out.positions = std::move(mesh.positions);
    out.uvs = std::move(mesh.uvs);
    out.tags = std::move(mesh.tags);
    out.tags.holes.clear();
    const bool uv = !mesh.uvIndices.empty();
    for (uint32_t f = 0; f < F; ++f) {
        const bool isHole = hole[f];
        if (partner[f] == kNone) {
            out.addFace(mesh.face(f));
            if (uv) {
                auto c = mesh.faceUVs(f);
                out.uvIndices.insert(out.uvIndices.end(), c.begin(), c.end());
            }
        } else if (partner[f] > f) {
            // Face f runs e0 -> e1 -> oppA, its partner e1 -> e0 -> oppB: the quad is
            // e1, oppA, e0, oppB (the winding of both).
            const uint32_t h = joinHalfedge[f], o = joinHalfedge[partner[f]];
            const uint32_t corners[4] = {T.next(h), T.prev(h), h, T.prev(o)};
            uint32_t quad[4];
            for (int k = 0; k < 4; ++k) quad[k] = T.vertex(corners[k]);
            out.addFace(quad);
            if (uv)
                for (int k = 0; k < 4; ++k) out.uvIndices.push_back(mesh.uvIndices[corners[k]]);
        } else {
            continue;
        }
        if (isHole) out.tags.holes.push_back(static_cast<uint32_t>(out.faceCount() - 1));
    }
    mesh = std::move(out);
    return report;
}

} // namespace limn
