// TBLS version 5's records of the irregular faces' surface (formats/tbls.md, "Per-valence bases
// as programs, and compact per-face records"): each per-valence basis as its one-level program
// (BasisProgram), which the reader expands to the same weights, bit for bit; the quadtree nodes,
// the smooth faces and their points (in runs by level, for the smooth faces below level N) as
// varint streams; version 6's sub-patch domains, taken from the quadtrees; and the bases of
// versions 3 and 4. Kept apart from the rest of the TBLS codec (tables_chunk.cpp).
#pragma once

#include "base/bytes.h"
#include "subdiv/tables.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace limn {

// A basis as its program. A basis without one (read from an older version) gets the program
// buildIrregularBasis makes for its valence, which must expand to its weights (std::logic_error
// otherwise: such tables cannot be written as version 5).
void writeBasisProgram(ByteWriter& w, const IrregularBasis& basis);
// Reads basis `index` and expands its weights; `earlier` are the bases read before it (no valence
// twice). Every count and index is checked before anything is allocated from it.
IrregularBasis readBasisProgram(ByteReader& r, uint32_t index, const std::vector<IrregularBasis>& earlier);
// A basis with its configuration (FVSF version 3, TBLS version 7; formats/limn.md): u32 valence,
// u32 configuration code (BasisConfiguration::code), u32 support size, u32 levels, then its
// program. An interior basis without a program (read from an older version) is written as
// writeBasisProgram writes it. The reader checks every field (an interior basis: valence 3 to
// kMaxBasisValence but 4, 2n + 8 points; a boundary one: its place in a fan of 1 to
// kMaxBasisValence faces), refuses a configuration twice, expands the weights and checks their
// range: [0, 1] for an interior basis (Catmull-Clark's smooth weights are convex), [-4, 5] for a
// boundary one (its phantom points, 2 a - b of such; corners 4 a - 2 b - 2 c + d). `what` names
// the basis in messages.
// TBLS version 9 (`dictionary` given): the program, rows in canonical order, through the chunk's
// program dictionary, in a stream after the header (tables_program_dictionary.h).
struct ProgramDictionary;
void writeConfigurationBasis(ByteWriter& w, const IrregularBasis& basis, ProgramDictionary* dictionary = nullptr);
// TBLS version 8 (`chains` given): a record of configuration code 2 is a decaying-crease chain
// (tables_chain_records.h), its programs shared through `chains`.
struct ChainPrograms;
IrregularBasis readConfigurationBasis(ByteReader& r, const std::string& what, const std::vector<IrregularBasis>& earlier,
                                      ChainPrograms* chains = nullptr, ProgramDictionary* dictionary = nullptr);

// The program alone (u32 palette size, the palette, the stream), over `support` points, which
// FVSF version 3 writes after a configuration's own header; `phantomRows` more rows than TBLS's
// bound allows (a boundary configuration's phantom points). Checked as readBasisProgram does.
void writeProgram(ByteWriter& w, const BasisProgram& program);
BasisProgram readProgram(ByteReader& r, const std::string& what, uint32_t support, uint32_t phantomRows);

// A basis as versions 3 (the weights, `compact` false) and 4 (each distinct row once, `compact`)
// store it, checked; `earlier` are the bases read before it (version 4: no valence twice).
IrregularBasis readBasisWeights(ByteReader& r, uint32_t index, bool compact, const std::vector<IrregularBasis>& earlier);

// The quadtree nodes (after their count): a stream of codes, each a varint from the last index of
// its kind, a node of four equal codes as one. The codes' kinds and indices are checked by the
// caller, as for the plain layout.
void writeNodeStream(ByteWriter& w, const std::vector<std::array<uint32_t, 4>>& nodes);
std::vector<std::array<uint32_t, 4>> readNodeStream(ByteReader& r, uint32_t count);

// The smooth faces (after their count): basis and corner in one varint, `first` as a difference
// from the end of the previous face's points.
void writeSmoothFaces(ByteWriter& w, const Tables& t);
std::vector<Tables::SmoothIrregular> readSmoothFaces(ByteReader& r, uint32_t count,
                                                     const std::vector<IrregularBasis>& bases);

// The smooth points (after their count): runs of points at one level, N + j (0 <= j < K; j > 0
// for the supports of smooth faces below level N), each a varint j, a varint count >= 1, then
// per point a varint `c + 3 * zigzag(v - last[c])`, c its class at that level (0: face points,
// 1: edge points, 2: vertex points) and last[c] the previous point of that class in the run (the
// class's first vertex at first): a support's points alternate between the three ranges, and
// are neighbours within each. Which level each face's points must be at is checked by the caller.
void writeSmoothPoints(ByteWriter& w, const Tables& t);
// `t` holds the header and levels read so far.
std::vector<uint32_t> readSmoothPoints(ByteReader& r, uint32_t count, const Tables& t);

// Smooth faces below level N (version 5): what is wrong with the quadtree's basis codes and the
// smooth faces' levels (each named once, a band left at its level, its support points at its
// level; before version 5 only roots hold basis codes), or an empty string. Called by the TBLS
// reader once the nodes' kinds and indices are checked and children come after their parents.
std::string checkSmoothFaceLevels(const Tables& t, uint32_t version);

// Version 6's sub-patches hold no domain: a sub-patch is a quadrant of its node, whose square
// is a quadrant of its parent's, down from the irregular face (formats/tbls.md, "Sub-patch
// domains"). Sets every sub-patch's ptex face and domain from the quadtrees, or returns what is
// wrong: a node or sub-patch named twice, a node below the roots or a sub-patch named by none, a
// sub-patch whose level is not its node's plus one. Called by the TBLS reader once the nodes'
// kinds and indices are checked and children come after their parents.
std::string assignSubPatchDomains(Tables& t);

} // namespace limn
