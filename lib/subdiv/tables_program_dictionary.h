// TBLS version 9's program dictionary (formats/tbls.md, "Program dictionary"): the bases' and
// chains' one-level programs share their rows and weights across the chunk. A program's rows are
// written in a canonical order (any order in which a row follows the rows it reads expands to the
// same weights, bit for bit), each as a reference to a row the chunk wrote before or as a new row
// that later programs can name; weights come from one palette that grows as rows bring new ones.
// The readers expand the same programs, row for row, as version 8's records hold them.
#pragma once

#include "subdiv/irregular_basis.h"
#include "subdiv/tables_stream.h"

#include <bit>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace limn {

// The writers' hash of a sequence of words (rows, programs), folded in one at a time; equal
// hashes are compared entry for entry, so it only spreads the keys: one multiply a word
// (FxHash's, as rustc's hash tables use).
inline uint64_t mixHash(uint64_t h, uint64_t x) { return (std::rotl(h, 5) ^ x) * 0x517CC1B727220A95u; }

// `p` with its rows in a canonical order, and where each row went (`moved[old] = new`). Order:
// in rounds, the rows whose read rows are all placed, sorted by their entries (sources as
// support points or placed rows' new numbers, weights' bits); equal rows keep their order. A
// program whose row reads a later or missing row comes back as it is (moved the identity), for
// the reader to refuse; control and support rows out of range stay so.
BasisProgram canonicalProgram(const BasisProgram& p, uint32_t support, std::vector<uint32_t>& moved);

// The rows and weights written or read so far in the chunk; one per chunk, in record order.
struct ProgramDictionary {
    BasisProgram rows;          // the rows (start, source, weight, averaged) in the order first written
    std::vector<float> palette; // the weights in the order first written
    // The writer's indices: rows by a hash of their entries (averaged, sources, weights' bits
    // unless averaged), each candidate compared with the row in `rows`; a weight's bits.
    std::unordered_multimap<uint64_t, uint32_t> rowIndex;
    std::unordered_map<uint32_t, uint32_t> slot;
};

// Appends `p` (canonical already) to stream `s`: varint row count, then rows by a varint h: h & 3
// = 1, the dictionary row h >> 2 back from its last (0: the last); h & 3 = 3, that row and the
// next ones in the dictionary, a varint count - 2 following (a run); h even, a new row, which joins the
// dictionary: its head h >> 1 (length << 1 | averaged), then per entry its source and, unless
// averaged, a varint weight slot: below the palette's size that weight, equal to it a new weight
// as 4 raw bytes. Then the 48 control rows as row + 1 (0: a phantom) and the next support's rows
// (its count is the caller's), packed in bit_width(rows + 1) bits each, least significant bit
// first, the last byte's spare bits 0 (std::logic_error for a row beyond that width).
void writeDictionaryProgram(std::vector<uint8_t>& s, const BasisProgram& p, ProgramDictionary& d);
// Reads a program over `support` points with at most `maxRows` rows (16 entries a row at most),
// `next` next-support rows; phantom control rows only where `phantoms`. Every reference, source,
// slot and weight is checked before it is used; failures name the stream's `what`.
BasisProgram readDictionaryProgram(StreamReader& in, uint32_t support, uint64_t maxRows, uint32_t next, bool phantoms,
                                   ProgramDictionary& d);

} // namespace limn
