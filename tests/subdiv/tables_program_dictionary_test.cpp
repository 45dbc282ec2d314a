// TBLS version 9's program dictionary and compact chain fields (formats/tbls.md, "Program
// dictionary (version 9)"), field by field on hand-written streams: every damaged field is
// refused by name before it is used (no crash, no allocation from an unchecked count). The
// streams are written here from the format text, not by the encoder under test; each test starts
// from a stream the reader accepts, so a refusal is the damage's.
#include "base/error.h"
#include "subdiv/tables_chain_records.h"
#include "subdiv/tables_program_dictionary.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

using namespace limn;

namespace {

struct StreamBytes {
    std::vector<uint8_t> b;
    StreamBytes& v(uint64_t x) { // LEB128
        for (; x >= 0x80; x >>= 7) b.push_back(uint8_t(x | 0x80));
        b.push_back(uint8_t(x));
        return *this;
    }
    StreamBytes& f(float x) {
        const uint32_t bits = std::bit_cast<uint32_t>(x);
        for (int i = 0; i < 4; ++i) b.push_back(uint8_t(bits >> (8 * i)));
        return *this;
    }
    // Values packed in `width` bits each, least significant bit first, spare bits `spare`.
    StreamBytes& packed(const std::vector<uint32_t>& values, uint32_t width, uint8_t spare = 0) {
        uint64_t pending = 0;
        uint32_t bits = 0;
        for (uint32_t x : values) {
            pending |= uint64_t(x) << bits;
            for (bits += width; bits >= 8; bits -= 8, pending >>= 8) b.push_back(uint8_t(pending));
        }
        if (bits) b.push_back(uint8_t(pending | uint32_t(spare) << bits));
        return *this;
    }
    StreamBytes& raw(std::initializer_list<uint8_t> bytes) {
        b.insert(b.end(), bytes);
        return *this;
    }
    StreamBytes& add(const StreamBytes& o) {
        b.insert(b.end(), o.b.begin(), o.b.end());
        return *this;
    }
};

// u32 length, the bytes, zero padding to 4.
std::vector<uint8_t> framed(const std::vector<uint8_t>& s) {
    std::vector<uint8_t> out;
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(s.size() >> (8 * i)));
    out.insert(out.end(), s.begin(), s.end());
    while (out.size() % 4) out.push_back(0);
    return out;
}

std::vector<uint32_t> repeated(size_t n, uint32_t x) { return std::vector<uint32_t>(n, x); }

// A program over 4 support points of one new row (source 0, a new weight 1) and 48 control
// rows naming it (row + 1 = 1, in bit_width(2) = 2 bits), then `next` next-support rows 0.
StreamBytes oneRowProgram(uint32_t source = 0, uint32_t next = 0) {
    StreamBytes s;
    s.v(1).v(1 << 2).v(source).v(0).f(1.0f); // rows; new row: length 1, weighted; source; slot 0 = a new weight
    std::vector<uint32_t> rows = repeated(48, 1);
    rows.insert(rows.end(), next, 0);
    return s.packed(rows, 2);
}

BasisProgram readProgram(const StreamBytes& s, ProgramDictionary& d, uint32_t support = 4, uint64_t maxRows = 12,
                         uint32_t next = 0, bool phantoms = false) {
    const std::vector<uint8_t> bytes = framed(s.b);
    ByteReader r(bytes, "test");
    StreamReader in(r, "program");
    BasisProgram p = readDictionaryProgram(in, support, maxRows, next, phantoms, d);
    in.finish();
    return p;
}

void expectRefused(const std::function<void()>& read, const std::string& why) {
    try {
        read();
        ADD_FAILURE() << "accepted: " << why;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
}

// A dictionary holding three rows over 4 points (sources 0, 1, 2), one weight (1).
ProgramDictionary threeRows() {
    ProgramDictionary d;
    StreamBytes s;
    s.v(3).v(4).v(0).v(0).f(1.0f).v(4).v(1).v(0).v(4).v(2).v(0).packed(repeated(48, 1), 3); // bit_width(4) bits
    readProgram(s, d);
    return d;
}

} // namespace

