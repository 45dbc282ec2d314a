// TBLS version 8's decaying-crease chains (formats/tbls.md, "Decaying-crease chains"): a basis
// record of configuration code 2 holds a chain (crease_basis.h) as its bands' programs, kinds
// and end; the reader runs expandCreaseChain on it, to the weights the builder expanded, bit for
// bit. Programs are shared across the chunk's chains: a band names one read before or brings
// its own.
#pragma once

#include "base/bytes.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/tables_program_dictionary.h"

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace limn {

// BasisConfiguration::code() is 0 or odd; 2 marks a chain.
inline constexpr uint32_t kChainConfigurationCode = 2;

// The programs written so far, and read so far (with the support each was written for). The
// writer's index: version 8 by the programs' bytes (which it writes); version 9 by a hash of the
// canonical program and its support, each candidate compared entry for entry (what equal bytes
// would say), without building the bytes.
struct ChainProgramIndex {
    std::map<std::vector<uint8_t>, uint32_t> bytes;
    std::unordered_multimap<uint64_t, uint32_t> hashed;
    std::vector<std::pair<uint32_t, BasisProgram>> written; // version 9: support, canonical program
};
struct ChainPrograms {
    std::vector<BasisProgram> programs;
    std::vector<uint32_t> support;
};

// After the record's u32 valence (a smooth end's basis; else 0), u32 code (2), u32 support size
// M and u32 levels K, which the caller writes and reads: u32 end (0 leaf: K bands, 1 smooth, 2
// regular), a smooth end's u32 basis (its valence's, an earlier record), u32
// bands, per band u32 program (an index of a program the chunk's chains brought before, or their
// count: u32 support, u32 next-support count, u32 palette size, the palette, a stream of the
// rows as writeProgram's, 48 control rows as varints of row + 1 (0: a phantom) and the next
// support's rows), its three quadrants' kinds (u32 boundary | crease << 4, f32 sharpness) and,
// on a regular end's last band, the corner patch's kind and 16 rows as u32 row + 1.
// Version 9 (`dictionary` given): the fields after the header as varints of one stream, a new
// program as its next-support count and its rows through the dictionary
// (tables_program_dictionary.h), a kind as writeCompactKind's varint (its sharpness mostly the
// previous band's less 1). The programs are written with their rows in canonical order in both.
void writeChainBasis(ByteWriter& w, const IrregularBasis& basis, ChainProgramIndex& programs,
                     ProgramDictionary* dictionary = nullptr);
// Checks every count, index, kind and the chain's shape (band 1's support M, each band's
// support the last one's next support, a smooth end's 2n + 8 points and its basis among
// `earlier`, at most K bands) before expanding, then the weights' range.
IrregularBasis readChainBasis(ByteReader& r, const std::string& what, uint32_t valence, uint32_t support,
                              uint32_t levels, const std::vector<IrregularBasis>& earlier, ChainPrograms& programs,
                              ProgramDictionary* dictionary = nullptr);

} // namespace limn
