#include "subdiv/irregular_basis.h"

#include "base/error.h"
#include "base/warnings.h"
#include "mesh/mesh.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace limn {

bool smoothSupport(const Level& L, uint32_t f, int& corner, uint32_t& valence,
                   std::vector<uint32_t>& support) {
    const Topology& T = L.topo;
    if (T.faceSize(f) != 4 || L.noLimit[f]) return false;
    const FaceFrame& fr = L.frames[f];
    int ev = -1;
    for (int k = 0; k < 4; ++k) {
        const uint32_t v = T.vertex(T.faceHalfedge(f) + (fr.rotation + k) % 4);
        if (T.vertexIsBoundary(v) || T.vertexIsNonManifold(v)) return false;
        const uint32_t n = T.vertexFaceCount(v);
        if (n == 4) continue;
        if (ev >= 0 || n < 3) return false;
        ev = k;
        valence = n;
    }
    if (ev < 0) return false;
    corner = ev;
    support.clear();
    for (int j = 0; j < 4; ++j) {
        const uint32_t h0 = T.faceHalfedge(f) + (fr.rotation + ev + j) % 4;
        uint32_t h = h0;
        do {
            const uint32_t g = T.face(h);
            if (T.faceSize(g) != 4 || L.noLimit[g]) return false;
            uint32_t x = h;
            for (int c = 0; c < 4; ++c, x = T.next(x)) {
                const uint32_t v = T.vertex(x);
                if (L.vertexSharpness[v] != 0 || L.edgeSharpness[T.edge(x)] != 0) return false;
                if (std::find(support.begin(), support.end(), v) == support.end()) support.push_back(v);
            }
            h = T.rotateCCW(h);
            if (h == kNone) return false;
        } while (h != h0);
    }
    return support.size() == 2 * size_t(valence) + 8;
}

IrregularBasis buildIrregularBasis(uint32_t n, uint32_t K) {
    if (n < 3 || K < 1 || K > uint32_t(kMaxDepth))
        throw std::logic_error("irregular basis: valence or levels out of range");
    // Three rings of quads around a valence-n vertex: sector j spans rays j and j+1, its point
    // (a, b) = a e_j + b e_{j+1}; the ray points (a, 0) belong to sector j. The rim (a boundary)
    // is two faces beyond face 0, whose sub-patches it therefore never reaches.
    Mesh m;
    auto id = [&](uint32_t j, uint32_t a, uint32_t b) -> uint32_t {
        if (a == 0 && b == 0) return 0;
        if (a == 0) return 1 + ((j + 1) % n) * 12 + (b - 1) * 4;
        return 1 + j * 12 + (a - 1) * 4 + b;
    };
    m.positions.resize(1 + 12 * size_t(n));
    for (size_t v = 0; v < m.positions.size(); ++v) m.positions[v] = glm::dvec3(double(v), 0, 0);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t a = 0; a < 3; ++a)
            for (uint32_t b = 0; b < 3; ++b) {
                for (uint32_t v : {id(j, a, b), id(j, a + 1, b), id(j, a + 1, b + 1), id(j, a, b + 1)})
                    m.faceVertices.push_back(v);
                m.faceOffsets.push_back(static_cast<uint32_t>(m.faceVertices.size()));
            }
    Warnings warnings;
    SchemeOptions options;
    TablesOptions opts;
    opts.depth = static_cast<int>(K);
    opts.irregularLevels = 0;
    const Tables t = buildTables(m, options, opts, warnings);
    Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
    Sharpness sharp = baseSharpness(topo, m.tags, options.boundary, warnings);
    const Level L0 = makeBaseLevel(std::move(topo), std::move(sharp));
    int corner = -1;
    uint32_t valence = 0;
    std::vector<uint32_t> support;
    if (!smoothSupport(L0, 0, corner, valence, support) || corner != 0 || valence != n)
        throw std::logic_error("irregular basis: the generated valence-" + std::to_string(n) +
                                             " mesh has no smooth support");
    IrregularBasis basis;
    basis.valence = n;
    basis.levels = K;
    const size_t M = support.size();
    basis.weights.assign(size_t(K) * 3 * 16 * M, 0.0f);
    std::vector<uint8_t> filled(size_t(K) * 3, 0);
    std::vector<uint8_t> inSupport(m.vertexCount(), 0);
    for (uint32_t v : support) inSupport[v] = 1;
    // The tables are linear in the control points: unit points (three at once, one per
    // coordinate) give each control point's weights.
    std::vector<glm::dvec3> control(m.vertexCount());
    for (size_t v0 = 0; v0 < m.vertexCount(); v0 += 3) {
        std::fill(control.begin(), control.end(), glm::dvec3(0.0));
        for (int c = 0; c < 3 && v0 + c < m.vertexCount(); ++c) control[v0 + c][c] = 1;
        const std::vector<glm::dvec3> V = evaluateVertices(t, control);
        for (const Patch& p : t.patches) {
            if (p.ptex != 0 || p.level < 1) continue;
            const double size = std::ldexp(1.0, -int(p.level));
            const int q = (p.u0 > 0 ? 1 : 0) + (p.v0 > 0 ? 2 : 0); // 1, 3 or 2 (both)
            const int quadrant = q == 1 ? 1 : q == 3 ? 2 : 3;
            if (q == 0 || p.size != size || (p.u0 != 0 && p.u0 != size) || (p.v0 != 0 && p.v0 != size))
                throw std::logic_error("irregular basis: unexpected sub-patch");
            const size_t block = (size_t(p.level - 1) * 3 + size_t(quadrant - 1));
            filled[block] = 1;
            glm::dvec3 P[4][4];
            gatherControlPoints(p, V, P);
            for (int c = 0; c < 3 && v0 + c < m.vertexCount(); ++c) {
                const uint32_t v = uint32_t(v0 + c);
                for (int j = 0; j < 16; ++j) {
                    const double w = P[j % 4][j / 4][c];
                    if (!inSupport[v]) {
                        if (std::abs(w) > 1e-12)
                            throw std::logic_error("irregular basis: support too small");
                        continue;
                    }
                    const size_t i = size_t(std::find(support.begin(), support.end(), v) - support.begin());
                    basis.weights[block * 16 * M + size_t(j) * M + i] = static_cast<float>(w);
                }
            }
        }
    }
    if (std::find(filled.begin(), filled.end(), 0) != filled.end())
        throw std::logic_error("irregular basis: a sub-patch is missing");
    return basis;
}

} // namespace limn
