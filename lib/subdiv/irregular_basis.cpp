#include "subdiv/irregular_basis.h"

#include "base/error.h"
#include "base/warnings.h"
#include "mesh/mesh.h"
#include "subdiv/evaluate.h"
#include "subdiv/support_index.h"
#include "subdiv/tables_build.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace limn {

bool smoothSupport(const Level& L, uint32_t f, int& corner, uint32_t& valence, std::vector<uint32_t>& support,
                   bool featuresBeyondCorners) {
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
    // The stencils one level reads for the sub-patches and the next support are the corners'
    // vertex points and the edge points of the edges at the corners: only there do sharpness
    // and boundaries change them. Beyond (an edge or vertex of the support's rim) they are
    // plain inputs.
    const uint32_t h0f = T.faceHalfedge(f);
    const uint32_t corners[4] = {T.vertex(h0f), T.vertex(h0f + 1), T.vertex(h0f + 2), T.vertex(h0f + 3)};
    auto atCorner = [&](uint32_t v) { return v == corners[0] || v == corners[1] || v == corners[2] || v == corners[3]; };
    // Faces met a second time are skipped, as they add no vertex (SupportIndex: this runs once
    // per irregular face of the last level). Fan j (j >= 1) starts with f and then the face
    // across edge (j-1, j), the last face of fan j-1; fan 3 ends with the face across edge
    // (3, 0), the second of fan 0.
    const size_t M = 2 * size_t(valence) + 8;
    SupportIndex inSupport(M);
    for (int j = 0; j < 4; ++j) {
        const uint32_t h0 = T.faceHalfedge(f) + (fr.rotation + ev + j) % 4;
        uint32_t h = h0;
        for (int step = 0;; ++step) {
            const uint32_t hn = T.rotateCCW(h);
            if (hn == kNone) return false;
            const bool seen = (j > 0 && step < 2) || (j == 3 && hn == h0);
            if (!seen) {
                const uint32_t g = T.face(h);
                // A hole in the support is no feature: a hole only keeps its own face from being drawn,
                // and the rules (so the support's points, band after band) are those of a face that is there.
                if (T.faceSize(g) != 4) return false;
                uint32_t x = h;
                for (int c = 0; c < 4; ++c, x = T.next(x)) {
                    const uint32_t v = T.vertex(x);
                    if (L.edgeSharpness[T.edge(x)] != 0 &&
                        (!featuresBeyondCorners || atCorner(v) || atCorner(T.vertex(T.next(x)))))
                        return false;
                    if (!inSupport.insert(v, uint32_t(support.size())).second) continue;
                    if ((L.vertexSharpness[v] != 0 && (!featuresBeyondCorners || atCorner(v))) || support.size() == M)
                        return false;
                    support.push_back(v);
                }
            }
            h = hn;
            if (h == h0) break;
        }
    }
    return support.size() == M;
}