TEST(TablesProgramDictionary, HostileRowsAndRunsAreRefused) {
    ProgramDictionary d;
    EXPECT_EQ(readProgram(oneRowProgram(), d).rows(), 1u); // the base the damage starts from
    auto refused = [](const StreamBytes& s, const std::string& why, uint32_t support = 4) {
        ProgramDictionary fresh = threeRows();
        expectRefused([&] { readProgram(s, fresh, support); }, why);
    };
    refused(StreamBytes().v(0), "bad row count 0");
    refused(StreamBytes().v(13), "bad row count 13"); // above maxRows (12)
    refused(StreamBytes().v(uint64_t(1) << 40), "bad row count"); // nothing allocated from it
    refused(StreamBytes().v(1).v(0 << 2), "row 0 has a bad length");          // a new row of no entries
    refused(StreamBytes().v(1).v(17 << 2), "row 0 has a bad length"); // 16 entries a row of the program
    refused(StreamBytes().v(1).v(1 << 2).v(4), "reads neither a support point nor an earlier row");
    refused(StreamBytes().v(1).v(1 << 2).v(0).v(2), "not in the palette"); // the palette holds 1 weight
    for (float w : {std::nanf(""), std::numeric_limits<float>::infinity(), 2e6f})
        refused(StreamBytes().v(1).v(1 << 2).v(0).v(1).f(w), "bad weight");
    // Named rows: h & 3 = 1 one row `back` from the last; h & 3 = 3 a run, its length less 2 after.
    refused(StreamBytes().v(1).v(3 << 2 | 1), "row 0 names a missing dictionary row"); // 3 rows: back 0..2
    refused(StreamBytes().v(2).v(0 << 2 | 3).v(0), "row 0 names a missing dictionary row"); // 2 rows from the last
    refused(StreamBytes().v(2).v(2 << 2 | 3).v(1), "row 0 has a bad run length");  // 3 rows in a program of 2
    refused(StreamBytes().v(2).v(0 << 2 | 1).v(0 << 2 | 3).v(0), "row 1 has a bad run length"); // 1 row left
    refused(StreamBytes().v(2).v(2 << 2 | 3).v(uint64_t(1) << 63), "row 0 has a bad run length");
    // A named row's sources are checked against this program's support: row 2 reads point 2.
    refused(StreamBytes().v(1).v(0 << 2 | 1), "row 0 reads neither a support point nor an earlier row", 2);
    refused(StreamBytes().v(1).raw({0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x02}), "longer than 64 bits");
    refused(StreamBytes().v(1).raw({0x80}), "ends inside a number");
    {
        // A named row brings its entries into this program's 16 a row: a row of 20 entries (from a
        // program of 2 rows, 32 entries) cannot be the one row of another.
        ProgramDictionary d20;
        StreamBytes wide;
        wide.v(2).v(20 << 2).v(0).v(0).f(0.05f);
        for (int e = 1; e < 20; ++e) wide.v(0).v(0);
        wide.v(4).v(1).v(0).packed(repeated(48, 1), 2);
        readProgram(wide, d20);
        expectRefused([&] { readProgram(StreamBytes().v(1).v(1 << 2 | 1).packed(repeated(48, 1), 2), d20); },
                      "row 0 has a bad length");
        readProgram(StreamBytes().v(1).v(0 << 2 | 1).packed(repeated(48, 1), 2), d20); // the 1-entry row is fine
    }
    {
        ProgramDictionary three = threeRows();
        StreamBytes run; // the three rows as one run, the control rows naming row 3
        run.v(3).v(2 << 2 | 3).v(1).packed(repeated(48, 3), 3); // bit_width(4) bits
        const BasisProgram p = readProgram(run, three);
        EXPECT_EQ(p.source, (std::vector<uint32_t>{0, 1, 2}));
        EXPECT_EQ(p.controlRow[0], 2u);
    }
}

