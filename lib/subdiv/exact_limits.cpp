#include "subdiv/exact_limits.h"

#include "subdiv/tables.h"

#include <opensubdiv/sdc/crease.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace limn {

namespace {

using OpenSubdiv::Sdc::Crease;

bool semiSharp(float s) { return s > 0 && s < Crease::SHARPNESS_INFINITE; }

// A semi-sharp feature at the vertex has not decayed: the rules change at a later level, so no
// mask of this level is the limit (opensubdiv.md, "Exact vertex limits").
bool undecayed(const Level& L, const VertexNeighborhood& hood) {
    if (semiSharp(L.vertexSharpness[hood.vertex])) return true;
    for (uint32_t e : hood.edges)
        if (semiSharp(L.edgeSharpness[e])) return true;
    return false;
}

using Sparse = std::map<uint32_t, double>;

// Levels past N a semi-sharp vertex may be refined (sharpness is below 10 when finite).
constexpr size_t kMaxExtraLevels = 12;

// One extra level around the vertices that need it, and where its vertices came from.
struct Extra {
    Level level;
    LevelStencils stencils;
    std::vector<uint32_t> faceChild, edgeChild, vertexChild; // parent element -> child vertex
};

// A combination of level-l vertices rewritten over level l-1 vertices through level l's
// stencils (face points are averages of their face's vertices).
void expandOnce(const Level& C, const LevelStencils& st, const Sparse& in, Sparse& out) {
    out.clear();
    auto facePoint = [&](uint32_t row, double w) {
        const uint32_t b = st.faceStart[row], e = st.faceStart[row + 1];
        const double k = w / double(e - b);
        for (uint32_t i = b; i < e; ++i) out[st.faceVertices[i]] += k;
    };
    auto rows = [&](uint32_t row, double w, const std::vector<uint32_t>& start,
                    const std::vector<StencilEntry>& entries) {
        for (uint32_t i = start[row]; i < start[row + 1]; ++i) {
            const StencilEntry& s = entries[i];
            if (s.fromFacePoint)
                facePoint(s.index, w * s.weight);
            else
                out[s.index] += w * s.weight;
        }
    };
    const uint32_t fp = C.facePointCount, ep = C.edgePointCount;
    for (const auto& [v, w] : in) {
        if (v < fp)
            facePoint(v, w);
        else if (v < fp + ep)
            rows(v - fp, w, st.edgeStart, st.edgeEntries);
        else
            rows(v - fp - ep, w, st.vertexStart, st.vertexEntries);
    }
}

// `list` at level N + levels, rewritten over level-N vertices.
std::vector<WeightedPoint> compose(const std::vector<Extra>& extra, size_t levels,
                                   const std::vector<WeightedPoint>& list) {
    Sparse a, b;
    for (const auto& wp : list) a[wp.vertex] += wp.weight;
    for (size_t j = levels; j-- > 0;) {
        expandOnce(extra[j].level, extra[j].stencils, a, b);
        std::swap(a, b);
    }
    double largest = 0;
    for (const auto& [v, w] : a) largest = std::max(largest, std::abs(w));
    std::vector<WeightedPoint> out;
    // Cancellation leaves weights of order 1e-17 where the exact weight is 0: drop them.
    for (const auto& [v, w] : a)
        if (std::abs(w) > 1e-13 * largest) out.push_back({v, w});
    return out;
}

// The local subdivision matrix S of a vertex whose rule is stable (no semi-sharpness): its
// one-ring at level l+1 as a linear function of its one-ring at level l (v, the far ends of its
// edges, the diagonals of its faces), from the stencils of the level after it. Limit masks are
// left eigenvectors of S (Halstead et al. 1993, section 4).
struct LocalMatrix {
    std::vector<uint32_t> list;
    std::map<uint32_t, size_t> column;
    std::vector<double> S;
    std::vector<size_t> rowStart;                    // S's nonzero entries, row by row
    std::vector<std::pair<size_t, double>> entries;  // (column, value)
    size_t n = 0;

