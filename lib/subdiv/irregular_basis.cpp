#include "subdiv/irregular_basis.h"

#include "base/error.h"
#include "base/warnings.h"
#include "mesh/mesh.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables_build.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
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

Mesh irregularBasisMesh(uint32_t n) {
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
    return m;
}

IrregularBasis buildIrregularBasis(uint32_t n, uint32_t K) {
    if (n < 3 || K < 1 || K > uint32_t(kMaxDepth))
        throw std::logic_error("irregular basis: valence or levels out of range");
    const Mesh m = irregularBasisMesh(n);
    Warnings warnings;
    const SchemeOptions options;
    // The table builder's refinement under face 0, one level deep: it refines the faces around
    // face 0's corners (the builder's isolation, oneRing); three children of face 0 are band 1's
    // sub-patches, the fourth (at the extraordinary vertex) has a support like face 0's. The rows
    // that make that level's support and sub-patches from face 0's support are kept as a program
    // (each row's entries in its stencil's order) and run again on each deeper band's support, in
    // smoothSupport's order: the local subdivision is the same at every level (Stam 1998), and so,
    // entry by entry, are the stencils. That gives the bits of refining every level as the tables
    // do: checked for every valence 3 to 64 at K = 16 (docs/irregular.md), and here by
    // IrregularBasis.WeightsAreThoseOfTheWholeTables. (kRefinedLevels > 1 would take the program
    // from a deeper level; the bits are the same.)
    constexpr uint32_t kRefinedLevels = 1;
    const uint32_t R = std::min(K, kRefinedLevels);
    AdaptiveLevels r;
    r.N = r.D = R;
    {
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        Sharpness sharp = baseSharpness(topo, m.tags, options.boundary, warnings);
        r.levels.push_back(makeBaseLevel(std::move(topo), std::move(sharp)));
    }
    r.stencils.resize(1);
    r.patchSets.emplace_back(r.levels[0].topo.faceCount(), 0);
    std::vector<uint32_t> ptexBase(r.levels[0].topo.faceCount());
    for (uint32_t f = 0; f < ptexBase.size(); ++f) ptexBase[f] = r.levels[0].frames[f].ptex;
    std::vector<uint32_t> centres{0}; // face 0's descendant at the extraordinary vertex, per level
    for (uint32_t l = 0; l < R; ++l) {
        const uint32_t centre = centres.back();
        std::vector<uint8_t> T(r.levels[l].topo.faceCount(), 0);
        T[centre] = 1;
        LevelStencils st;
        Level child = refineLevel(r.levels[l], oneRing(r.levels[l].topo, T), options, ptexBase, st);
        std::vector<uint8_t> P(child.topo.faceCount(), 0);
        uint32_t next = kNone;
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf) {
            if (child.faceParent[cf] != centre) continue;
            if (child.frames[cf].u0 == 0 && child.frames[cf].v0 == 0)
                next = cf;
            else
                P[cf] = 1;
        }
        if (next == kNone) throw std::logic_error("irregular basis: no face at the extraordinary vertex");
        r.levels.push_back(std::move(child));
        r.stencils.push_back(std::move(st));
        r.patchSets.push_back(std::move(P));
        centres.push_back(next);
    }
    // The support of each level's centre, in smoothSupport's order (level 0: face 0's, the
    // basis's columns).
    std::vector<std::vector<uint32_t>> supports(R + 1);
    for (uint32_t l = 0; l <= R; ++l) {
        int corner = -1;
        uint32_t valence = 0;
        if (!smoothSupport(r.levels[l], centres[l], corner, valence, supports[l]) || corner != 0 ||
            valence != n)
            throw std::logic_error("irregular basis: the generated valence-" + std::to_string(n) +
                                   " mesh has no smooth support at level " + std::to_string(l));
    }
    const std::vector<uint32_t>& support = supports[0];
    IrregularBasis basis;
    basis.valence = n;
    basis.levels = K;
    const size_t M = support.size();
    basis.weights.assign(size_t(K) * 3 * 16 * M, 0.0f);
    std::vector<uint8_t> filled(size_t(K) * 3, 0);
    // Rows of W = M + 1 values rounded up to even: the columns are summed two at a time (packed
    // doubles, below), the pad column staying 0.
    const size_t W = (M + 2) & ~size_t(1);
    // Face 0's sub-patches (level, quadrant, control points), and the vertices they read.
    struct SubPatch {
        uint32_t level;
        size_t quadrant;
        Patch patch;
    };
    std::vector<SubPatch> subPatches;
    std::vector<std::vector<uint8_t>> needed(R + 1);
    for (uint32_t l = 0; l <= R; ++l) needed[l].assign(r.levels[l].topo.vertexCount(), 0);
    for (uint32_t l = 1; l <= R; ++l) {
        const Level& L = r.levels[l];
        std::vector<uint32_t> identity(L.topo.vertexCount());
        for (uint32_t v = 0; v < identity.size(); ++v) identity[v] = v;
        for (uint32_t f = 0; f < r.patchSets[l].size(); ++f) {
            if (!r.patchSets[l][f] || L.frames[f].ptex != 0) continue;
            const Patch p = gatherPatch(L, f, 0, identity, kNone);
            const double size = std::ldexp(1.0, -int(p.level));
            const int q = (p.u0 > 0 ? 1 : 0) + (p.v0 > 0 ? 2 : 0); // 1, 3 or 2 (both)
            const int quadrant = q == 1 ? 1 : q == 3 ? 2 : 3;
            if (q == 0 || p.size != size || (p.u0 != 0 && p.u0 != size) ||
                (p.v0 != 0 && p.v0 != size) || p.boundary != 0)
                throw std::logic_error("irregular basis: unexpected sub-patch");
            subPatches.push_back({l, size_t(quadrant - 1), p});
            for (uint32_t v : p.cv) needed[l][v] = 1;
        }
    }
    // The deeper bands' input, and where level R's rows read theirs.
    for (uint32_t v : supports[R]) needed[R][v] = 1;
    for (uint32_t v : supports[R - 1]) needed[R - 1][v] = 1;
    for (uint32_t l = R; l >= 1; --l) {
        const Level& L = r.levels[l];
        const LevelStencils& st = r.stencils[l];
        auto mark = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                        const std::vector<StencilEntry>& entries) {
            for (uint32_t i = 0; i < count; ++i)
                if (needed[l][first + i])
                    for (uint32_t k = start[i]; k < start[i + 1]; ++k)
                        (entries[k].fromFacePoint ? needed[l] : needed[l - 1])[entries[k].index] = 1;
        };
        mark(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
        mark(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
        for (uint32_t i = 0; i < L.facePointCount; ++i)
            if (needed[l][i])
                for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k) needed[l - 1][st.faceVertices[k]] = 1;
    }
    // The refinement is linear in the control points: every needed vertex is evaluated for M + 1
    // control meshes at once, unit points on each support point (giving its weights), and 1 on
    // every other point (column M): Catmull-Clark's smooth rules have no negative weights, so a
    // zero there means that none of them reaches face 0's sub-patches. Each column is computed
    // as evaluateVertices computes the tables (the float weights, in the stencils' order).
    // Each level's needed vertices (at level 0 with the support) get consecutive rows of W
    // values; no other vertex is read.
    for (uint32_t v : support) needed[0][v] = 1;
    std::vector<std::vector<uint32_t>> row(R + 1);
    std::vector<std::vector<double>> V(R + 1);
    for (uint32_t l = 0; l <= R; ++l) {
        row[l].assign(needed[l].size(), kNone);
        uint32_t rows = 0;
        for (size_t v = 0; v < needed[l].size(); ++v)
            if (needed[l][v]) row[l][v] = rows++;
        V[l].assign(size_t(rows) * W, 0.0);
    }
    for (size_t v = 0; v < needed[0].size(); ++v)
        if (needed[0][v]) V[0][size_t(row[0][v]) * W + M] = 1;
    for (size_t i = 0; i < M; ++i) {
        V[0][size_t(row[0][support[i]]) * W + i] = 1;
        V[0][size_t(row[0][support[i]]) * W + M] = 0;
    }
    // A level's rows as a program: each row the sum of its entries in the stencil's order,
    // reading the previous level's rows or this level's (face points, read by edge and vertex
    // points), then divided by `divisor` (face points; 0: not divided).
    struct Entry {
        uint32_t source;
        bool current;
        double weight;
    };
    struct Row {
        uint32_t target, first, last; // entries[first, last)
        double divisor;
    };
    std::vector<Entry> entries;
    std::vector<Row> program;
    auto buildProgram = [&](uint32_t l) {
        entries.clear();
        program.clear();
        const Level& L = r.levels[l];
        const LevelStencils& st = r.stencils[l];
        for (uint32_t i = 0; i < L.facePointCount; ++i) {
            if (!needed[l][i]) continue;
            const uint32_t first = uint32_t(entries.size());
            for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k)
                entries.push_back({row[l - 1][st.faceVertices[k]], false, 1.0});
            program.push_back({row[l][i], first, uint32_t(entries.size()),
                               double(st.faceStart[i + 1] - st.faceStart[i])});
        }
        auto rows = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                        const std::vector<StencilEntry>& stencil) {
            for (uint32_t i = 0; i < count; ++i) {
                if (!needed[l][first + i]) continue;
                const uint32_t begin = uint32_t(entries.size());
                for (uint32_t k = start[i]; k < start[i + 1]; ++k) {
                    const StencilEntry& e = stencil[k];
                    entries.push_back({e.fromFacePoint ? row[l][e.index] : row[l - 1][e.index],
                                       e.fromFacePoint, double(static_cast<float>(e.weight))});
                }
                program.push_back({row[l][first + i], begin, uint32_t(entries.size()), 0.0});
            }
        };
        rows(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
        rows(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
    };
    // Two columns at a time (GCC's packed doubles: SSE2, NEON): each column is still its own
    // product and sum in the stencil's order, so every bit is that of one column at a time.
    using Pair = double __attribute__((vector_size(16)));
    auto load = [](const double* p) {
        Pair x;
        std::memcpy(&x, p, sizeof x);
        return x;
    };
    auto store = [](double* p, Pair x) { std::memcpy(p, &x, sizeof x); };
    auto run = [&](const std::vector<double>& prev, std::vector<double>& cur) {
        for (const Row& x : program) {
            double* out = &cur[size_t(x.target) * W];
            for (uint32_t k = x.first; k < x.last; ++k) {
                const Entry& e = entries[k];
                const double* in = &(e.current ? cur : prev)[size_t(e.source) * W];
                if (x.divisor != 0) {
                    for (size_t c = 0; c < W; c += 2) store(out + c, load(out + c) + load(in + c));
                } else {
                    const Pair weight = {e.weight, e.weight};
                    for (size_t c = 0; c < W; c += 2)
                        store(out + c, load(out + c) + weight * load(in + c));
                }
            }
            if (x.divisor != 0) {
                const Pair divisor = {x.divisor, x.divisor};
                for (size_t c = 0; c < W; c += 2) store(out + c, load(out + c) / divisor);
            }
        }
    };
    for (uint32_t l = 1; l <= R; ++l) {
        buildProgram(l); // the last one, level R's, is kept for the deeper bands
        run(V[l - 1], V[l]);
    }
    auto readSubPatches = [&](uint32_t band, const std::vector<double>& values) {
        for (const SubPatch& sp : subPatches) {
            if (sp.level != std::min(band, R)) continue;
            const size_t block = size_t(band - 1) * 3 + sp.quadrant;
            filled[block] = 1;
            for (int j = 0; j < 16; ++j) {
                const double* P = &values[size_t(row[sp.level][sp.patch.cv[j]]) * W];
                if (std::abs(P[M]) > 1e-12) throw std::logic_error("irregular basis: support too small");
                for (size_t i = 0; i < M; ++i)
                    basis.weights[block * 16 * M + size_t(j) * M + i] = static_cast<float>(P[i]);
            }
        }
    };
    for (uint32_t band = 1; band <= R; ++band) readSubPatches(band, V[band]);
    if (K > R) {
        // The program reads level R - 1 in that level's rows; remap them to the support's order,
        // which is where the deeper levels put their input.
        std::vector<uint32_t> inputOf(V[R - 1].size() / W, kNone);
        for (size_t i = 0; i < M; ++i) inputOf[row[R - 1][supports[R - 1][i]]] = uint32_t(i);
        for (Entry& e : entries)
            if (!e.current) {
                if (inputOf[e.source] == kNone)
                    throw std::logic_error("irregular basis: a row reads outside the support");
                e.source = inputOf[e.source];
            }
        std::vector<double> input(M * W), output(V[R].size());
        for (uint32_t band = R + 1; band <= K; ++band) {
            const std::vector<double>& from = band == R + 1 ? V[R] : output;
            for (size_t i = 0; i < M; ++i)
                std::memcpy(&input[i * W], &from[size_t(row[R][supports[R][i]]) * W], W * sizeof(double));
            std::fill(output.begin(), output.end(), 0.0);
            run(input, output);
            readSubPatches(band, output);
        }
    }
    if (std::find(filled.begin(), filled.end(), 0) != filled.end())
        throw std::logic_error("irregular basis: a sub-patch is missing");
    return basis;
}

} // namespace limn