bool boundarySupport(const Level& L, uint32_t f, int& corner, BasisConfiguration& configuration,
                     std::vector<uint32_t>& support, std::vector<uint32_t>& signature) {
    const Topology& T = L.topo;
    if (T.faceSize(f) != 4 || L.noLimit[f]) return false;
    const FaceFrame& fr = L.frames[f];
    // A wall bounds a fan: a boundary edge, or an infinitely sharp one (the rules on its side read
    // no point across it: edge points are midpoints, vertex points of crease vertices the
    // (1, 6, 1) / 8 of the crease, as on a boundary).
    auto wall = [&](uint32_t e) { return T.edgeIsBoundary(e) || L.edgeSharpness[e] >= kInfiniteSharpness; };
    // The fan of corner halfedge hc: faces counter-clockwise from hc's to a wall, then clockwise
    // from it to a wall (rotateCCW crosses prev(h)'s edge, rotateCW h's); closed if it came round.
    std::vector<uint32_t> fan;
    auto fanOf = [&](uint32_t hc) {
        fan.assign(1, hc);
        for (uint32_t h = hc; !wall(T.edge(T.prev(h)));) {
            h = T.rotateCCW(h);
            if (h == hc) return true;
            if (fan.size() > kMaxBasisValence) return false;
            fan.push_back(h);
        }
        for (uint32_t h = hc; !wall(T.edge(h));) {
            h = T.rotateCW(h);
            if (fan.size() > kMaxBasisValence) return false;
            fan.push_back(h);
        }
        return false;
    };
    // Per corner: its walls (0, or 2 along a boundary or crease; the extraordinary one's sector
    // may be bounded by more, a corner), no other sharp edge (it would change the vertex's rule).
    int ev = -1;
    for (int k = 0; k < 4; ++k) {
        const uint32_t hc = T.faceHalfedge(f) + (fr.rotation + k) % 4, v = T.vertex(hc);
        if (T.vertexIsNonManifold(v)) return false;
        uint32_t walls = 0;
        for (uint32_t h : T.vertexOutgoing(v)) {
            for (uint32_t e : {T.edge(h), T.edge(T.prev(h))}) {
                if (e == T.edge(T.prev(h)) && !T.edgeIsBoundary(e)) continue; // each edge once
                if (wall(e))
                    ++walls;
                else if (L.edgeSharpness[e] != 0)
                    return false;
            }
        }
        if (walls == 1) return false; // a dart: the smooth rule across the whole vertex
        const bool closed = fanOf(hc);
        const uint32_t n = uint32_t(fan.size());
        if (L.vertexSharpness[v] == 0 && (walls == 0 ? closed && n == 4 : n == 2 && walls == 2)) continue; // regular
        if (ev >= 0 || walls == 0 || n < 1 || n > kMaxBasisValence) return false;
        if (L.vertexSharpness[v] != 0 && L.vertexSharpness[v] < kInfiniteSharpness) return false;
        ev = k;
        configuration = {n, true, 0, L.vertexSharpness[v] != 0 || walls > 2};
    }
    if (ev < 0) return false;
    corner = ev;
    const uint32_t h0 = T.faceHalfedge(f) + (fr.rotation + ev) % 4;
    for (uint32_t h = h0; !wall(T.edge(h)); h = T.rotateCW(h))
        if (++configuration.position >= configuration.valence) return false;
    support.clear();
    signature.clear();
    // A linear search: the supports are small (2n + 8 at most) and this runs only on the faces
    // around a boundary or crease vertex (mesh boundaries, UV seams, infinitely sharp creases).
    auto index = [&](uint32_t v) -> uint32_t {
        const auto it = std::find(support.begin(), support.end(), v);
        if (it != support.end()) return uint32_t(it - support.begin());
        support.push_back(v);
        return uint32_t(support.size() - 1);
    };
    for (int j = 0; j < 4; ++j) {
        const bool closed = fanOf(T.faceHalfedge(f) + (fr.rotation + ev + j) % 4);
        if (fan.size() > kMaxBasisValence) return false;
        signature.push_back(uint32_t(fan.size()) << 1 | (closed ? 1u : 0u));
        for (uint32_t h : fan) {
            const uint32_t g = T.face(h);
            if (T.faceSize(g) != 4) return false; // a hole is no feature (smoothSupport)
            uint32_t x = h;
            for (int c = 0; c < 4; ++c, x = T.next(x)) signature.push_back(index(T.vertex(x)));
            if (support.size() > 2 * size_t(kMaxBasisValence) + 8) return false;
        }
    }
    return true;
}

Mesh irregularBasisMesh(uint32_t n) { return basisConfigurationMesh(n, false); }