    // False where the one-ring is degenerate (a vertex repeated in it) or not closed.
    bool build(const Extra& next, const VertexNeighborhood& hood) {
        list = {hood.vertex};
        list.insert(list.end(), hood.ringVertex.begin(), hood.ringVertex.end());
        list.insert(list.end(), hood.diagonal.begin(), hood.diagonal.end());
        n = list.size();
        column.clear();
        for (size_t i = 0; i < n; ++i)
            if (list[i] == kNone || !column.emplace(list[i], i).second) return false;
        // The child one-ring in the same order: the vertex's child, the children of its edges
        // and the points of its faces.
        std::vector<uint32_t> childList = {next.vertexChild[hood.vertex]};
        for (uint32_t e : hood.edges) childList.push_back(next.edgeChild[e]);
        for (uint32_t f : hood.faces) childList.push_back(next.faceChild[f]);
        S.assign(n * n, 0.0);
        Sparse row, out;
        for (size_t r = 0; r < n; ++r) {
            if (childList[r] == kNone) return false;
            row = {{childList[r], 1.0}};
            expandOnce(next.level, next.stencils, row, out);
            for (const auto& [v, w] : out) {
                auto it = column.find(v);
                if (it == column.end()) return false;
                S[r * n + it->second] += w;
            }
        }
        // S's rows are stencils (a face point reads 4 values, an edge point about 6): products
        // go over the nonzero entries only, in the same order, so every sum is the dense one
        // less its exact zeros. A cone point of 64 faces iterates 64 times; dense, that was 9 s.
        rowStart.assign(1, 0);
        entries.clear();
        for (size_t r = 0; r < n; ++r) {
            for (size_t c = 0; c < n; ++c)
                if (S[r * n + c] != 0) entries.push_back({c, S[r * n + c]});
            rowStart.push_back(entries.size());
        }
        return true;
    }
    std::vector<double> times(const std::vector<double>& x) const { // x S
        std::vector<double> y(n, 0.0);
        for (size_t r = 0; r < n; ++r)
            if (x[r] != 0)
                for (size_t k = rowStart[r]; k < rowStart[r + 1]; ++k)
                    y[entries[k].first] += x[r] * entries[k].second;
        return y;
    }
    bool toLocal(const std::vector<WeightedPoint>& wp, std::vector<double>& x) const {
        x.assign(n, 0.0);
        for (const auto& p : wp) {
            auto it = column.find(p.vertex);
            if (it == column.end()) return false;
            x[it->second] += p.weight;
        }
        return true;
    }
    void fromLocal(const std::vector<double>& x, std::vector<WeightedPoint>& wp) const {
        double largest = 0;
        for (double w : x) largest = std::max(largest, std::abs(w));
        wp.clear();
        for (size_t i = 0; i < n; ++i)
            if (std::abs(x[i]) > 1e-13 * largest) wp.push_back({list[i], x[i]});
    }
    // Position: l S^k converges to the left eigenvector of eigenvalue 1 with sum 1 (S 1 = 1,
    // every other eigenvalue is below 1 in modulus), at the rate of the subdominant one.
    bool limitPosition(std::vector<double>& l) const {
        for (int it = 0; it < 5000; ++it) {
            std::vector<double> y = times(l);
            double d = 0;
            for (size_t i = 0; i < n; ++i) d = std::max(d, std::abs(y[i] - l[i]));
            l = std::move(y);
            if (d < 1e-16) return true;
        }
        return false;
    }
    // Zero-sum masks (differences of points) lose their eigenvalue-1 part exactly; rounding
    // brings it back and S amplifies it, so it is taken out against the limit mask l each step.
    void deflate(std::vector<double>& t, const std::vector<double>& l) const {
        double s = 0;
        for (double x : t) s += x;
        for (size_t i = 0; i < n; ++i) t[i] -= s * l[i];
    }
};

bool normalize(std::vector<double>& t) {
    double s = 0;
    for (double x : t) s += x * x;
    s = std::sqrt(s);
    if (!(s > 0)) return false;
    for (double& x : t) x /= s;
    return true;
}

double maxChange(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0;
    for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

// Darts and valence-2 vertices: one tangent plane, the left invariant subspace of the two
// largest eigenvalues below 1, found by subspace iteration from the closed-form tangents. The
// Gram-Schmidt step is triangular with a positive diagonal, so the pair keeps the orientation
// the closed-form masks gave it (tangent1 x tangent2 outward). `m` is replaced on success.
bool tangentPlaneMasks(const LocalMatrix& M, const VertexNeighborhood& hood, LimitMasks& m) {
    std::vector<double> l, t1, t2;
    if (!M.toLocal(m.position, l) || !M.toLocal(m.tangent1, t1) || !M.toLocal(m.tangent2, t2))
        return false;
    if (!M.limitPosition(l)) return false;
    auto orthonormalize = [&]() {
        M.deflate(t1, l);
        M.deflate(t2, l);
        if (!normalize(t1)) return false;
        double d = 0;
        for (size_t i = 0; i < M.n; ++i) d += t1[i] * t2[i];
        for (size_t i = 0; i < M.n; ++i) t2[i] -= d * t1[i];
        return normalize(t2);
    };
    if (!orthonormalize()) return false;
    bool exact = true;
    if (hood.faces.size() == 2 && !hood.boundary) {
        // Valence 2: S has the eigenvalues 1/4, 1/4 and -1/4 (equal modulus, so no iteration
        // separates them). For the smooth rule, e_0 - e_1 and d_0 - d_1 span the eigenvalue
        // 1/4 (the modes odd under swapping the two faces); their cross product is the sum of
        // the two faces' normals at v. The -1/4 mode (even) generally leaves that plane, so the
        // surface has no tangent plane there and the point stays flagged approximate.
        std::vector<double> a(M.n, 0.0), b(M.n, 0.0);
        a[1] = 1, a[2] = -1, b[3] = 1, b[4] = -1;
        std::vector<double> sa = M.times(a), sb = M.times(b);
        double r = 0;
        for (size_t i = 0; i < M.n; ++i)
            r = std::max({r, std::abs(sa[i] - a[i] / 4), std::abs(sb[i] - b[i] / 4)});
        if (r > 1e-12) return false; // not the smooth valence-2 matrix (a dart)
        t1 = a, t2 = b;
        exact = false;
    } else {
        bool converged = false;
        for (int it = 0; it < 5000 && !converged; ++it) {
            std::vector<double> p1 = t1, p2 = t2;
            t1 = M.times(t1);
            t2 = M.times(t2);
            if (!orthonormalize()) return false;
            converged = std::max(maxChange(t1, p1), maxChange(t2, p2)) < 1e-14;
        }
        if (!converged) return false;
    }
    M.fromLocal(l, m.position);
    M.fromLocal(t1, m.tangent1);
    M.fromLocal(t2, m.tangent2);
    m.exact = exact;
    return true;
}

// Corners whose sector has more than one face, and cone points (a corner on a ring no sharp
// edge cuts): the fixed vertex makes a mode of the faces' interior grow faster than the sharp
// edges' directions (on a cone the rotation-invariant mode, eigenvalue 0.6545 against 1/2 for
// any valence), so the surface has no tangent plane at v and its normal depends on the face
// and the direction it is approached from. Each face gets its own limit point with the
// normal approached along the face's diagonal (where the drawn corner's neighbours are): the
// limit of the face's normal (d_i - v) x (e_{i+1} - e_i) under subdivision, each factor
// iterated by S to the dominant mode it contains. Position: v (the corner mask, exact).
bool faceNormalMasks(const LocalMatrix& M, const VertexNeighborhood& hood, uint32_t face,
                     LimitMasks& m) {
    std::vector<double> l, t1(M.n, 0.0), t2(M.n, 0.0);
    if (!M.toLocal(m.position, l) || !M.limitPosition(l)) return false;
    const size_t E = hood.edges.size();
    t1[1 + E + face] = 1, t1[0] = -1;                // d_i - v
    t2[1 + (face + 1) % E] = 1, t2[1 + face] = -1;   // e_{i+1} - e_i
    bool converged = false;
    for (int it = 0; it < 5000 && !converged; ++it) {
        std::vector<double> p1 = t1, p2 = t2;
        for (auto* t : {&t1, &t2}) {
            *t = M.times(*t);
            M.deflate(*t, l);
            if (!normalize(*t)) return false;
        }
        converged = std::max(maxChange(t1, p1), maxChange(t2, p2)) < 1e-13;
    }
    if (!converged) return false;
    M.fromLocal(l, m.position);
    M.fromLocal(t1, m.tangent1);
    M.fromLocal(t2, m.tangent2);
    m.exact = true;
    return true;
}

// Corner sectors that faceNormalMasks handles (the rest have exact closed forms).
bool splitPerFace(VertexRule rule, const Sector& sector) {
    return rule == VertexRule::Corner && (sector.closed || sector.faceCount > 1);
}

// Stable rules whose closed-form masks are not eigenvectors of the local subdivision matrix:
// darts, valence-2 vertices, and corners with a sector of more than one face or none (cones).
bool needsEigen(const VertexNeighborhood& hood, VertexRule rule, const std::vector<float>& edgeSharpness) {
    if (rule == VertexRule::Dart) return true;
    if (rule == VertexRule::Smooth) return !hood.boundary && hood.faces.size() == 2;
    if (rule == VertexRule::Corner)
        for (const Sector& s : vertexSectors(hood, rule, edgeSharpness))
            if (splitPerFace(rule, s)) return true;
    return false;
}

} // namespace

std::vector<VertexLimits> exactVertexLimits(const Level& LN, const std::vector<uint32_t>& vertices,
                                            const std::vector<uint8_t>& drawn,
                                            const SchemeOptions& options,
                                            const std::vector<uint32_t>& ptexBase) {
    std::vector<VertexLimits> out(vertices.size());
    VertexNeighborhood hood;
    LimitMasks masks;
    // Vertices whose masks need levels beyond N: their vertex and the descendant of each of
    // their level-N faces at the current level.
    struct Track {
        size_t index;
        uint32_t vertex;
        std::vector<uint32_t> faces;
        int eigenLevel = -1; // the extra level whose one-ring S maps from (waits for the next)
    };
    std::vector<Track> pending;
    // Fills out[i] from the masks of `L` (extra level `j`, 0 for level N itself) at vertex w.
    LocalMatrix M;
    auto finish = [&](Track& tr, const Level& L, size_t j, const std::vector<Extra>& extra,
                      const Extra* next) {
        VertexLimits& vl = out[tr.index];
        gatherNeighborhood(L.topo, tr.vertex, hood);
        const auto rule = static_cast<VertexRule>(L.vertexRule[tr.vertex]);
        const auto sectors = vertexSectors(hood, rule, L.edgeSharpness);
        const uint32_t k = static_cast<uint32_t>(hood.faces.size());
        // S is dense, (2k + 1)^2 doubles, and a cone point iterates it for each of its k faces,
        // each face's point a mask over the whole ring: O(k^2) memory. A hostile dart of 16,383
        // faces asked for 8.6 GB, a cone of 16,383 for 25 GB; a cone of 300 ran past a minute.
        // Beyond kMaxBasisValence faces (where irregular faces are drawn bilinear anyway) the
        // closed-form masks stay, one point per sector, flagged approximate and counted.
        const bool crowded = k > kMaxBasisValence;
        const bool local = next && !crowded && M.build(*next, hood);
        // Limit point of each ring face (its sector's, or its own where split per face).
        std::vector<uint8_t> pointOf(k, 0);
        vl.sectors.clear();
        auto add = [&]() {
            if (j) {
                masks.position = compose(extra, j, masks.position);
                masks.tangent1 = compose(extra, j, masks.tangent1);
                masks.tangent2 = compose(extra, j, masks.tangent2);
            }
            vl.sectors.push_back(masks);
            return static_cast<uint8_t>(std::min<size_t>(vl.sectors.size() - 1, 255));
        };
        for (uint32_t si = 0; si < sectors.size(); ++si) {
            const Sector& sector = sectors[si];
            limitMasks(hood, rule, sector, L.edgeSharpness, L.vertexSharpness[tr.vertex], masks);
            if (next && splitPerFace(rule, sector) && crowded) masks.exact = false;
            if (next && splitPerFace(rule, sector) && !crowded) {
                const LimitMasks closedForm = masks;
                for (uint32_t i = 0; i < sector.faceCount; ++i) {
                    const uint32_t f = (sector.firstFace + i) % k;
                    // Only faces drawn through their corners need their own point.
                    const auto at = std::find(tr.faces.begin(), tr.faces.end(), hood.faces[f]);
                    if (at == tr.faces.end() || !drawn[vl.ringFaces[size_t(at - tr.faces.begin())]])
                        continue;
                    masks = closedForm;
                    if (!local || !faceNormalMasks(M, hood, f, masks)) masks.exact = false;
                    pointOf[f] = add();
                }
                continue;
            }
            // Darts and valence 2 (a corner's other sectors have exact closed forms).
            if (next && rule != VertexRule::Corner && needsEigen(hood, rule, L.edgeSharpness) &&
                (!local || !tangentPlaneMasks(M, hood, masks)))
                masks.exact = false;
            const uint8_t p = add();
            for (uint32_t i = 0; i < sector.faceCount; ++i) pointOf[(sector.firstFace + i) % k] = p;
        }
        vl.ringSector.clear();
        for (uint32_t f : tr.faces) {
            uint32_t pos = uint32_t(std::find(hood.faces.begin(), hood.faces.end(), f) - hood.faces.begin());
            vl.ringSector.push_back(pointOf[pos]);
        }
    };
    const std::vector<Extra> none;
    for (size_t i = 0; i < vertices.size(); ++i) {
        const uint32_t v = vertices[i];
        gatherNeighborhood(LN.topo, v, hood);
        out[i].ringFaces = hood.faces;
        const auto rule = static_cast<VertexRule>(LN.vertexRule[v]);
        Track tr{i, v, hood.faces};
        if (undecayed(LN, hood) || needsEigen(hood, rule, LN.edgeSharpness))
            pending.push_back(std::move(tr));
        else
            finish(tr, LN, 0, none, nullptr);
    }

    std::vector<Extra> extra;
    while (!pending.empty()) {
        const size_t j = extra.size();
        const Level& L = j ? extra[j - 1].level : LN;
        // Decide at level N + j: still semi-sharp (refine), stable with closed-form masks
        // (finish), or stable but needing S (refine once more, finish at the next level).
        std::vector<Track> refine;
        for (Track& tr : pending) {
            if (tr.eigenLevel >= 0) {
                // S maps the one-ring of level N + eigenLevel to that of this level.
                const size_t e = size_t(tr.eigenLevel);
                const Level& at = e ? extra[e - 1].level : LN;
                finish(tr, at, e, extra, &extra[e]);
                continue;
            }
            gatherNeighborhood(L.topo, tr.vertex, hood);
            const auto rule = static_cast<VertexRule>(L.vertexRule[tr.vertex]);
            if (undecayed(L, hood) && j >= kMaxExtraLevels) {
                // Sharpness below 10 decays within 10 levels under either creasing method; this
                // only guards the loop. The masks then stay flagged approximate.
                finish(tr, L, j, extra, nullptr);
            } else if (undecayed(L, hood)) {
                refine.push_back(std::move(tr));
            } else if (needsEigen(hood, rule, L.edgeSharpness)) {
                tr.eigenLevel = int(j);
                refine.push_back(std::move(tr));
            } else {
                finish(tr, L, j, extra, nullptr);
            }
        }
        pending.clear();
        if (refine.empty()) break;
        // The vertices' faces: their children are the next level's one-ring of the vertex, and
        // everything its stencils read. Chaikin creasing also reads the sharpness of the edges
        // around the ring's far ends, so there the one-ring of those faces is refined too, as
        // tables.h isolates (their children then have complete neighbourhoods); uniform
        // creasing decrements each edge on its own (Sdc::Crease), and refining less is faster.
        std::vector<uint8_t> marked(L.topo.faceCount(), 0);
        for (const Track& tr : refine)
            for (uint32_t h : L.topo.vertexOutgoing(tr.vertex)) marked[L.topo.face(h)] = 1;
        Extra x;
        x.level = refineLevel(L,
                              options.creaseMethod == CreaseMethod::Uniform ? marked
                                                                            : oneRing(L.topo, marked),
                              options, ptexBase, x.stencils);
        const Level& C = x.level;
        x.faceChild.assign(L.topo.faceCount(), kNone);
        x.edgeChild.assign(L.topo.edgeCount(), kNone);
        x.vertexChild.assign(L.topo.vertexCount(), kNone);
        for (uint32_t c = 0; c < C.topo.vertexCount(); ++c) {
            const uint32_t p = C.vertexParent[c];
            switch (C.vertexOrigin[c]) {
            case VertexOrigin::Face: x.faceChild[p] = c; break;
            case VertexOrigin::Edge: x.edgeChild[p] = c; break;
            case VertexOrigin::Vertex: x.vertexChild[p] = c; break;
            case VertexOrigin::Base: break;
            }
        }
        for (Track& tr : refine) {
            if (tr.eigenLevel >= 0) continue; // stays at its level; S reads this one
            const uint32_t w = x.vertexChild[tr.vertex];
            for (uint32_t& f : tr.faces)
                for (uint32_t h : C.topo.vertexOutgoing(w))
                    if (C.faceParent[C.topo.face(h)] == f) {
                        f = C.topo.face(h);
                        break;
                    }
            tr.vertex = w;
        }
        extra.push_back(std::move(x));
        pending = std::move(refine);
    }
    return out;
}

} // namespace limn
