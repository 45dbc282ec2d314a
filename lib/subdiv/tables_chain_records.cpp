#include "subdiv/tables_chain_records.h"

#include "subdiv/crease_basis.h"
#include "subdiv/tables_program_dictionary.h"
#include "subdiv/tables_stream.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

namespace limn {

namespace {

// A band's program can hold about two rows per support point (the children the patches and the
// next support read, and the face points they read); these bounds leave room and keep a hostile
// chain's expansion small.
constexpr uint32_t kMaxChainRowsPerPoint = 3;
constexpr uint32_t kMaxChainEntriesPerRow = 16;
// creaseSupport's faces around four corners of at most kMaxBasisValence faces each.
constexpr uint32_t kMaxChainSupport = 4 * 2 * kMaxBasisValence + 16;

std::vector<uint8_t> programBytes(const BasisProgram& p, uint32_t support) {
    ByteWriter w;
    std::vector<float> palette;
    std::map<uint32_t, uint32_t> slot; // a weight's bits -> its palette index
    std::vector<uint8_t> s;
    writeVarint(s, p.rows());
    for (uint32_t r = 0; r < p.rows(); ++r) {
        writeVarint(s, uint64_t(p.start[r + 1] - p.start[r]) << 1 | p.averaged[r]);
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
            writeVarint(s, p.source[e]);
            if (p.averaged[r]) continue;
            const auto [it, added] =
                slot.try_emplace(std::bit_cast<uint32_t>(p.weight[e]), static_cast<uint32_t>(palette.size()));
            if (added) palette.push_back(p.weight[e]);
            writeVarint(s, it->second);
        }
    }
    for (uint32_t x : p.controlRow) writeVarint(s, x == kNone ? 0 : uint64_t(x) + 1);
    for (uint32_t x : p.nextSupport) writeVarint(s, x);
    w.write<uint32_t>(support);
    w.write<uint32_t>(static_cast<uint32_t>(p.nextSupport.size()));
    w.write<uint32_t>(static_cast<uint32_t>(palette.size()));
    w.writeArray(palette);
    writeStream(w, s);
    return w.take();
}

// Version 9's program index (ChainProgramIndex): the fields programBytes writes, as a hash, and
// their comparison, weights as bits and only where a row is not averaged.
uint64_t programHash(const BasisProgram& p, uint32_t support) {
    uint64_t h = mixHash(support, p.nextSupport.size());
    for (uint32_t r = 0; r < p.rows(); ++r) {
        h = mixHash(h, uint64_t(p.start[r + 1] - p.start[r]) << 1 | p.averaged[r]);
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e)
            h = mixHash(h, uint64_t(p.source[e]) << 32 | (p.averaged[r] ? 0u : std::bit_cast<uint32_t>(p.weight[e])));
    }
    for (uint32_t x : p.controlRow) h = mixHash(h, x);
    for (uint32_t x : p.nextSupport) h = mixHash(h, x);
    return h;
}

bool sameWrittenProgram(const BasisProgram& x, const BasisProgram& y) {
    if (x.start != y.start || x.source != y.source || x.averaged != y.averaged || x.controlRow != y.controlRow ||
        x.nextSupport != y.nextSupport)
        return false;
    for (uint32_t r = 0; r < x.rows(); ++r)
        if (!x.averaged[r])
            for (uint32_t e = x.start[r]; e < x.start[r + 1]; ++e)
                if (std::bit_cast<uint32_t>(x.weight[e]) != std::bit_cast<uint32_t>(y.weight[e])) return false;
    return true;
}