// The control rows (row + 1, 0 a phantom) and next-support rows, packed in bit_width(rows + 1)
// bits: a value naming no row, a phantom where none may be, and spare bits that are not 0.
TEST(TablesProgramDictionary, HostilePackedRowsAreRefused) {
    auto refused = [](const StreamBytes& s, const std::string& why, uint32_t next = 0, bool phantoms = false) {
        ProgramDictionary d;
        expectRefused([&] { readProgram(s, d, 4, 12, next, phantoms); }, why);
    };
    auto head = [] { return StreamBytes().v(1).v(1 << 2).v(0).v(0).f(1.0f); };
    std::vector<uint32_t> rows = repeated(48, 1);
    rows[7] = 2; // row 1 of a program of 1
    refused(StreamBytes(head()).packed(rows, 2), "a control point names a missing row");
    rows[7] = 0; // a phantom
    refused(StreamBytes(head()).packed(rows, 2), "a control point names a missing row");
    {
        ProgramDictionary d;
        EXPECT_EQ(readProgram(StreamBytes(head()).packed(rows, 2), d, 4, 12, 0, true).controlRow[7], kNone);
    }
    std::vector<uint32_t> withNext = repeated(48, 1);
    withNext.push_back(0);
    withNext.push_back(1); // next-support rows are rows, not row + 1: 1 names no row
    refused(StreamBytes(head()).packed(withNext, 2), "a support point names a missing row", 2);
    withNext.back() = 0;
    {
        ProgramDictionary d;
        EXPECT_EQ(readProgram(StreamBytes(head()).packed(withNext, 2), d, 4, 12, 2).nextSupport.size(), 2u);
    }
    // 50 values of 2 bits end inside a byte: its 4 spare bits must be 0.
    refused(StreamBytes(head()).packed(withNext, 2, 0x1), "spare bits are not 0", 2);
    refused(StreamBytes(head()).packed(withNext, 2, 0x8), "spare bits are not 0", 2);
    refused(StreamBytes(head()).packed(repeated(40, 1), 2), "ends inside a record");
}

namespace {

// A leaf chain of one band over 4 points (valence 0, K = 1): end 0, 1 band, program 0 (new, no
// next support); the band's three kinds and, for a regular end (end 2), its kind and 16 rows
// follow.
StreamBytes chainHead(uint32_t end = 0) {
    return StreamBytes().v(end).v(1).v(0).v(0).add(oneRowProgram());
}

void readChain(const StreamBytes& s) {
    const std::vector<uint8_t> bytes = framed(s.b);
    ByteReader r(bytes, "test");
    ChainPrograms programs;
    ProgramDictionary d;
    const IrregularBasis b = readChainBasis(r, "chain", 0, 4, 1, {}, programs, &d);
    EXPECT_EQ(b.weights.size(), 48u * 4);
}

} // namespace

