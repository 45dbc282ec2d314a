// Per-configuration bases (TablesOptions::creaseChains; TBLS version 8) for the irregular faces
// whose feature corner is on semi-sharp creases that have not decayed at
// level N (docs/irregular-tables.md, "Decaying-crease configurations"). Today such a face is refined K
// more levels (its quadtree); but the sub-patches of its three quadrants away from the feature
// corner, band after band, follow from its support by one-level programs that depend only on
// the local topology and the sharpness the stencils of that level read (Stam's observation for
// smooth vertices, with a program per band instead of one repeated: the sharpness decreases
// band by band until the crease has decayed, then the per-valence basis goes on).
#pragma once

#include "mesh/mesh.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/level.h"
#include "subdiv/tables.h"

#include <array>
#include <map>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn {

// One band (one level below the chain face): a program over the chain face's support at that
// level whose rows give the sub-patches of its quadrants 1..3 (controlRow, canonical frame, as
// BasisProgram's) and the next band's support (nextSupport; empty at the last band).
struct CreaseBand {
    std::vector<uint32_t> key; // the chain face's configuration at this band (creaseSupport)
    uint32_t support = 0;      // its points
    BasisProgram program;
    std::array<CreaseBandKind, 3> kind{}; // quadrants 1, 3, 2 (BasisProgram's order)
    // The last band of a chain that ends Regular: the corner quadrant's patch too.
    std::array<uint32_t, 16> centreRow{};
    CreaseBandKind centreKind;
    // Builder only: the band holds the first band's program, not its own (buildCreaseChain's
    // sharedPrograms), which the tables may keep only where sharing by programKey replaces it.
    bool borrowed = false;
};

// How a chain ends: at level N + K with the corner's child still irregular (a leaf, as the
// quadtree's); with the corner's child a smooth face of the per-valence basis (the crease has
// decayed; nextSupport in smoothSupport's order); or with the corner's child a regular patch (a
// dart's end once its crease has decayed).
enum class CreaseEnd : uint8_t { Leaf, Smooth, Regular };

struct CreaseChain {
    std::vector<uint32_t> key; // band 1's
    std::vector<CreaseBand> bands;
    CreaseEnd end = CreaseEnd::Leaf;
    uint32_t valence = 0; // CreaseEnd::Smooth: the basis that goes on
    uint32_t endBasis = UINT32_MAX; // and its index among the tables' bases (TBLS version 8 names it)
};

// The support of face f of level L seen from its ptex corner `corner`: the vertices of the faces
// around its four corners (corners from `corner` counter-clockwise, each fan counter-clockwise from
// f, then clockwise from f where it is open, each face's vertices from that corner on, each vertex
// once), and the key of its configuration: per corner its fan's length and whether it closed, per
// fan face its four vertices' support indices and, for its edges at a corner, their sharpness
// (the bits of the float), then the corners' vertex sharpness. That is what the stencils of one
// level read for the face's children and the next support: the corners' vertex points and the
// edge points of the edges at the corners (and their children's sharpness: the Chaikin rule
// reads only edges at the same vertex). `faces` (optional): the fans' faces, with repeats.
bool creaseSupport(const Level& L, uint32_t f, int corner, std::vector<uint32_t>& support,
                   std::vector<uint32_t>& key, std::vector<uint32_t>* faces = nullptr);

// The key of a band's program: `key` with every sharpness of at least `sharp` as `sharp`. Rules
// read sharpness only below 1 (a crease's edge point is its midpoint from 1 on; a vertex's rule
// changes where a child's sharpness reaches 0, blended by the parent's fraction), so bands whose
// keys differ only above that share their program: a crease of sharpness 7.9 runs one program
// for its first bands, and only the kinds' sharpness (the single-crease patches') changes.
std::vector<uint32_t> programKey(const std::vector<uint32_t>& key, float sharp);
// The sharpness from which programKey clamps where programs are shared and bands repeated.
inline constexpr float kProgramSharpness = 1.0f;