BasisProgram readChainProgram(ByteReader& r, const std::string& what, uint32_t& support) {
    support = r.read<uint32_t>();
    const uint32_t next = r.read<uint32_t>();
    if (support < 4 || support > kMaxChainSupport || next > kMaxChainSupport)
        r.fail(what + " has a bad support size");
    const uint32_t P = r.read<uint32_t>();
    const std::vector<float> palette = r.readArray<float>(P, (what + " palette").c_str());
    for (float x : palette)
        if (!(std::abs(x) <= kMaxStencilWeight)) r.fail(what + " has a bad weight");
    StreamReader in(r, what);
    BasisProgram p;
    const uint64_t rows = in.varint();
    if (rows == 0 || rows > uint64_t(kMaxChainRowsPerPoint) * support) in.fail("bad row count " + std::to_string(rows));
    const uint64_t maxEntries = rows * kMaxChainEntriesPerRow;
    for (uint32_t row = 0; row < rows; ++row) {
        const uint64_t head = in.varint(), length = head >> 1;
        if (length == 0 || length > maxEntries - p.source.size())
            in.fail("row " + std::to_string(row) + " has a bad length");
        const bool averaged = head & 1;
        for (uint64_t e = 0; e < length; ++e) {
            const uint64_t source = in.varint();
            if (source >= uint64_t(support) + row)
                in.fail("row " + std::to_string(row) + " reads neither a support point nor an earlier row");
            p.source.push_back(static_cast<uint32_t>(source));
            if (averaged) {
                p.weight.push_back(1.0f);
                continue;
            }
            const uint64_t slot = in.varint();
            if (slot >= P) in.fail("a weight is not in the palette");
            p.weight.push_back(palette[slot]);
        }
        p.start.push_back(static_cast<uint32_t>(p.source.size()));
        p.averaged.push_back(averaged ? 1 : 0);
    }
    for (uint32_t& x : p.controlRow) {
        const uint64_t v = in.varint();
        if (v > rows) in.fail("a control point names a missing row");
        x = v == 0 ? kNone : static_cast<uint32_t>(v - 1);
    }
    p.nextSupport.resize(next);
    for (uint32_t& x : p.nextSupport) {
        const uint64_t v = in.varint();
        if (v >= rows) in.fail("a support point names a missing row");
        x = static_cast<uint32_t>(v);
    }
    in.finish();
    return p;
}

// Version 9's kind: a varint boundary | crease << 4 | how << 8, the sharpness by `how`: 0 none
// (0), 1 the previous band's in that quadrant less 1, 2 the previous band's, 3 its 4 raw bytes
// (a crease's sharpness counts down band by band).
void writeCompactKind(std::vector<uint8_t>& s, const CreaseBandKind& k, float previous) {
    const uint32_t bits = std::bit_cast<uint32_t>(k.sharpness);
    const uint32_t how = bits == 0 ? 0u : bits == std::bit_cast<uint32_t>(previous - 1.0f) ? 1u
                         : bits == std::bit_cast<uint32_t>(previous) ? 2u : 3u;
    writeVarint(s, uint32_t(k.boundary) | uint32_t(k.crease) << 4 | how << 8);
    if (how == 3)
        for (int i = 0; i < 4; ++i) s.push_back(static_cast<uint8_t>(bits >> (8 * i)));
}

// A kind's checks: a single-crease patch has one crease edge, not on its boundary; infinitely
// sharp at most.
void checkKind(ByteReader& r, uint32_t bits, const CreaseBandKind& k, const std::string& what) {
    if (bits >> 8 || (k.crease & (k.crease - 1)) || (k.crease & k.boundary) ||
        !(k.sharpness >= 0 && k.sharpness <= kInfiniteSharpness) || (k.crease && k.sharpness == 0))
        r.fail(what + " has a bad patch kind");
}

CreaseBandKind readCompactKind(ByteReader& r, StreamReader& in, float previous, const std::string& what) {
    const uint64_t code = in.varint();
    if (code >> 10) r.fail(what + " has a bad patch kind");
    const uint32_t how = static_cast<uint32_t>(code >> 8), bits = static_cast<uint32_t>(code & 0xFF);
    const float sharpness = how == 0 ? 0.0f : how == 1 ? previous - 1.0f : how == 2 ? previous : in.rawFloat();
    CreaseBandKind k{uint8_t(bits & 15), uint8_t(bits >> 4), sharpness};
    checkKind(r, bits, k, what);
    return k;
}

void writeKind(ByteWriter& w, const CreaseBandKind& k) {
    w.write<uint32_t>(uint32_t(k.boundary) | uint32_t(k.crease) << 4);
    w.write<float>(k.sharpness);
}

CreaseBandKind readKind(ByteReader& r, const std::string& what) {
    const uint32_t bits = r.read<uint32_t>();
    CreaseBandKind k{uint8_t(bits & 15), uint8_t(bits >> 4), r.read<float>()};
    checkKind(r, bits, k, what);
    return k;
}

} // namespace