Mesh basisConfigurationMesh(uint32_t n, bool boundary) {
    // Three rings of quads around a valence-n vertex: sector j spans rays j and j+1, its point
    // (a, b) = a e_j + b e_{j+1}; the ray points (a, 0) belong to sector j. The rim (a boundary)
    // is two faces beyond face 0, whose sub-patches it therefore never reaches. On a boundary,
    // ray n is not ray 0: its three points come last.
    Mesh m;
    auto id = [&](uint32_t j, uint32_t a, uint32_t b) -> uint32_t {
        if (a == 0 && b == 0) return 0;
        if (a == 0 && boundary && j + 1 == n) return 1 + n * 12 + (b - 1);
        if (a == 0) return 1 + ((j + 1) % n) * 12 + (b - 1) * 4;
        return 1 + j * 12 + (a - 1) * 4 + b;
    };
    m.positions.resize(1 + 12 * size_t(n) + (boundary ? 3 : 0));
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

namespace {

// The support of face f of a level, in its basis's order, and whether it is the configuration
// the basis is for (as the face one level up was).
using SupportOf = bool (*)(const Level& L, uint32_t f, const void* context, std::vector<uint32_t>& support);

// One level of Catmull-Clark under face `face0` of `m` (its corner 0 the extraordinary vertex),
// as a program over face0's support, and (`weights`) the weights of K bands expanded from it.
IrregularBasis basisFromMesh(const Mesh& m, const SchemeOptions& options, uint32_t face0, uint32_t n, uint32_t K,
                             SupportOf supportOf, const void* context, bool boundary, bool weights) {
    Warnings warnings;
    // The table builder's refinement under face 0, one level deep: it refines the faces around
    // face 0's corners (the builder's isolation, oneRing); three children of face 0 are band 1's
    // sub-patches, the fourth (at the extraordinary vertex) has a support like face 0's. The rows
    // that make that level's support and sub-patches from face 0's support are kept as a program
    // (each row's entries in its stencil's order) and run again on each deeper band's support, in
    // smoothSupport's order: the local subdivision is the same at every level (Stam 1998), and so,
    // entry by entry, are the stencils. That gives the bits of refining every level as the tables
    // do: checked for every valence 3 to 64 at K = 16 (docs/irregular.md), and here by
    // IrregularBasis.WeightsAreThoseOfTheWholeTables.
    std::vector<Level> levels;
    {
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        Sharpness sharp = baseSharpness(topo, m.tags, options.boundary, warnings);
        levels.push_back(makeBaseLevel(std::move(topo), std::move(sharp)));
    }
    std::vector<uint32_t> ptexBase(levels[0].topo.faceCount());
    for (uint32_t f = 0; f < ptexBase.size(); ++f) ptexBase[f] = levels[0].frames[f].ptex;
    LevelStencils st;
    {
        std::vector<uint8_t> T(levels[0].topo.faceCount(), 0);
        T[face0] = 1;
        levels.push_back(refineLevel(levels[0], oneRing(levels[0].topo, T), options, ptexBase, st));
    }
    const Level& L = levels[1];
    const uint32_t ptex0 = levels[0].frames[face0].ptex;
    // Face 0's children: the one at the extraordinary vertex (u0 = v0 = 0), and band 1's three
    // sub-patches.
    uint32_t centre = kNone;
    struct SubPatch {
        size_t quadrant;
        Patch patch;
    };
    std::vector<SubPatch> subPatches;
    std::vector<uint32_t> identity(L.topo.vertexCount());
    for (uint32_t v = 0; v < identity.size(); ++v) identity[v] = v;
    auto regularCorners = [&](uint32_t cf) {
        for (uint32_t v : L.topo.faceVertices(cf))
            if (L.vertexSharpness[v] != 0 || L.topo.vertexFaceCount(v) != (L.topo.vertexIsBoundary(v) ? 2u : 4u))
                return false;
        return true;
    };
    for (uint32_t cf = 0; cf < L.topo.faceCount(); ++cf) {
        if (L.faceParent[cf] != face0) continue;
        if (L.frames[cf].u0 == 0 && L.frames[cf].v0 == 0) {
            centre = cf;
            continue;
        }
        const Patch p = gatherPatch(L, cf, 0, identity, kNone);
        const int q = (p.u0 > 0 ? 1 : 0) + (p.v0 > 0 ? 2 : 0); // 1, 3 or 2 (both)
        if (q == 0 || p.size != 0.5f || (p.boundary != 0 && !boundary) || p.ptex != ptex0 ||
            (boundary && !regularCorners(cf)))
            throw std::logic_error("irregular basis: unexpected sub-patch");
        subPatches.push_back({size_t(q == 1 ? 0 : q == 3 ? 1 : 2), p});
    }
    if (centre == kNone || subPatches.size() != 3)
        throw std::logic_error("irregular basis: face 0 has no child at the extraordinary vertex");
    // The support of face 0 (the basis's columns) and of its child at the vertex, in
    // smoothSupport's order.
    std::vector<uint32_t> supports[2];
    for (uint32_t l = 0; l < 2; ++l)
        if (!supportOf(levels[l], l == 0 ? face0 : centre, context, supports[l]))
            throw std::logic_error("irregular basis: the generated valence-" + std::to_string(n) +
                                   " mesh has no support of its configuration at level " + std::to_string(l));
    const size_t M = supports[0].size();
    if (supports[1].size() != M) throw std::logic_error("irregular basis: supports of two sizes");
    // The level-1 vertices the sub-patches and the next support read.
    std::vector<uint8_t> needed(L.topo.vertexCount(), 0);
    for (const SubPatch& sp : subPatches)
        for (int i = 0; i < 16; ++i)
            if (!isPhantom(sp.patch.boundary, i)) needed[sp.patch.cv[i]] = 1;
    for (uint32_t v : supports[1]) needed[v] = 1;
    IrregularBasis basis;
    basis.valence = n;
    basis.levels = K;
    BasisProgram& p = basis.program;
    const std::vector<uint32_t> row =
        stencilRows(L, st, supports[0], levels[0].topo.vertexCount(), std::move(needed), p);
    uint32_t rows = p.rows();
    // A boundary sub-patch's phantom points, as gatherControlPoints makes them (columns first,
    // then rows over all columns): rows 2 a - b of earlier rows, the same double operations
    // (0 + 2 a + (-1) b is 2 a - b to the bit).
    auto phantom = [&](uint32_t a, uint32_t b) {
        p.source.push_back(uint32_t(M) + a);
        p.weight.push_back(2.0f);
        p.source.push_back(uint32_t(M) + b);
        p.weight.push_back(-1.0f);
        p.start.push_back(uint32_t(p.source.size()));
        p.averaged.push_back(0);
        return rows++;
    };
    for (const SubPatch& sp : subPatches) {
        const uint8_t mask = sp.patch.boundary;
        uint32_t R[4][4]; // P[i][j]'s row
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) R[i][j] = isPhantom(mask, 4 * j + i) ? kNone : row[sp.patch.cv[4 * j + i]];
        for (int j = 0; j < 4; ++j) { // a column phantom beside a row phantom is overwritten below
            if ((mask & kBoundaryV0) && j == 0) continue;
            if ((mask & kBoundaryV1) && j == 3) continue;
            if (mask & kBoundaryU0) R[0][j] = phantom(R[1][j], R[2][j]);
            if (mask & kBoundaryU1) R[3][j] = phantom(R[2][j], R[1][j]);
        }
        for (int i = 0; i < 4; ++i) {
            if (mask & kBoundaryV0) R[i][0] = phantom(R[i][1], R[i][2]);
            if (mask & kBoundaryV1) R[i][3] = phantom(R[i][2], R[i][1]);
        }
        for (int j = 0; j < 16; ++j) p.controlRow[sp.quadrant * 16 + size_t(j)] = R[j % 4][j / 4];
    }
    for (uint32_t v : supports[1]) p.nextSupport.push_back(row[v]);
    if (boundary) basis.support = uint32_t(M);
    if (weights) basis.weights = expandIrregularBasis(p, uint32_t(M), K);
    return basis;
}

bool interiorSupport(const Level& L, uint32_t f, const void* context, std::vector<uint32_t>& support) {
    int corner = -1;
    uint32_t valence = 0;
    return smoothSupport(L, f, corner, valence, support) && corner == 0 &&
           valence == *static_cast<const uint32_t*>(context);
}

struct BoundaryContext {
    BasisConfiguration configuration;
    std::vector<uint32_t> signature; // of face 0, which the centre child must share
};

bool boundarySupportOf(const Level& L, uint32_t f, const void* context, std::vector<uint32_t>& support) {
    auto* c = static_cast<const BoundaryContext*>(context);
    int corner = -1;
    BasisConfiguration x;
    std::vector<uint32_t> signature;
    return boundarySupport(L, f, corner, x, support, signature) && corner == 0 && x == c->configuration &&
           signature == c->signature;
}

} // namespace

