// Version 4's compact encodings of the TBLS chunk (formats/tbls.md, "Compact encodings"): byte
// streams of LEB128 varints for stencil tables (palette indices and index differences), patch
// records and point lists; and the plain stencil tables of versions 1 to 3.
#pragma once

#include "base/bytes.h"
#include "subdiv/tables.h"

#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn {

// Catmull-Clark's masks (refinement and limit, any valence) have weights of order 1; a finite
// 3e38 can only come from a damaged file, and the GPU's float sums would be NaN.
inline constexpr float kMaxStencilWeight = 1e6f;

// LEB128, 7 bits a byte, least significant first. Inline: the stencil tables and programs write
// hundreds of thousands, most of them one byte.
inline void writeVarint(std::vector<uint8_t>& out, uint64_t x) {
    for (; x >= 0x80; x >>= 7) out.push_back(static_cast<uint8_t>(x | 0x80));
    out.push_back(static_cast<uint8_t>(x));
}
// Signed differences as unsigned varints: 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...
inline uint64_t zigzag(int64_t d) { return d >= 0 ? uint64_t(d) * 2 : uint64_t(-(d + 1)) * 2 + 1; }
inline int64_t unzigzag(uint64_t z) { return (z & 1) ? -int64_t(z >> 1) - 1 : int64_t(z >> 1); }

// A stream: u32 length, the bytes, zero padding to a multiple of 4.
void writeStream(ByteWriter& w, const std::vector<uint8_t>& stream);

// Reads a stream's framing from `r` and its varints after; every failure names `what` and is
// reported through r (ByteReader::fail).
class StreamReader {
public:
    StreamReader(ByteReader& r, std::string what);
    size_t size() const { return data_.size(); }
    uint64_t varint();
    // A u32 given as a zigzag difference from `previous`.
    uint32_t after(uint32_t previous, const char* what);
    float rawFloat(); // 4 raw little-endian bytes
    uint8_t rawByte();
    void finish() {
        if (at_ != data_.size()) fail("unexpected bytes after the last record");
    }
    [[noreturn]] void fail(const std::string& message) const { r_.fail(what_ + ": " + message); }

private:
    ByteReader& r_;
    std::string what_;
    std::span<const uint8_t> data_;
    size_t at_ = 0;
};

// A stencil table in the plain layout (versions 1 to 3) or the compact one (version 4).
void writeStencilTable(ByteWriter& w, const StencilTable& t, bool weights, bool compact);
// Reads a stencil table with `rows` rows whose sources must lie in [lo0, hi0) or [lo1, hi1).
StencilTable readStencilTable(ByteReader& r, bool compact, const std::string& what, uint32_t rows, bool weights,
                              uint32_t lo0, uint32_t hi0, uint32_t lo1 = 0, uint32_t hi1 = 0);

// Checks a stencil table read or expanded from `r`'s chunk as readStencilTable does.
void checkStencilTable(ByteReader& r, const StencilTable& t, const std::string& what, uint32_t rows, bool weights,
                       uint32_t lo0, uint32_t hi0, uint32_t lo1 = 0, uint32_t hi1 = 0);

// The level records: six u32 each (first, face, edge and vertex points, regular patches,
// irregular faces), or (`stream`, version 9) one stream of varints without the first, which
// readLevels sets to where the previous level ends (capped at 2^32 - 1); the caller checks them.
void writeLevels(ByteWriter& w, const std::vector<LevelInfo>& levels, bool stream);
std::vector<LevelInfo> readLevels(ByteReader& r, uint32_t count, bool stream);

// Version 6's repeated levels (formats/limn.md): below a decaying feature the refinement of
// level l is that of level l - 1 one level finer, the same rows over the same neighbours, so
// level l's table is level l - 1's with every source moved to the next level: a source of level
// l - 2 (below `parentFirst`, the first vertex of level l - 1) by parentFirst - grandFirst, one of
// level l - 1 (its face points) by first - parentFirst. The weights are the same bits.
StencilTable shiftedStencilTable(const StencilTable& previous, uint32_t grandFirst, uint32_t parentFirst,
                                 uint32_t first);
// Whether `t` is shiftedStencilTable(previous, ...), without building it (the encoder's test).
bool isShiftedStencilTable(const StencilTable& t, const StencilTable& previous, uint32_t grandFirst,
                           uint32_t parentFirst, uint32_t first);

// Version 6: bit l set when level l's three stencil tables are level l - 1's shifted
// (shiftedStencilTable), with as many face, edge and vertex points; level 1 never is.
uint32_t repeatedLevels(const Tables& t);
// Appends level l's three tables (l >= 2, the levels before it read) as a repeated level stands
// for them, checked as stored ones; refuses (through r) a level of other counts than level l - 1.
void appendRepeatedLevel(ByteReader& r, Tables& t, uint32_t l);

// Version 4's patch records, one stream for the list (the reader is decodeTablesChunk's).
// Without `domains` (version 6's sub-patches) the ptex face and domain are left out: the
// reader takes them from the quadtrees (assignSubPatchDomains, tables_surface_records.h).
void writePatchStream(ByteWriter& w, const std::vector<Patch>& patches, bool domains = true);

} // namespace limn