void writeChainBasis(ByteWriter& w, const IrregularBasis& b, ChainProgramIndex& programs, ProgramDictionary* dictionary) {
    if (!b.chain) throw std::logic_error("TBLS: a chain basis without its chain");
    const CreaseChain& c = *b.chain;
    // Version 8: u32 fields, the programs' own bytes; version 9: one stream of varints, the
    // programs through the chunk's dictionary (tables_program_dictionary.h).
    std::vector<uint8_t> s;
    auto number = [&](uint32_t x) {
        if (dictionary)
            writeVarint(s, x);
        else
            w.write<uint32_t>(x);
    };
    number(c.end == CreaseEnd::Leaf ? 0u : c.end == CreaseEnd::Smooth ? 1u : 2u);
    if (c.end == CreaseEnd::Smooth) number(c.endBasis);
    number(static_cast<uint32_t>(c.bands.size()));
    std::vector<uint32_t> moved;
    std::array<float, 3> previous{};
    // A chain's bands often run one program (the sharpness clamped): a band whose program is the
    // last band's names the same entry, neither canonicalised nor looked up again.
    const CreaseBand* last = nullptr;
    BasisProgram canonical;
    auto same = [](const CreaseBand& a, const CreaseBand& o) {
        return a.support == o.support && sameProgramBytes(a.program, o.program);
    };
    uint32_t index = 0;
    for (const CreaseBand& band : c.bands) {
        // A band that runs the last band's program names the same entry without looking it up.
        if (!last || !same(*last, band)) {
            canonical = canonicalProgram(band.program, band.support, moved);
            if (dictionary) {
                const uint64_t h = programHash(canonical, band.support);
                index = kNone;
                for (auto [it, end] = programs.hashed.equal_range(h); it != end && index == kNone; ++it) {
                    const auto& [support, program] = programs.written[it->second];
                    if (support == band.support && sameWrittenProgram(program, canonical)) index = it->second;
                }
                const bool added = index == kNone;
                if (added) {
                    index = static_cast<uint32_t>(programs.written.size());
                    programs.hashed.emplace(h, index);
                }
                number(index);
                if (added) {
                    writeVarint(s, canonical.nextSupport.size());
                    writeDictionaryProgram(s, canonical, *dictionary);
                    programs.written.emplace_back(band.support, std::move(canonical));
                }
            } else {
                const auto [it, added] = programs.bytes.try_emplace(programBytes(canonical, band.support),
                                                                    static_cast<uint32_t>(programs.bytes.size()));
                index = it->second;
                number(index);
                if (added) w.writeArray(it->first);
            }
        } else {
            number(index);
        }
        last = &band;
        for (size_t q = 0; q < 3; ++q) {
            if (dictionary)
                writeCompactKind(s, band.kind[q], previous[q]);
            else
                writeKind(w, band.kind[q]);
            previous[q] = band.kind[q].sharpness;
        }
    }
    if (c.end == CreaseEnd::Regular) {
        if (dictionary)
            writeCompactKind(s, c.bands.back().centreKind, 0.0f);
        else
            writeKind(w, c.bands.back().centreKind);
        // (A row out of range, from damaged tables, stays so: the reader refuses it.)
        for (uint32_t x : c.bands.back().centreRow) number(x < moved.size() ? moved[x] + 1 : x + 1);
    }
    if (dictionary) writeStream(w, s);
}

