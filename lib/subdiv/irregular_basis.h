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
#include <memory>
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

// Whether two programs are the same, entry for entry (weights compared as bits).
bool sameProgramBytes(const BasisProgram& x, const BasisProgram& y);

// Which faces a basis draws: those around one extraordinary vertex with `valence` faces, the other
// vertices of the faces around their corners regular. Interior: Stam's setting, one basis per
// valence (the faces around the vertex are alike up to rotation). On a boundary (a UV seam or a
// mesh boundary; FVSF version 3, TBLS version 7) the faces around the vertex differ,
// so a basis is per face: `position` is the face's place in the vertex's fan, 0 for the face at
// its clockwise end, and `corner` says the vertex is infinitely sharp (a corner) rather than a
// smooth boundary vertex.
struct BasisConfiguration {
    uint32_t valence = 0;
    bool boundary = false;
    uint32_t position = 0;
    bool corner = false;
    // What FVSF version 3 and TBLS version 7 store: 0 for interior, else 1 | corner << 1 | position << 2.
    uint32_t code() const { return boundary ? 1u | uint32_t(corner) << 1 | position << 2 : 0u; }
    uint64_t key() const { return uint64_t(valence) << 32 | code(); }
    bool operator==(const BasisConfiguration&) const = default;
};

// The kind of a band's sub-patch, as the quadtree's Patch holds it: boundary and crease bits (in
// the canonical frame: the feature corner at (0, 0)) and the crease's sharpness.
struct CreaseBandKind {
    uint8_t boundary = 0, crease = 0;
    float sharpness = 0;
    bool operator==(const CreaseBandKind&) const = default;
};

struct CreaseChain; // crease_basis.h

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
    // Interior: 2n + 8 points. A boundary configuration's support has `support` points (FVSF
    // version 3, TBLS version 7).
    BasisConfiguration configuration;
    uint32_t support = 0;
    // A decaying-crease chain's (crease_basis.h, expandCreaseChain; empty for the per-valence and
    // boundary bases, whose sub-patches are all B-splines): kinds[(k - 1) * 3 + (q - 1)] is the
    // band-k sub-patch's in quadrant q, crease bit and sharpness in the canonical frame (its
    // boundary phantoms are in the weights already, so its boundary bits are 0).
    std::vector<CreaseBandKind> kinds;
    // What a chain's weights were expanded from (TBLS version 8 stores it).
    std::shared_ptr<const CreaseChain> chain;
    // Builder only (not stored): the local topology the program was made for, as
    // boundarySupport's signature; a face whose signature differs is refined instead.
    std::vector<uint32_t> signature;
    uint32_t supportSize() const { return support ? support : 2 * valence + 8; }
    // The weights' count: K bands of three sub-patches' 16 rows of supportSize().
    size_t weightCount() const { return size_t(levels) * 48 * supportSize(); }
    // Whether the weights are there (tables built with TablesOptions::basisWeights off, to be
    // written only, have none: a renderer or evaluator refuses them).
    bool hasWeights() const { return weights.size() == weightCount(); }
};

// The mesh a basis is refined from: three rings of quads around a valence-n vertex (vertex 0),
// face 0 one of the faces at it, the rim a boundary two faces beyond face 0.
Mesh irregularBasisMesh(uint32_t valence);
// The same around a vertex with `valence` faces, on a boundary (the fan open between rays 0 and n)
// or not (irregularBasisMesh); face 9 j is the fan's face j, vertex 0 its corner 0.
Mesh basisConfigurationMesh(uint32_t valence, bool boundary);

// Builds the basis of valence n (3..kMaxBasisValence) for K levels (1..16): its program, and the
// weights expanded from it (`weights` false: none, TablesOptions::basisWeights). Throws on failure.
IrregularBasis buildIrregularBasis(uint32_t valence, uint32_t levels, bool weights = true);

