#include "subdiv/tables_program_dictionary.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace limn {

namespace {

constexpr uint32_t kMaxDictionaryEntriesPerRow = 16;

void appendRawFloat(std::vector<uint8_t>& s, float x) {
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    for (int i = 0; i < 4; ++i) s.push_back(static_cast<uint8_t>(bits >> (8 * i)));
}

} // namespace

BasisProgram canonicalProgram(const BasisProgram& p, uint32_t support, std::vector<uint32_t>& moved) {
    const uint32_t n = p.rows();
    moved.assign(n, kNone);
    // A row's entries as the sequence averaged, then per entry its source (a placed row's new
    // number after the support) and weight bits (0 when averaged), compared in place.
    auto source = [&](uint32_t e) { return p.source[e] < support ? uint64_t(p.source[e]) : uint64_t(support) + moved[p.source[e] - support]; };
    auto bits = [&](uint32_t r, uint32_t e) { return p.averaged[r] ? 0u : std::bit_cast<uint32_t>(p.weight[e]); };
    auto before = [&](uint32_t a, uint32_t b) {
        if (p.averaged[a] != p.averaged[b]) return p.averaged[a] < p.averaged[b];
        const uint32_t na = p.start[a + 1] - p.start[a], nb = p.start[b + 1] - p.start[b];
        for (uint32_t i = 0; i < std::min(na, nb); ++i) {
            const uint32_t ea = p.start[a] + i, eb = p.start[b] + i;
            if (source(ea) != source(eb)) return source(ea) < source(eb);
            if (bits(a, ea) != bits(b, eb)) return bits(a, ea) < bits(b, eb);
        }
        return na < nb;
    };
    std::vector<uint32_t> order;
    order.reserve(n);
    // Each row's first entry (averaged, source, weight bits) as one number ordered as `before`
    // orders rows on it (a source from 2^24 on as 2^24 - 1 and its bits as 0, for `before` to
    // settle): most comparisons end there.
    std::vector<uint64_t> key(n);
    auto keyed = [&](uint32_t a, uint32_t b) { return key[a] != key[b] ? key[a] < key[b] : before(a, b); };
    // One round's rows, in row order, sorted stably (by binary insertion: a round has a few dozen
    // rows, and std::stable_sort would allocate its buffer every round) and placed.
    auto place = [&](std::vector<uint32_t>::iterator first, std::vector<uint32_t>::iterator last) {
        for (auto it = first; it != last; ++it) {
            const uint32_t e = p.start[*it];
            const uint64_t x = e < p.start[*it + 1] ? source(e) : 0;
            const uint64_t entry = e == p.start[*it + 1] ? 0 // an empty row first, as `before` has it
                                   : x < 0xFFFFFF        ? x << 32 | bits(*it, e)
                                                         : uint64_t(0xFFFFFF) << 32;
            key[*it] = uint64_t(p.averaged[*it]) << 56 | entry;
        }
        for (auto it = first; it != last; ++it) {
            const uint32_t r = *it;
            const auto to = std::upper_bound(first, it, r, keyed);
            std::move_backward(to, it, it + 1);
            *to = r;
        }
        for (auto it = first; it != last; ++it) {
            moved[*it] = static_cast<uint32_t>(order.size());
            order.push_back(*it);
        }
    };
    // Where every row reads only support points and earlier rows (as the builders write them), a
    // row's round is 1 + the latest round of the rows it reads (0: support points only), found in
    // one pass; the rows are bucketed by round, in row order.
    std::vector<uint32_t> round(n), ready;
    uint32_t rounds = 0;
    bool forward = true;
    for (uint32_t r = 0; r < n && forward; ++r) {
        uint32_t k = 0;
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
            const uint32_t x = p.source[e];
            if (x < support) continue;
            if (x - support >= r) {
                forward = false;
                break;
            }
            k = std::max(k, round[x - support] + 1);
        }
        round[r] = k;
        rounds = std::max(rounds, k + 1);
    }
    if (forward) {
        std::vector<uint32_t> at(rounds + 1, 0);
        for (uint32_t r = 0; r < n; ++r) ++at[round[r] + 1];
        for (uint32_t k = 0; k < rounds; ++k) at[k + 1] += at[k];
        ready.resize(n);
        std::vector<uint32_t> fill(at.begin(), at.end() - 1);
        for (uint32_t r = 0; r < n; ++r) ready[fill[round[r]]++] = r;
        for (uint32_t k = 0; k < rounds; ++k) place(ready.begin() + at[k], ready.begin() + at[k + 1]);
    }
    // Otherwise in rounds: the rows not placed whose read rows all are.
    ready.reserve(n);
    while (order.size() < n) {
        ready.clear();
        for (uint32_t r = 0; r < n; ++r) {
            if (moved[r] != kNone) continue;
            bool placed = true;
            for (uint32_t e = p.start[r]; e < p.start[r + 1] && placed; ++e)
                placed = p.source[e] < support || (p.source[e] - support < n && moved[p.source[e] - support] != kNone);
            if (placed) ready.push_back(r);
        }
        if (ready.empty()) { // a row reads a later or missing row: written as it is, for the reader to refuse
            for (uint32_t r = 0; r < n; ++r) moved[r] = r;
            return p;
        }
        place(ready.begin(), ready.end());
    }
    BasisProgram c; // start holds its first 0
    c.start.reserve(n + 1);
    c.source.reserve(p.source.size());
    c.weight.reserve(p.source.size());
    c.averaged.reserve(n);
    for (uint32_t r : order) {
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
            const uint32_t s = p.source[e];
            c.source.push_back(s < support ? s : support + moved[s - support]);
            c.weight.push_back(p.weight[e]);
        }
        c.start.push_back(static_cast<uint32_t>(c.source.size()));
        c.averaged.push_back(p.averaged[r]);
    }
    // (Rows out of range stay so: the reader refuses them.)
    for (size_t i = 0; i < c.controlRow.size(); ++i)
        c.controlRow[i] = p.controlRow[i] < n ? moved[p.controlRow[i]] : p.controlRow[i];
    c.nextSupport.reserve(p.nextSupport.size());
    for (uint32_t x : p.nextSupport) c.nextSupport.push_back(x < n ? moved[x] : x);
    return c;
}

