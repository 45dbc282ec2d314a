// The surface of a face left irregular at the last level around one smooth interior
// extraordinary vertex (docs/irregular.md; Stam 1998's setting, without the eigenbasis): its
// sub-patches at levels 1..K deeper are regular bicubic B-splines whose 16 control points are
// fixed linear combinations of the face's 2n + 8 surrounding points (n the valence), the same
// for every such face of valence n. The combinations are found once per valence by refining a
// generated mesh around a valence-n vertex with the tables' own rules, so they follow limn's
// (and OpenSubdiv's) Catmull-Clark exactly.
#pragma once

#include "mesh/mesh.h"
#include "subdiv/level.h"

#include <array>
#include <cstdint>
#include <vector>

namespace limn {

// One level of Catmull-Clark under face 0 of the generated mesh, as a program over its 2n + 8
// support points (docs/irregular.md, section 1): buildIrregularBasis runs it once per band, each
// band's input being the previous band's next support. TBLS version 5 stores it in place of the
// K * 3 * 16 * (2n + 8) weights; expandIrregularBasis gives those back bit for bit.
struct BasisProgram {
    // Row r is the sum, in order, of weight[e] * value(source[e]) over e in [start[r],
    // start[r + 1]), computed in double; an averaged row (a face point) sums its sources and
    // divides by their count (its weights are 1). A source below m = 2n + 8 is the band's
    // support point of that index, source m + r' the earlier row r' (< r).
    std::vector<uint32_t> start{0};
    std::vector<uint32_t> source;
    std::vector<float> weight;
    std::vector<uint8_t> averaged; // per row
    // Control point j of the band's sub-patch in quadrant q (1..3) is row controlRow[16(q-1)+j];
    // the next band's support point i is row nextSupport[i].
    std::array<uint32_t, 48> controlRow{};
    std::vector<uint32_t> nextSupport;
    uint32_t rows() const { return static_cast<uint32_t>(start.size() - 1); }
};

struct IrregularBasis {
    uint32_t valence = 0;
    uint32_t levels = 0; // K
    // weights[((k - 1) * 3 + (q - 1)) * 16 * m + j * m + i]: control point j (P_{j%4, j/4}) of
    // the band-k sub-patch in quadrant q (1: s >= 1/2 > t, 2: both >= 1/2, 3: t >= 1/2 > s, in
    // the band's square [0, 2^-(k-1)]^2 with the extraordinary vertex at (0, 0)), as weights of
    // the m = 2n + 8 support points (smoothSupport's order).
    std::vector<float> weights;
    // What the weights were expanded from (empty rows when read from TBLS before version 5).
    BasisProgram program;
    uint32_t supportSize() const { return 2 * valence + 8; }
};

// The mesh a basis is refined from: three rings of quads around a valence-n vertex (vertex 0),
// face 0 one of the faces at it, the rim a boundary two faces beyond face 0.
Mesh irregularBasisMesh(uint32_t valence);

// Builds the basis of valence n (3..kMaxBasisValence) for K levels (1..16): its program, and the
// weights expanded from it. Throws on failure.
IrregularBasis buildIrregularBasis(uint32_t valence, uint32_t levels);

// The weights of K bands (IrregularBasis::weights' layout) from a program over 2n + 8 support
// points, with the builder's own arithmetic (double sums in the program's order, each weight
// rounded to float once). The program must be valid (TBLS's reader checks every count and index
// before calling this); throws std::logic_error otherwise.
std::vector<float> expandIrregularBasis(const BasisProgram& program, uint32_t valence, uint32_t levels);

// Whether face f of level L is a quad whose surface these bases give: exactly one corner is an
// extraordinary vertex (valence n >= 3, any n != 4), the other three have valence 4, every face
// around its corners is a quad, nothing there is on a boundary, sharp, or without a limit. Then
// `corner` is the extraordinary corner's ptex index (0: (0,0), 1: (1,0), 2: (1,1), 3: (0,1)),
// `valence` its valence and `support` the 2n + 8 vertices of the faces around its corners in
// a canonical order (corners from the extraordinary one counter-clockwise, faces around each
// counter-clockwise from f, each face's vertices from that corner on; each vertex once).
bool smoothSupport(const Level& L, uint32_t f, int& corner, uint32_t& valence,
                   std::vector<uint32_t>& support);

} // namespace limn