bool sameProgramBytes(const BasisProgram& x, const BasisProgram& y) {
    return x.start == y.start && x.source == y.source && x.averaged == y.averaged && x.controlRow == y.controlRow &&
           x.nextSupport == y.nextSupport && x.weight.size() == y.weight.size() &&
           std::memcmp(x.weight.data(), y.weight.data(), x.weight.size() * sizeof(float)) == 0;
}

std::vector<uint32_t> stencilRows(const Level& L, const LevelStencils& st, const std::vector<uint32_t>& input,
                                  uint32_t parentVertices, std::vector<uint8_t> needed, BasisProgram& p) {
    const size_t M = input.size();
    std::vector<uint32_t> inputOf(parentVertices, kNone);
    for (size_t i = 0; i < M; ++i) inputOf[input[i]] = uint32_t(i);
    // The face points the needed edge and vertex points read (a level holds face points, then
    // edge points, then vertex points).
    auto markFacePoints = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                              const std::vector<StencilEntry>& entries) {
        for (uint32_t i = 0; i < count; ++i)
            if (needed[first + i])
                for (uint32_t k = start[i]; k < start[i + 1]; ++k)
                    if (entries[k].fromFacePoint) needed[entries[k].index] = 1;
    };
    markFacePoints(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
    markFacePoints(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
    std::vector<uint32_t> row(needed.size(), kNone);
    uint32_t rows = 0;
    for (size_t v = 0; v < needed.size(); ++v)
        if (needed[v]) row[v] = rows++;
    p = BasisProgram{};
    // Each array allocated once: the rows' and entries' counts first.
    size_t entries = 0;
    for (uint32_t i = 0; i < L.facePointCount; ++i)
        if (needed[i]) entries += st.faceStart[i + 1] - st.faceStart[i];
    for (uint32_t i = 0; i < L.edgePointCount; ++i)
        if (needed[L.facePointCount + i]) entries += st.edgeStart[i + 1] - st.edgeStart[i];
    for (uint32_t i = 0; i < L.vertexPointCount; ++i)
        if (needed[L.facePointCount + L.edgePointCount + i]) entries += st.vertexStart[i + 1] - st.vertexStart[i];
    p.source.reserve(entries);
    p.weight.reserve(entries);
    p.start.reserve(size_t(rows) + 1);
    p.averaged.reserve(rows);
    auto in = [&](uint32_t v) {
        if (inputOf[v] == kNone) throw std::logic_error("basis program: a row reads outside the support");
        return inputOf[v];
    };
    for (uint32_t i = 0; i < L.facePointCount; ++i) {
        if (!needed[i]) continue;
        for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k) {
            p.source.push_back(in(st.faceVertices[k]));
            p.weight.push_back(1.0f);
        }
        p.start.push_back(uint32_t(p.source.size()));
        p.averaged.push_back(1);
    }
    auto weighted = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                        const std::vector<StencilEntry>& stencil) {
        for (uint32_t i = 0; i < count; ++i) {
            if (!needed[first + i]) continue;
            for (uint32_t k = start[i]; k < start[i + 1]; ++k) {
                const StencilEntry& e = stencil[k];
                p.source.push_back(e.fromFacePoint ? uint32_t(M) + row[e.index] : in(e.index));
                p.weight.push_back(static_cast<float>(e.weight));
            }
            p.start.push_back(uint32_t(p.source.size()));
            p.averaged.push_back(0);
        }
    };
    weighted(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
    weighted(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
    return row;
}

IrregularBasis buildIrregularBasis(uint32_t n, uint32_t K, bool weights) {
    if (n < 3 || n > kMaxBasisValence || K < 1 || K > uint32_t(kMaxDepth))
        throw std::logic_error("irregular basis: valence or levels out of range");
    IrregularBasis b = basisFromMesh(irregularBasisMesh(n), SchemeOptions{}, 0, n, K, interiorSupport, &n, false, weights);
    b.configuration = {n, false, 0, false};
    return b;
}

IrregularBasis buildBoundaryBasis(const BasisConfiguration& c, uint32_t K, BoundaryRule rule, bool weights) {
    if (!c.boundary || c.valence < 1 || c.valence > kMaxBasisValence || c.position >= c.valence || K < 1 ||
        K > uint32_t(kMaxDepth))
        throw std::logic_error("boundary basis: configuration or levels out of range");
    Mesh m = basisConfigurationMesh(c.valence, true);
    if (c.corner) m.tags.corners.push_back({0, kInfiniteSharpness});
    // Edge-only for the face-varying mesh (fvar_surface.cpp); the geometry's own rule for TBLS.
    // Under edge-and-corner a vertex of one face is a corner (its configuration says so); the
    // generated mesh's rim corners are beyond what one level under face 0 reads.
    SchemeOptions options;
    options.boundary = rule == BoundaryRule::None ? BoundaryRule::EdgeOnly : rule;
    m.tags.boundary = options.boundary;
    // The face at the configuration's place in the vertex's fan, and its signature.
    Warnings warnings;
    Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
    Sharpness sharp = baseSharpness(topo, m.tags, options.boundary, warnings);
    const Level base = makeBaseLevel(std::move(topo), std::move(sharp));
    BoundaryContext context{c, {}};
    for (uint32_t j = 0; j < c.valence; ++j) {
        int corner = -1;
        BasisConfiguration x;
        std::vector<uint32_t> support, signature;
        if (!boundarySupport(base, j * 9, corner, x, support, signature) || corner != 0 || !(x == c)) continue;
        context.signature = signature;
        IrregularBasis b = basisFromMesh(m, options, j * 9, c.valence, K, boundarySupportOf, &context, true, weights);
        b.configuration = c;
        b.signature = std::move(context.signature);
        return b;
    }
    throw std::logic_error("boundary basis: the generated mesh has no face of the configuration");
}

std::vector<float> expandIrregularBasis(const BasisProgram& p, uint32_t support, uint32_t K) {
    const size_t M = support, T = p.rows();
    bool valid = p.start.size() >= 1 && p.start[0] == 0 && p.averaged.size() == T &&
                 p.source.size() == p.start[T] && p.weight.size() == p.source.size() &&
                 p.nextSupport.size() == M;
    for (size_t r = 0; valid && r < T; ++r) {
        valid = p.start[r] <= p.start[r + 1];
        for (uint32_t e = p.start[r]; valid && e < p.start[r + 1]; ++e) valid = p.source[e] < M + r;
    }
    for (uint32_t x : p.controlRow) valid = valid && x < T;
    for (uint32_t x : p.nextSupport) valid = valid && x < T;
    if (!valid) throw std::logic_error("irregular basis: invalid program");
    // Rows of W values rounded up to even: the columns are summed two at a time (GCC's packed
    // doubles: SSE2, NEON), each column still its own product and sum in the program's order,
    // so every bit is that of one column at a time (the web runtime's tables_chunk.mjs computes
    // one at a time). The pad column stays 0.
    const size_t W = (M + 1) & ~size_t(1);
    using Pair = double __attribute__((vector_size(16)));
    auto load = [](const double* x) {
        Pair v;
        std::memcpy(&v, x, sizeof v);
        return v;
    };
    auto store = [](double* x, Pair v) { std::memcpy(x, &v, sizeof v); };
    std::vector<double> input(M * W, 0.0), values(T * W), next(M * W);
    for (size_t i = 0; i < M; ++i) input[i * W + i] = 1; // band 1 reads face 0's support
    std::vector<float> weights(size_t(K) * 48 * M);
    for (uint32_t band = 1; band <= K; ++band) {
        std::fill(values.begin(), values.end(), 0.0);
        for (size_t r = 0; r < T; ++r) {
            double* out = &values[r * W];
            for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
                const uint32_t s = p.source[e];
                const double* in = s < M ? &input[s * W] : &values[(s - M) * W];
                if (p.averaged[r]) {
                    for (size_t c = 0; c < W; c += 2) store(out + c, load(out + c) + load(in + c));
                } else {
                    const double w = p.weight[e];
                    const Pair weight = {w, w};
                    for (size_t c = 0; c < W; c += 2) store(out + c, load(out + c) + weight * load(in + c));
                }
            }
            if (p.averaged[r]) {
                const double d = double(p.start[r + 1] - p.start[r]);
                const Pair divisor = {d, d};
                for (size_t c = 0; c < W; c += 2) store(out + c, load(out + c) / divisor);
            }
        }
        float* block = &weights[size_t(band - 1) * 48 * M];
        for (size_t j = 0; j < 48; ++j)
            for (size_t i = 0; i < M; ++i) block[j * M + i] = static_cast<float>(values[p.controlRow[j] * W + i]);
        for (size_t i = 0; i < M; ++i)
            std::memcpy(&next[i * W], &values[p.nextSupport[i] * W], W * sizeof(double));
        input.swap(next);
    }
    return weights;
}

} // namespace limn
