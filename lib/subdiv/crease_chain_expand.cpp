// A decaying-crease chain as a basis of its face's own support (crease_basis.h,
// expandCreaseChain): the band programs run on weights, the boundary quadrants' phantoms folded
// in, then on to band K through the chain's end (docs/irregular-tables.md, "Chains in the tables").
#include "subdiv/crease_basis.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace limn {

namespace {

// Rows of weights are summed two columns at a time (GCC's packed doubles: SSE2, NEON), each column
// still its own products and sums in the program's order, so every bit is that of one column at
// a time (expandIrregularBasis's arithmetic; the web runtime computes one at a time).
using Pair = double __attribute__((vector_size(16)));
Pair load(const double* x) {
    Pair v;
    std::memcpy(&v, x, sizeof v);
    return v;
}
void store(double* x, Pair v) { std::memcpy(x, &v, sizeof v); }
Pair splat(double w) { return Pair{w, w}; }

// out += w * x over a row (W columns, even).
void addScaled(double* out, double w, const double* x, size_t W) {
    const Pair p = splat(w);
    for (size_t i = 0; i < W; i += 2) store(out + i, load(out + i) + p * load(x + i));
}

// Points as weights of the chain face's M level-N points: row r is [r * W, r * W + M) of a
// flat array, W being M rounded up to even (the pad column stays 0; one allocation per band,
// not per point).
struct WeightRows {
    size_t M = 0, W = 0;
    std::vector<double> w;
    // Zeroed rows (`zero` false: the caller writes every row).
    void assign(size_t rows, size_t m, bool zero = true) {
        M = m, W = (m + 1) & ~size_t(1);
        if (zero)
            w.assign(rows * W, 0.0);
        else
            w.resize(rows * W);
    }
    double* row(size_t r) { return w.data() + r * W; }
    const double* row(size_t r) const { return w.data() + r * W; }
    size_t rows() const { return W ? w.size() / W : 0; }
};

// a * x + b * y into out.
void combine(double* out, double a, const double* x, double b, const double* y, size_t W) {
    const Pair pa = splat(a), pb = splat(b);
    for (size_t i = 0; i < W; i += 2) store(out + i, pa * load(x + i) + pb * load(y + i));
}

// A patch's 16 control points (P[i + 4 j] = P_{i,j}) from a band's rows (kNone: a phantom),
// then gatherControlPoints' phantoms (columns first, then rows over all columns).
void patchWeights(const uint32_t* rows, uint8_t boundary, const WeightRows& values, WeightRows& P) {
    const size_t W = values.W;
    P.assign(16, values.M, false);
    for (int j = 0; j < 16; ++j)
        if (rows[j] != kNone)
            std::copy(values.row(rows[j]), values.row(rows[j]) + W, P.row(size_t(j)));
        else // a phantom, made below (a corner's from other phantoms, which start at 0)
            std::fill(P.row(size_t(j)), P.row(size_t(j)) + W, 0.0);
    auto at = [&](int i, int j) { return P.row(size_t(i + 4 * j)); };
    for (int j = 0; j < 4; ++j) {
        if (boundary & kBoundaryU0) combine(at(0, j), 2.0, at(1, j), -1.0, at(2, j), W);
        if (boundary & kBoundaryU1) combine(at(3, j), 2.0, at(2, j), -1.0, at(1, j), W);
    }
    for (int i = 0; i < 4; ++i) {
        if (boundary & kBoundaryV0) combine(at(i, 0), 2.0, at(i, 1), -1.0, at(i, 2), W);
        if (boundary & kBoundaryV1) combine(at(i, 3), 2.0, at(i, 2), -1.0, at(i, 1), W);
    }
}

// A uniform cubic B-spline's half (0: [0, 1/2], 1: [1/2, 1]) as its control points' weights.
constexpr double kHalf[2][4][4] = {
    {{0.5, 0.5, 0, 0}, {0.125, 0.75, 0.125, 0}, {0, 0.5, 0.5, 0}, {0, 0.125, 0.75, 0.125}},
    {{0.125, 0.75, 0.125, 0}, {0, 0.5, 0.5, 0}, {0, 0.125, 0.75, 0.125}, {0, 0, 0.5, 0.5}}};

// Half hu of patch P along u (the same for both halves along v: splitAlongV).
void splitAlongU(const WeightRows& P, int hu, WeightRows& T) {
    const size_t W = P.W;
    T.assign(16, P.M);
    for (int b = 0; b < 4; ++b)
        for (int i = 0; i < 4; ++i)
            for (int a = 0; a < 4; ++a)
                if (const double w = kHalf[hu][i][a]; w != 0)
                    addScaled(T.row(size_t(i + 4 * b)), w, P.row(size_t(a + 4 * b)), W);
}

// Quadrant (hu, hv) of patch P, separably: along u (T: splitAlongU(P, hu)), then along v.
void splitAlongV(const WeightRows& T, int hv, WeightRows& Q) {
    const size_t W = T.W;
    Q.assign(16, T.M);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            for (int b = 0; b < 4; ++b)
                if (const double w = kHalf[hv][j][b]; w != 0)
                    addScaled(Q.row(size_t(i + 4 * j)), w, T.row(size_t(i + 4 * b)), W);
}

} // namespace

