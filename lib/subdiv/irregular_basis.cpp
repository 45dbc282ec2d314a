#include "subdiv/irregular_basis.h"

#include "base/error.h"
#include "base/warnings.h"
#include "mesh/mesh.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables.h"

#include <algorithm>
#include <array>
#include <bit>
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
        if (ev >= 0 || n < 3 || n > kMaxBasisValence) return false;
        ev = k;
        valence = n;
    }
    if (ev < 0) return false;
    corner = ev;
    support.clear();
    // This runs once per irregular face of the last level (hundreds of thousands on a scanned
    // mesh), so it avoids searching: the support's vertices go into a small open-addressing set
    // (at most half full), and faces met a second time are skipped, as they add no vertex. Fan j
    // (j >= 1) starts with f and then the face across edge (j-1, j), the last face of fan j-1;
    // fan 3 ends with the face across edge (3, 0), the second of fan 0.
    const size_t M = 2 * size_t(valence) + 8;
    size_t slots = 16;
    while (slots < 2 * M) slots *= 2;
    std::array<uint32_t, 512> set; // 2 M <= 272 for valences up to kMaxBasisValence
    std::fill_n(set.begin(), slots, kNone);
    const int bits = std::countr_zero(slots);
    auto insert = [&](uint32_t v) { // false if already there
        for (size_t i = (v * 0x9E3779B1u) >> (32 - bits);; i = (i + 1) & (slots - 1)) {
            if (set[i] == v) return false;
            if (set[i] == kNone) {
                set[i] = v;
                return true;
            }
        }
    };
    for (int j = 0; j < 4; ++j) {
        const uint32_t h0 = T.faceHalfedge(f) + (fr.rotation + ev + j) % 4;
        uint32_t h = h0;
        for (int step = 0;; ++step) {
            const uint32_t hn = T.rotateCCW(h);
            if (hn == kNone) return false;
            const bool seen = (j > 0 && step < 2) || (j == 3 && hn == h0);
            if (!seen) {
                const uint32_t g = T.face(h);
                if (T.faceSize(g) != 4 || L.noLimit[g]) return false;
                uint32_t x = h;
                for (int c = 0; c < 4; ++c, x = T.next(x)) {
                    if (L.edgeSharpness[T.edge(x)] != 0) return false;
                    const uint32_t v = T.vertex(x);
                    if (!insert(v)) continue;
                    if (L.vertexSharpness[v] != 0 || support.size() == M) return false;
                    support.push_back(v);
                }
            }
            h = hn;
            if (h == h0) break;
        }
    }
    return support.size() == M;
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
    // Sharp rim corners: each rim corner (one face) is then a regular corner patch instead of an
    // irregular face refined K levels deep like the centre. The rim's rules never reach face 0's
    // sub-patches (the checks below would throw), so the weights are the same to the bit.
    options.boundary = BoundaryRule::EdgeAndCorner;
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
    // The tables are linear in the control points, and each coordinate is evaluated on its own:
    // unit points, three support points at a time (one per coordinate), give each support point's
    // weights. A last pass puts 1 on every other point: Catmull-Clark's smooth rules have no
    // negative weights, so a zero there means that none of them reaches face 0's sub-patches.
    const size_t passes = (M + 2) / 3;
    std::vector<glm::dvec3> control(m.vertexCount());
    for (size_t pass = 0; pass <= passes; ++pass) {
        std::fill(control.begin(), control.end(), glm::dvec3(0.0));
        if (pass == passes) {
            for (size_t v = 0; v < control.size(); ++v) control[v][0] = 1;
            for (uint32_t v : support) control[v][0] = 0;
        } else {
            for (size_t c = 0; c < 3 && 3 * pass + c < M; ++c) control[support[3 * pass + c]][int(c)] = 1;
        }
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
            for (int j = 0; j < 16; ++j) {
                if (pass == passes) {
                    if (std::abs(P[j % 4][j / 4][0]) > 1e-12)
                        throw std::logic_error("irregular basis: support too small");
                    continue;
                }
                for (size_t c = 0; c < 3 && 3 * pass + c < M; ++c)
                    basis.weights[block * 16 * M + size_t(j) * M + 3 * pass + c] =
                        static_cast<float>(P[j % 4][j / 4][int(c)]);
            }
        }
    }
    if (std::find(filled.begin(), filled.end(), 0) != filled.end())
        throw std::logic_error("irregular basis: a sub-patch is missing");
    return basis;
}

} // namespace limn