// The pieces a chain is built from (tests/support's crease trees build from them too).
// localLevel: a level of the faces in `faces` (sorted by index, so that every stencil's entries
// come in the level's own order), vertex i being support[i], with their sharpness, the copy's rim
// infinitely sharp; face f (`face0` in the copy) turned so that `corner` is at (0, 0).
Level localLevel(const Level& L, const std::vector<uint32_t>& support, std::vector<uint32_t> faces, uint32_t f,
                 int corner, uint32_t& face0);
CreaseBandKind kindOf(const Patch& p);
// The program of one band: the rows of `child` (refined from a level of `parentVertices`
// vertices with stencils `st`) that `patches` and `next` read, over the parent's vertices
// `input` (basisFromMesh's construction); throws std::logic_error where a row reads outside it.
void bandProgram(const Level& child, const LevelStencils& st, const std::vector<uint32_t>& input,
                 uint32_t parentVertices, const std::vector<Patch>& patches, const std::vector<uint32_t>& next,
                 BasisProgram& p, std::vector<std::array<uint32_t, 16>>& controlRows);

// A band's rows over its support's values (evaluateVertices' arithmetic: double sums in the
// program's order of float weights times points, face points averaged).
std::vector<glm::dvec3> runBandProgram(const BasisProgram& program, std::span<const glm::dvec3> support);
// Whether two bands' programs are the same function: the same points to the bit from the same
// (arbitrary) support values of size about 1 (`tolerance` > 0: within it); `difference`
// (optional) gets the largest difference met.
// `xProbe` (optional): bandProbe(x), computed once where x is compared with many bands.
bool sameBandFunction(const CreaseBand& x, const CreaseBand& y, double* difference = nullptr, double tolerance = 0,
                      const std::vector<glm::dvec3>* xProbe = nullptr);
// A band's rows from sameBandFunction's support values.
std::vector<glm::dvec3> bandProbe(const CreaseBand& band);

// The chain of face f of level L with feature corner `corner` over `levels` bands, from a copy
// of its support's faces (their sharpness; the copy's rim edges infinitely sharp, which no
// stencil of the programs reads) refined band by band by the table builder's refineLevel, only
// around the chain face (its isolation). False where some band's three other quadrants are not
// all regular patches (the face is not of this kind: two feature corners, a bent crease).
// `sharedPrograms`: the caller runs each band with the first program of its programKey and end
// (takeCreaseFaces, for the tables), so a band need not hold its own program's bits: a second
// band whose key is the first's less 1 repeats the first (`borrowed`; see buildCreaseChain),
// where the study, which compares each face's own chain with its quadtree bit for bit, refines it.
bool buildCreaseChain(const Level& L, uint32_t f, int corner, uint32_t levels, const SchemeOptions& options,
                      const TablesOptions& opts, CreaseChain& chain, bool sharedPrograms = false);

// A chain's surface in the layout of a basis (IrregularBasis::weights, K bands of three
// quadrants' 16 control points as weights of the face's own M level-N support points) with each
// band's kinds (IrregularBasis::kinds): its bands' programs run on weights instead of points
// (double sums in each program's order, rounded to float once), boundary quadrants' phantom
// points folded into the weights as gatherControlPoints makes them (so only a crease's bits and
// sharpness remain of a kind), and then, to band K, a Smooth end's per-valence basis (the
// `valence` basis's one-level program run again from the end's next support, band after band,
// as expandIrregularBasis runs it) or a Regular end's
// B-spline patch split into its quadrants band by band (uniform knot insertion: (1, 1)/2 and
// (1, 6, 1)/8); a Leaf end has its K bands already. False, and nothing usable, for a Regular
// end whose patch has a crease: such faces are refined as before.
// `endBasis` (a Smooth end's): the valence's basis with its program (built here where it is not
// given or has none). Throws std::logic_error where it is not that valence's.
// `weights` false (TablesOptions::basisWeights): the same checks, levels, support and kinds,
// without the weights.
bool expandCreaseChain(const CreaseChain& chain, uint32_t levels, IrregularBasis& out,
                       const IrregularBasis* endBasis = nullptr, bool weights = true);

} // namespace limn