IrregularBasis readChainBasis(ByteReader& r, const std::string& what, uint32_t valence, uint32_t M, uint32_t K,
                              const std::vector<IrregularBasis>& earlier, ChainPrograms& programs,
                              ProgramDictionary* dictionary) {
    auto chain = std::make_shared<CreaseChain>();
    CreaseChain& c = *chain;
    // Version 9: the record's fields are varints of one stream (writeChainBasis).
    std::optional<StreamReader> in;
    if (dictionary) in.emplace(r, what);
    auto number = [&]() -> uint32_t {
        if (!in) return r.read<uint32_t>();
        const uint64_t x = in->varint();
        if (x > 0xFFFFFFFFu) in->fail("a number out of range");
        return static_cast<uint32_t>(x);
    };
    std::array<float, 3> previous{};
    auto kind = [&](size_t q, const std::string& name) {
        const CreaseBandKind k = in ? readCompactKind(r, *in, previous[q], name) : readKind(r, name);
        previous[q] = k.sharpness;
        return k;
    };
    const uint32_t end = number();
    const uint32_t endBasis = end == 1 ? number() : kNone;
    const uint32_t bands = number();
    if (end > 2 || bands < 1 || bands > K || K > uint32_t(kMaxDepth) || M < 4 || M > kMaxChainSupport ||
        (end == 1 && (valence < 3 || valence == 4 || valence > kMaxBasisValence || bands == K)) ||
        (end != 1 && valence != 0) || (end == 0 && bands != K))
        r.fail(what + " has a bad end, band count, valence or support size");
    c.end = end == 0 ? CreaseEnd::Leaf : end == 1 ? CreaseEnd::Smooth : CreaseEnd::Regular;
    c.valence = valence;
    // A smooth end names its valence's basis, read before it, with the bands left.
    const IrregularBasis* endOf = nullptr;
    if (end == 1) {
        if (endBasis >= earlier.size()) r.fail(what + "'s smooth end names a missing basis");
        endOf = &earlier[endBasis];
        if (endOf->chain || endOf->configuration.boundary || endOf->valence != valence || endOf->levels < K - bands)
            r.fail(what + "'s smooth end names basis " + std::to_string(endBasis) + ", not valence " +
                   std::to_string(valence) + "'s with " + std::to_string(K - bands) + " bands");
        c.endBasis = endBasis;
    }
    uint32_t support = M;
    for (uint32_t j = 0; j < bands; ++j) {
        const std::string band = what + " band " + std::to_string(j + 1);
        const uint32_t index = number();
        if (index > programs.programs.size()) r.fail(band + " names a missing program");
        if (index == programs.programs.size() && in) { // over this band's support
            const uint64_t next = in->varint();
            if (next > kMaxChainSupport) in->fail(band + " has a bad support size");
            programs.programs.push_back(readDictionaryProgram(*in, support, uint64_t(kMaxChainRowsPerPoint) * support,
                                                              static_cast<uint32_t>(next), true, *dictionary));
            programs.support.push_back(support);
        } else if (index == programs.programs.size()) {
            uint32_t s = 0;
            programs.programs.push_back(readChainProgram(r, band + " program", s));
            programs.support.push_back(s);
        }
        // A program's sources were checked against the support it was written for.
        if (programs.support[index] != support)
            r.fail(band + "'s program reads " + std::to_string(programs.support[index]) + " points, not the band's " +
                   std::to_string(support));
        CreaseBand b;
        b.program = programs.programs[index];
        b.support = support;
        for (size_t q = 0; q < 3; ++q) b.kind[q] = kind(q, band);
        c.bands.push_back(std::move(b));
        support = static_cast<uint32_t>(c.bands.back().program.nextSupport.size());
    }
    if (c.end == CreaseEnd::Smooth ? support != 2 * valence + 8 : support != 0)
        r.fail(what + "'s last band has a bad next support for its end");
    if (c.end == CreaseEnd::Regular) {
        CreaseBand& last = c.bands.back();
        previous[0] = 0.0f;
        last.centreKind = kind(0, what + " end");
        if (last.centreKind.crease) r.fail(what + "'s regular end has a crease");
        // 0: no row (a boundary phantom, which the expansion makes from the rows beside it), as
        // the program's control rows store it.
        for (uint32_t& x : last.centreRow) {
            const uint32_t v = number();
            if (v > last.program.rows()) r.fail(what + "'s regular end names a missing row");
            x = v == 0 ? kNone : v - 1;
        }
    }
    if (in) in->finish();
    IrregularBasis basis;
    if (!expandCreaseChain(c, K, basis, endOf)) r.fail(what + " cannot be expanded");
    for (float x : basis.weights)
        if (!(std::abs(x) <= kMaxStencilWeight)) r.fail(what + " has a bad weight");
    basis.chain = std::move(chain);
    return basis;
}

} // namespace limn