bool expandCreaseChain(const CreaseChain& chain, uint32_t K, IrregularBasis& out, const IrregularBasis* endBasis,
                       bool weights) {
    out = IrregularBasis{};
    // A leaf end's K bands are all there is: within 2^-K of the corner evaluateIrregular blends
    // the corner's limit point and band K's sub-patches at their corners, as the quadtree's leaf
    // blends its corners' limit points (the same points to the float limit masks' rounding).
    if (chain.bands.empty() || chain.bands.size() > K || (chain.end == CreaseEnd::Leaf && chain.bands.size() != K))
        return false;
    if (chain.end == CreaseEnd::Regular && chain.bands.back().centreKind.crease) return false;
    const size_t M = chain.bands[0].support;
    out.levels = K;
    out.support = uint32_t(M);
    out.kinds.assign(size_t(K) * 3, CreaseBandKind{});
    if (!weights) { // the bands' kinds and the supports' sizes only
        size_t S = M;
        for (size_t b = 0; b < chain.bands.size(); ++b) {
            const CreaseBand& band = chain.bands[b];
            if (band.support != S) throw std::logic_error("crease chain: a band's support is not the last band's next");
            for (size_t q = 0; q < 3; ++q) out.kinds[b * 3 + q] = {0, band.kind[q].crease, band.kind[q].sharpness};
            S = band.program.nextSupport.size();
        }
        if (chain.end == CreaseEnd::Smooth && chain.bands.size() < K && S != 2 * size_t(chain.valence) + 8)
            throw std::logic_error("crease chain: a smooth end's support is not the basis's");
        return true;
    }
    // Every band's three patches are stored in order (band k, quadrant q at (3 (k - 1) + q) 16 M).
    out.weights.reserve(size_t(K) * 3 * 16 * M);
    auto storePatch = [&](uint32_t k, int q, const WeightRows& P) {
        if (out.weights.size() != (size_t(k - 1) * 3 + size_t(q)) * 16 * M)
            throw std::logic_error("crease chain: patches stored out of order");
        out.weights.resize(out.weights.size() + 16 * M);
        float* w = out.weights.data() + out.weights.size() - 16 * M;
        for (size_t j = 0; j < 16; ++j)
            for (size_t i = 0; i < M; ++i) w[j * M + i] = static_cast<float>(P.row(j)[i]);
    };
    WeightRows cur, rows, next, P, Q, T;
    cur.assign(M, M);
    for (size_t i = 0; i < M; ++i) cur.row(i)[i] = 1.0;
    uint32_t k = 0;
    // One band: program p over the support `cur` (as weights of the face's M points), its three
    // quadrants' patches stored with `kinds`, and the next band's support into `cur`.
    auto runBand = [&](const BasisProgram& p, const std::array<CreaseBandKind, 3>& kinds) {
        ++k;
        const size_t S = cur.rows();
        rows.assign(p.rows(), M, false);
        const size_t W = rows.W;
        for (uint32_t r = 0; r < p.rows(); ++r) {
            double* sum = rows.row(r);
            // The sums start at 0 (0 + w x, then + w x ...: the bits of summing into zeros).
            if (p.start[r] == p.start[r + 1]) std::fill(sum, sum + W, 0.0);
            for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
                const uint32_t src = p.source[e];
                if (src >= S + r) throw std::logic_error("crease chain: a row reads a later row");
                const double* x = src < S ? cur.row(src) : rows.row(src - S);
                const double w = p.averaged[r] ? 1.0 : double(p.weight[e]);
                if (e == p.start[r]) {
                    const Pair pw = splat(w), zero = splat(0.0);
                    for (size_t i = 0; i < W; i += 2) store(sum + i, zero + pw * load(x + i));
                } else {
                    addScaled(sum, w, x, W);
                }
            }
            if (p.averaged[r]) {
                const Pair n = splat(double(p.start[r + 1] - p.start[r]));
                for (size_t i = 0; i < W; i += 2) store(sum + i, load(sum + i) / n);
            }
        }
        for (int q = 0; q < 3; ++q) {
            patchWeights(p.controlRow.data() + 16 * q, kinds[size_t(q)].boundary, rows, P);
            storePatch(k, q, P);
            out.kinds[size_t(k - 1) * 3 + size_t(q)] = {0, kinds[size_t(q)].crease, kinds[size_t(q)].sharpness};
        }
        next.assign(p.nextSupport.size(), M, false);
        for (size_t i = 0; i < p.nextSupport.size(); ++i)
            std::copy(rows.row(p.nextSupport[i]), rows.row(p.nextSupport[i]) + W, next.row(i));
        std::swap(cur, next);
    };
    for (const CreaseBand& band : chain.bands) {
        if (band.support != cur.rows())
            throw std::logic_error("crease chain: a band's support is not the last band's next");
        runBand(band.program, band.kind);
        // `rows` still holds this band's rows.
        if (&band == &chain.bands.back() && chain.end == CreaseEnd::Regular)
            patchWeights(band.centreRow.data(), band.centreKind.boundary, rows, P);
    }
    if (chain.end == CreaseEnd::Regular) {
        // The corner's patch P, split: its quadrants 1..3 are band k's, its corner quadrant the next P.
        // Quadrants 1 (hu 1, hv 0), 3 (1, 1) and 2 (0, 1) in that order, then the corner (0, 0);
        // each half along u made once (T1, T0).
        WeightRows T0;
        for (++k; k <= K; ++k) {
            splitAlongU(P, 1, T);
            splitAlongV(T, 0, Q);
            storePatch(k, 0, Q);
            splitAlongV(T, 1, Q);
            storePatch(k, 1, Q);
            splitAlongU(P, 0, T0);
            splitAlongV(T0, 1, Q);
            storePatch(k, 2, Q);
            if (k == K) break; // no band below the last
            splitAlongV(T0, 0, Q);
            std::swap(P, Q);
        }
    } else if (k < K) {
        // Smooth: the crease has decayed and the corner's child is a smooth face of its valence,
        // whose bands are that valence's one-level program run again and again
        // (expandIrregularBasis) — here on the end's next support as weights of the face's own
        // points, so each weight is still rounded to float once (the program, not the basis's
        // float weights composed with the support: 4-5x fewer operations around a pole).
        IrregularBasis built;
        const IrregularBasis* found = endBasis;
        if (!found || found->program.rows() == 0) {
            built = buildIrregularBasis(chain.valence, K - k, false); // its program is what runs
            found = &built;
        }
        if (found->valence != chain.valence || found->configuration.boundary || !found->kinds.empty())
            throw std::logic_error("crease chain: a smooth end's basis is not its valence's");
        if (cur.rows() != found->supportSize())
            throw std::logic_error("crease chain: a smooth end's support is not the basis's");
        const std::array<CreaseBandKind, 3> smooth{};
        while (k < K) runBand(found->program, smooth);
    }
    return true;
}

} // namespace limn
