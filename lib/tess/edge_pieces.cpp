#include "tess/edge_pieces.h"

#include "base/error.h"
#include "base/flat_map.h"
#include "tess/tessellation.h"
#include "topology/ptex.h"
#include "topology/topology.h"

#include <glm/geometric.hpp>

namespace limn {

namespace {

struct Domain {
    uint32_t ptex, U0, V0, W; // in units of 1/R
};

// The lattice point at distance x along side k of d, counter-clockwise (side 0: t = 0, s
// increasing; 1: s = 1; 2: t = 1, s decreasing; 3: s = 0).
void sidePoint(const Domain& d, int k, uint32_t x, uint32_t& U, uint32_t& V) {
    switch (k) {
    case 0: U = d.U0 + x, V = d.V0; break;
    case 1: U = d.U0 + d.W, V = d.V0 + x; break;
    case 2: U = d.U0 + d.W - x, V = d.V0 + d.W; break;
    default: U = d.U0, V = d.V0 + d.W - x; break;
    }
}

// The element's own parameter of that point, in 1/32768.
uint32_t sideST(const Domain& d, int k, uint32_t x) {
    const uint32_t unit = kTessParamOne / d.W, p = x * unit, q = kTessParamOne - p;
    switch (k) {
    case 0: return packST(p, 0);
    case 1: return packST(kTessParamOne, p);
    case 2: return packST(q, kTessParamOne);
    default: return packST(0, q);
    }
}

} // namespace

EdgePieces buildEdgePieces(const Mesh& mesh, const Tables& t) {
    const uint32_t N = t.depth;
    if (N + 1 > 16)
        throw Error(ErrorKind::BadInput, "view-adaptive tessellation supports tables up to depth 15, these have depth " +
                                             std::to_string(N) +
                                             ": rebuild them with limn-tables --depth 15 or less, or draw the fixed "
                                             "grids with --edge-pixels 0");
    const uint32_t R = 1u << N;
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    PtexMap keys(mesh, topo, R), halfKeys(mesh, topo, 2 * R); // halves: piece midpoints
    const bool withUV = mesh.hasUVs();

    std::vector<Domain> domains;
    EdgePieces out;
    // About one point and two pieces per element, four sides of one piece or more each.
    const size_t elements = t.patches.size() + t.irregular.size();
    domains.reserve(elements);
    out.elements.reserve(elements);
    out.points.reserve(elements + elements / 8);
    out.pieces.reserve(2 * elements + elements / 4);
    out.sidePieces.reserve(4 * elements + elements / 2);
    auto add = [&](uint32_t ptex, float u0, float v0, float size, uint32_t level) {
        Domain d{ptex, uint32_t(double(u0) * R), uint32_t(double(v0) * R), uint32_t(double(size) * R)};
        if (d.W == 0 || (d.W & (d.W - 1)) != 0 || d.W > R)
            throw Error(ErrorKind::BadInput, "an element's domain is not a quadtree cell at the tables' depth");
        domains.push_back(d);
        AdaptiveElement e{};
        e.level = level;
        if (withUV) {
            const uint32_t cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
            for (int c = 0; c < 4; ++c)
                e.cornerUV[c] = glm::vec2(keys.ownUV(ptex, double(d.U0 + cu[c] * d.W) / R,
                                                     double(d.V0 + cv[c] * d.W) / R));
        }
        out.elements.push_back(e);
    };
    for (const Patch& p : t.patches) add(p.ptex, p.u0, p.v0, p.size, p.level);
    for (const IrregularFace& q : t.irregular) add(q.ptex, q.u0, q.v0, q.size, 255);

    // Points: every element corner, owned by the first element (in order) that has it.
    FlatKeyMap pointOf(domains.size() * 2);
    for (uint32_t ei = 0; ei < domains.size(); ++ei)
        for (int k = 0; k < 4; ++k) {
            uint32_t U, V;
            sidePoint(domains[ei], k, 0, U, V);
            const bool inserted = pointOf.tryEmplace(keys.key(domains[ei].ptex, U, V),
                                                     static_cast<uint32_t>(out.points.size())).second;
            if (inserted) out.points.push_back({ei, sideST(domains[ei], k, 0)});
        }

    // Pieces: each side cut at every point on it; a piece is named by its midpoint (on the
    // lattice of 1/(2R), so even a piece one lattice step long has one).
    FlatKeyMap pieceOf(domains.size() * 2);
    for (uint32_t ei = 0; ei < domains.size(); ++ei) {
        const Domain& d = domains[ei];
        AdaptiveElement& e = out.elements[ei];
        for (int k = 0; k < 4; ++k) {
            e.sideFirst[k] = static_cast<uint32_t>(out.sidePieces.size());
            uint32_t a = 0, aPoint = 0;
            {
                uint32_t U, V;
                sidePoint(d, k, 0, U, V);
                aPoint = pointOf.find(keys.key(d.ptex, U, V)); // every corner is a point
            }
            // The side's points, in order. The elements along it tile it in aligned dyadic
            // intervals (a quadtree in each ptex chart, and charts meet at whole or half edges),
            // so a stretch [x0, x1] of it holds a point inside only if its midpoint is one:
            // bisect from the whole side instead of looking up every lattice step (W of them:
            // 64 per side of a level-0 patch at depth 6).
            uint32_t stack[2 * 17], top = 0; // pending stretch ends, at most log2(W) + 1 deep
            uint32_t x0 = 0, x1 = d.W;
            for (;;) {
                uint32_t bPoint = FlatKeyMap::kAbsent;
                if (x1 - x0 >= 2) {
                    const uint32_t m = (x0 + x1) / 2;
                    uint32_t U, V;
                    sidePoint(d, k, m, U, V);
                    if (pointOf.find(keys.key(d.ptex, U, V)) != FlatKeyMap::kAbsent) {
                        stack[top++] = x1; // the right half after the left one
                        x1 = m;
                        continue;
                    }
                }
                const uint32_t b = x1;
                uint32_t U, V, Ua, Va;
                sidePoint(d, k, b, U, V);
                bPoint = pointOf.find(keys.key(d.ptex, U, V)); // ends are points: corners or midpoints found
                sidePoint(d, k, a, Ua, Va);
                const uint64_t mid = halfKeys.key(d.ptex, Ua + U, Va + V);
                const auto [piece, inserted] = pieceOf.tryEmplace(mid, static_cast<uint32_t>(out.pieces.size()));
                if (inserted) {
                    EdgePiece pc{};
                    pc.owner = ei;
                    pc.ownerStart = sideST(d, k, a);
                    pc.ownerEnd = sideST(d, k, b);
                    pc.users[0] = ei, pc.users[1] = kNoElement;
                    pc.startPoint = aPoint, pc.endPoint = bPoint;
                    pc.span = (b - a) * (kTessParamOne / d.W);
                    if (withUV)
                        pc.uvLength = float(glm::length(keys.ownUV(d.ptex, double(Ua) / R, double(Va) / R) -
                                                        keys.ownUV(d.ptex, double(U) / R, double(V) / R)));
                    out.pieces.push_back(pc);
                } else {
                    EdgePiece& pc = out.pieces[piece];
                    if (pc.users[1] == kNoElement && pc.users[0] != ei) pc.users[1] = ei;
                }
                const EdgePiece& pc = out.pieces[piece];
                SidePiece sp{};
                sp.piece = piece;
                sp.startPoint = aPoint;
                sp.reversed = pc.owner == ei && inserted ? 0u : (pc.startPoint == aPoint ? 0u : 1u);
                sp.from = a * (kTessParamOne / d.W);
                sp.to = b * (kTessParamOne / d.W);
                out.sidePieces.push_back(sp);
                a = b, aPoint = bPoint;
                if (top == 0) break;
                x0 = x1, x1 = stack[--top];
            }
            e.sideCount[k] = static_cast<uint32_t>(out.sidePieces.size()) - e.sideFirst[k];
        }
    }
    return out;
}

} // namespace limn