void writeDictionaryProgram(std::vector<uint8_t>& s, const BasisProgram& p, ProgramDictionary& d) {
    writeVarint(s, p.rows());
    // Row r of `p` against dictionary row k: the same entries, weights compared as bits unless
    // averaged (an averaged row's weights are not written).
    auto sameRow = [&](uint32_t r, uint32_t k) {
        const uint32_t n = p.start[r + 1] - p.start[r], from = d.rows.start[k];
        if (p.averaged[r] != d.rows.averaged[k] || d.rows.start[k + 1] - from != n) return false;
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t e = p.start[r] + i;
            if (p.source[e] != d.rows.source[from + i]) return false;
            if (!p.averaged[r] && std::bit_cast<uint32_t>(p.weight[e]) != std::bit_cast<uint32_t>(d.rows.weight[from + i]))
                return false;
        }
        return true;
    };
    auto hashRow = [&](uint32_t r) {
        uint64_t h = mixHash(0x9E3779B97F4A7C15u, p.averaged[r]);
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e)
            h = mixHash(h, uint64_t(p.source[e]) << 32 | (p.averaged[r] ? 0u : std::bit_cast<uint32_t>(p.weight[e])));
        return h;
    };
    auto known = [&](uint32_t r, uint64_t h) {
        for (auto [it, end] = d.rowIndex.equal_range(h); it != end; ++it)
            if (sameRow(r, it->second)) return it->second;
        return kNone;
    };
    for (uint32_t r = 0; r < p.rows();) {
        const uint64_t h = hashRow(r);
        if (const uint32_t first = known(r, h); first != kNone) {
            // A run of rows written before, one after the other in the dictionary (each row is
            // there once: the next row continues the run exactly when it equals the next one).
            uint32_t length = 1;
            while (r + length < p.rows() && first + length < d.rows.rows() && sameRow(r + length, first + length))
                ++length;
            const uint64_t back = d.rows.rows() - 1 - first;
            writeVarint(s, back << 2 | (length > 1 ? 3 : 1));
            if (length > 1) writeVarint(s, length - 2);
            r += length;
            continue;
        }
        d.rowIndex.emplace(h, d.rows.rows());
        writeVarint(s, (uint64_t(p.start[r + 1] - p.start[r]) << 1 | p.averaged[r]) << 1);
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
            writeVarint(s, p.source[e]);
            d.rows.source.push_back(p.source[e]);
            d.rows.weight.push_back(p.weight[e]);
            if (p.averaged[r]) continue;
            const auto [slot, fresh] =
                d.slot.try_emplace(std::bit_cast<uint32_t>(p.weight[e]), static_cast<uint32_t>(d.palette.size()));
            writeVarint(s, slot->second);
            if (fresh) {
                d.palette.push_back(p.weight[e]);
                appendRawFloat(s, p.weight[e]);
            }
        }
        d.rows.start.push_back(static_cast<uint32_t>(d.rows.source.size()));
        d.rows.averaged.push_back(p.averaged[r]);
        ++r;
    }
    // The control rows (row + 1, 0 a phantom) and the next support's rows, each in
    // bit_width(rows + 1) bits, least significant first, the last byte's spare bits 0.
    const uint32_t width = static_cast<uint32_t>(std::bit_width(uint64_t(p.rows()) + 1));
    uint64_t pending = 0;
    uint32_t bits = 0;
    auto put = [&](uint64_t x) {
        if (x >> width) throw std::logic_error("TBLS: a control or support row beyond what its width holds");
        pending |= x << bits;
        for (bits += width; bits >= 8; bits -= 8, pending >>= 8) s.push_back(static_cast<uint8_t>(pending));
    };
    for (uint32_t x : p.controlRow) put(x == kNone ? 0 : uint64_t(x) + 1);
    for (uint32_t x : p.nextSupport) put(x);
    if (bits) s.push_back(static_cast<uint8_t>(pending));
}