// A kind is a varint boundary | crease << 4 | how << 8, its sharpness 0, the previous band's less
// 1, the previous band's, or 4 raw bytes; the previous of band 1 and of a regular end's kind is 0.
TEST(TablesProgramDictionary, HostileCompactChainFieldsAreRefused) {
    readChain(StreamBytes(chainHead()).v(0).v(0).v(0));
    const StreamBytes sharp3 = StreamBytes().v(0x10 | 3 << 8).f(3.0f); // a crease of sharpness 3
    readChain(StreamBytes(chainHead()).add(sharp3).v(0).v(0));
    auto refused = [](const StreamBytes& s, const std::string& why) { expectRefused([&] { readChain(s); }, why); };
    refused(StreamBytes(chainHead()).v(1 << 8).v(0).v(0), "bad patch kind");          // 0 - 1 on band 1
    refused(StreamBytes(chainHead()).v(0x10 | 2 << 8).v(0).v(0), "bad patch kind");   // a crease of the previous 0
    refused(StreamBytes(chainHead()).v(0x10).v(0).v(0), "bad patch kind");            // a crease of sharpness 0
    for (float x : {std::nanf(""), std::numeric_limits<float>::infinity(), -0.5f, 10.5f})
        refused(StreamBytes(chainHead()).v(3 << 8).f(x).v(0).v(0), "bad patch kind");
    refused(StreamBytes(chainHead()).v(4 << 8).v(0).v(0), "bad patch kind");          // how 4
    refused(StreamBytes(chainHead()).v(0x30 | 3 << 8).f(2.0f).v(0).v(0), "bad patch kind"); // two crease edges
    refused(StreamBytes(chainHead()).v(0x11 | 3 << 8).f(2.0f).v(0).v(0), "bad patch kind"); // a crease on the boundary
    // A regular end's kind starts from 0 again: "less 1" is -1 there, not band 1's 3 - 1.
    StreamBytes regular = StreamBytes(chainHead(2)).add(sharp3).v(0).v(0);
    StreamBytes centreRows;
    for (int i = 0; i < 16; ++i) centreRows.v(1);
    readChain(StreamBytes(regular).v(0).add(centreRows));
    refused(StreamBytes(regular).v(1 << 8).add(centreRows), "bad patch kind");
    refused(StreamBytes(regular).v(0).v(2), "regular end names a missing row"); // row 1 of a program of 1
    // Numbers are u32s as varints: 2^32 overflows; counts are bounded before anything is sized.
    refused(StreamBytes().v(uint64_t(1) << 32), "a number out of range");
    refused(StreamBytes().v(0).v(uint64_t(1) << 32), "a number out of range");
    refused(StreamBytes().v(0).v(1).v(1), "band 1 names a missing program");
    refused(StreamBytes().v(0).v(1).v(0).v(529), "bad support size");
    refused(StreamBytes().v(0).v(1).v(0).v(uint64_t(1) << 40), "bad support size");
    refused(StreamBytes().v(0).v(1).v(0).v(0).v(13), "bad row count 13"); // 3 rows a support point
    refused(StreamBytes(chainHead()).v(0).v(0).v(0).v(0), "unexpected bytes after the last record");
}

// Version 9's level records: per level five counts as varints of one stream (each level's first
// is where the previous ends): a count past 2^32 - 1, a stream cut short or one with bytes left.
TEST(TablesProgramDictionary, HostileLevelStreamIsRefused) {
    auto levels = [](const StreamBytes& s, uint32_t count) {
        const std::vector<uint8_t> bytes = framed(s.b);
        ByteReader r(bytes, "test");
        return readLevels(r, count, true);
    };
    const std::vector<LevelInfo> two = levels(StreamBytes().v(0).v(0).v(9).v(0).v(1).v(1).v(2).v(3).v(4).v(5), 2);
    EXPECT_EQ(two[1].first, 9u);
    EXPECT_EQ(two[1].vertexPoints, 3u);
    expectRefused([&] { levels(StreamBytes().v(0).v(0).v(uint64_t(1) << 32).v(0).v(0), 1); }, "a count out of range");
    expectRefused([&] { levels(StreamBytes().v(0).v(0).v(9).v(0), 1); }, "ends inside a number");
    expectRefused([&] { levels(StreamBytes().v(0).v(0).v(9).v(0).v(0).v(0), 1); }, "unexpected bytes");
    // Every stream's padding to 4 bytes MUST be 0 (5 bytes of counts, 3 of padding).
    std::vector<uint8_t> padded = framed(StreamBytes().v(0).v(0).v(9).v(0).v(0).b);
    padded.back() = 1;
    expectRefused([&] { ByteReader r(padded, "test"); readLevels(r, 1, true); }, "padding is not zero");
}
