#include "subdiv/tables_chain_records.h"

#include "subdiv/crease_basis.h"
#include "subdiv/tables_stream.h"

#include <bit>
#include <cmath>
#include <memory>
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

void writeKind(ByteWriter& w, const CreaseBandKind& k) {
    w.write<uint32_t>(uint32_t(k.boundary) | uint32_t(k.crease) << 4);
    w.write<float>(k.sharpness);
}

CreaseBandKind readKind(ByteReader& r, const std::string& what) {
    const uint32_t bits = r.read<uint32_t>();
    CreaseBandKind k{uint8_t(bits & 15), uint8_t(bits >> 4), r.read<float>()};
    // A single-crease patch has one crease edge, not on its boundary; infinitely sharp at most.
    if (bits >> 8 || (k.crease & (k.crease - 1)) || (k.crease & k.boundary) ||
        !(k.sharpness >= 0 && k.sharpness <= kInfiniteSharpness) || (k.crease && k.sharpness == 0))
        r.fail(what + " has a bad patch kind");
    return k;
}

} // namespace

void writeChainBasis(ByteWriter& w, const IrregularBasis& b, ChainProgramIndex& programs) {
    if (!b.chain) throw std::logic_error("TBLS: a chain basis without its chain");
    const CreaseChain& c = *b.chain;
    w.write<uint32_t>(c.end == CreaseEnd::Leaf ? 0u : c.end == CreaseEnd::Smooth ? 1u : 2u);
    if (c.end == CreaseEnd::Smooth) w.write<uint32_t>(c.endBasis);
    w.write<uint32_t>(static_cast<uint32_t>(c.bands.size()));
    // A chain's bands that share a program hold copies of it, which need not be encoded again.
    const CreaseBand* previous = nullptr;
    uint32_t previousIndex = 0;
    for (const CreaseBand& band : c.bands) {
        if (!previous || previous->support != band.support || !sameProgramBytes(previous->program, band.program)) {
            std::vector<uint8_t> bytes = programBytes(band.program, band.support);
            const auto [it, added] = programs.try_emplace(std::move(bytes), static_cast<uint32_t>(programs.size()));
            previousIndex = it->second;
            w.write<uint32_t>(previousIndex);
            if (added) w.writeArray(it->first);
        } else {
            w.write<uint32_t>(previousIndex);
        }
        previous = &band;
        for (const CreaseBandKind& k : band.kind) writeKind(w, k);
    }
    if (c.end == CreaseEnd::Regular) {
        writeKind(w, c.bands.back().centreKind);
        for (uint32_t x : c.bands.back().centreRow) w.write<uint32_t>(x + 1);
    }
}

IrregularBasis readChainBasis(ByteReader& r, const std::string& what, uint32_t valence, uint32_t M, uint32_t K,
                              const std::vector<IrregularBasis>& earlier, ChainPrograms& programs) {
    auto chain = std::make_shared<CreaseChain>();
    CreaseChain& c = *chain;
    const uint32_t end = r.read<uint32_t>();
    const uint32_t endBasis = end == 1 ? r.read<uint32_t>() : kNone;
    const uint32_t bands = r.read<uint32_t>();
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
        const uint32_t index = r.read<uint32_t>();
        if (index > programs.programs.size()) r.fail(band + " names a missing program");
        if (index == programs.programs.size()) {
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
        for (CreaseBandKind& k : b.kind) k = readKind(r, band);
        c.bands.push_back(std::move(b));
        support = static_cast<uint32_t>(c.bands.back().program.nextSupport.size());
    }
    if (c.end == CreaseEnd::Smooth ? support != 2 * valence + 8 : support != 0)
        r.fail(what + "'s last band has a bad next support for its end");
    if (c.end == CreaseEnd::Regular) {
        CreaseBand& last = c.bands.back();
        last.centreKind = readKind(r, what + " end");
        if (last.centreKind.crease) r.fail(what + "'s regular end has a crease");
        // 0: no row (a boundary phantom, which the expansion makes from the rows beside it), as
        // the program's control rows store it.
        for (uint32_t& x : last.centreRow) {
            const uint32_t v = r.read<uint32_t>();
            if (v > last.program.rows()) r.fail(what + "'s regular end names a missing row");
            x = v == 0 ? kNone : v - 1;
        }
    }
    IrregularBasis basis;
    if (!expandCreaseChain(c, K, basis, endOf)) r.fail(what + " cannot be expanded");
    for (float x : basis.weights)
        if (!(std::abs(x) <= kMaxStencilWeight)) r.fail(what + " has a bad weight");
    basis.chain = std::move(chain);
    return basis;
}

} // namespace limn