BasisProgram readDictionaryProgram(StreamReader& in, uint32_t support, uint64_t maxRows, uint32_t next, bool phantoms,
                                   ProgramDictionary& d) {
    BasisProgram p;
    const uint64_t rows = in.varint();
    if (rows == 0 || rows > maxRows) in.fail("bad row count " + std::to_string(rows));
    const uint64_t maxEntries = rows * kMaxDictionaryEntriesPerRow;
    for (uint32_t row = 0; row < rows;) {
        const uint64_t code = in.varint();
        const std::string at = "row " + std::to_string(row);
        if (code & 1) { // rows written before, `back` from the last: their sources checked here
            const uint64_t back = code >> 2, extra = (code & 2) ? in.varint() : 0, left = rows - row;
            // A run's length less 2 is stored (one row is h & 3 = 1): 2 rows or more, within the
            // program's rows left and the dictionary's rows from the one named.
            if ((code & 2) && (left < 2 || extra > left - 2)) in.fail(at + " has a bad run length");
            const uint64_t run = (code & 2) ? extra + 2 : 1;
            if (back >= d.rows.rows() || run > back + 1) in.fail(at + " names a missing dictionary row");
            const uint32_t ref = d.rows.rows() - 1 - static_cast<uint32_t>(back);
            for (uint32_t k = 0; k < run; ++k, ++row) {
                const uint32_t from = d.rows.start[ref + k], to = d.rows.start[ref + k + 1];
                if (to - from > maxEntries - p.source.size()) in.fail(at + " has a bad length");
                for (uint32_t e = from; e < to; ++e) {
                    if (d.rows.source[e] >= uint64_t(support) + row)
                        in.fail(at + " reads neither a support point nor an earlier row");
                    p.source.push_back(d.rows.source[e]);
                    p.weight.push_back(d.rows.weight[e]);
                }
                p.averaged.push_back(d.rows.averaged[ref + k]);
                p.start.push_back(static_cast<uint32_t>(p.source.size()));
            }
            continue;
        }
        {
            const uint64_t head = code >> 1, length = head >> 1;
            if (length == 0 || length > maxEntries - p.source.size()) in.fail(at + " has a bad length");
            const bool averaged = head & 1;
            for (uint64_t e = 0; e < length; ++e) {
                const uint64_t source = in.varint();
                if (source >= uint64_t(support) + row) in.fail(at + " reads neither a support point nor an earlier row");
                float w = 1.0f;
                if (!averaged) {
                    const uint64_t slot = in.varint();
                    if (slot > d.palette.size()) in.fail("a weight is not in the palette");
                    if (slot == d.palette.size()) {
                        const float x = in.rawFloat();
                        if (!(std::abs(x) <= kMaxStencilWeight)) in.fail("has a bad weight");
                        d.palette.push_back(x);
                    }
                    w = d.palette[slot];
                }
                p.source.push_back(static_cast<uint32_t>(source));
                p.weight.push_back(w);
                d.rows.source.push_back(static_cast<uint32_t>(source));
                d.rows.weight.push_back(w);
            }
            d.rows.start.push_back(static_cast<uint32_t>(d.rows.source.size()));
            d.rows.averaged.push_back(averaged ? 1 : 0);
            p.averaged.push_back(averaged ? 1 : 0);
        }
        p.start.push_back(static_cast<uint32_t>(p.source.size()));
        ++row;
    }
    const uint32_t width = static_cast<uint32_t>(std::bit_width(rows + 1)); // rows <= maxRows: a few thousand
    uint64_t pending = 0;
    uint32_t bits = 0;
    auto take = [&]() -> uint64_t {
        for (; bits < width; bits += 8) pending |= uint64_t(in.rawByte()) << bits;
        const uint64_t x = pending & ((uint64_t(1) << width) - 1);
        pending >>= width;
        bits -= width;
        return x;
    };
    for (uint32_t& x : p.controlRow) {
        const uint64_t v = take();
        if (v > rows || (v == 0 && !phantoms)) in.fail("a control point names a missing row");
        x = v == 0 ? kNone : static_cast<uint32_t>(v - 1);
    }
    p.nextSupport.resize(next);
    for (uint32_t& x : p.nextSupport) {
        const uint64_t v = take();
        if (v >= rows) in.fail("a support point names a missing row");
        x = static_cast<uint32_t>(v);
    }
    if (pending != 0) in.fail("the packed rows' spare bits are not 0");
    return p;
}

} // namespace limn