// The same for a boundary configuration (boundarySupport's), from a generated mesh of three rings
// of quads around a boundary vertex with that many faces, refined one level with the builder's
// own rules under boundary rule `rule` (the face-varying mesh's is edge-only; the geometry's is
// its mesh's, None read as edge-only: a face with a surface under None has its boundary edges
// tagged sharp, which is what edge-only does) and the vertex tagged a corner when it is one. The program also holds the boundary sub-patches' phantom points (gatherControlPoints'
// 2 a - b, columns first), so its weights give the ptex-frame control points as the tables
// evaluate them. Throws where the configuration is not self-similar (the sub-patch at the vertex
// one level down must be the same configuration) or a sub-patch is not regular.
IrregularBasis buildBoundaryBasis(const BasisConfiguration& configuration, uint32_t levels,
                                  BoundaryRule rule = BoundaryRule::EdgeOnly, bool weights = true);

// The rows of one refined level that a basis's program keeps (basisFromMesh's, and each band of
// a crease chain's, crease_basis.cpp): the child vertices marked `needed`, and the face points
// their edge and vertex stencils read, in vertex order (face points, edge points, vertex points),
// each row's entries in its stencil's order as the tables' evaluation reads them (float weights;
// a face point averaged), reading the parent's support `input` (source i: input[i]'s point) or an
// earlier row. `p` gets those rows (nothing else); the result is each child vertex's row (kNone
// where none). Throws std::logic_error where a row reads a parent vertex outside `input`.
std::vector<uint32_t> stencilRows(const Level& child, const LevelStencils& stencils, const std::vector<uint32_t>& input,
                                  uint32_t parentVertices, std::vector<uint8_t> needed, BasisProgram& p);

// The weights of K bands (IrregularBasis::weights' layout) from a program over `support` points
// (2n + 8 for an interior basis), with the builder's own arithmetic (double sums in the program's order, each weight
// rounded to float once). The program must be valid (TBLS's reader checks every count and index
// before calling this); throws std::logic_error otherwise.
std::vector<float> expandIrregularBasis(const BasisProgram& program, uint32_t support, uint32_t levels);

// Whether face f of level L is a quad whose surface these bases give: exactly one corner is an
// extraordinary vertex (valence n >= 3, any n != 4), the other three have valence 4, every face
// around its corners is a quad, nothing there is on a boundary, sharp, or without a limit. Then
// `corner` is the extraordinary corner's ptex index (0: (0,0), 1: (1,0), 2: (1,1), 3: (0,1)),
// `valence` its valence and `support` the 2n + 8 vertices of the faces around its corners in
// a canonical order (corners from the extraordinary one counter-clockwise, faces around each
// counter-clockwise from f, each face's vertices from that corner on; each vertex once).
// `featuresBeyondCorners`: accept boundaries, creases and sharp vertices on the support's rim
// (edges and vertices not at the four corners), which the stencils of one level do not read as
// features (TablesOptions::basisRimFeatures: the UV surface beside its seams, and the geometry
// beside its boundaries and creases since TBLS version 7).
bool smoothSupport(const Level& L, uint32_t f, int& corner, uint32_t& valence, std::vector<uint32_t>& support,
                   bool featuresBeyondCorners = false);

// Whether face f of level L is a quad around one boundary vertex (any number of faces up to
// kMaxBasisValence, a smooth boundary or an infinitely sharp corner) whose other corners are
// regular (4 faces inside, 2 on a boundary), no crease or other sharp vertex at its corners, and
// no face around them without a limit. A wall is a boundary edge or an infinitely sharp one: the
// rules on one side of an infinitely sharp crease read nothing across it, so a sector between two
// such edges (or more: a corner) is a boundary vertex's fan, and a corner on a crease with two
// faces on f's side is regular. Then `corner`, `configuration` (its fan's faces; `corner` if the
// vertex is infinitely sharp or has more than two walls) and `support` (the vertices of the faces
// around the corners: corners from the extraordinary one counter-clockwise, each corner's fan
// counter-clockwise from f to a wall, then clockwise from f, each face's vertices from that corner
// on, each vertex once), and `signature`: per corner its fan's length and whether it closed, then
// per face its four vertices' support indices — the local topology the stencils of one level
// read, which buildBoundaryBasis's generated mesh must share.
bool boundarySupport(const Level& L, uint32_t f, int& corner, BasisConfiguration& configuration,
                     std::vector<uint32_t>& support, std::vector<uint32_t>& signature);

} // namespace limn
