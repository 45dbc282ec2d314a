#include "subdiv/tables_stream.h"

#include "base/cli.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

namespace limn {

void writeStream(ByteWriter& w, const std::vector<uint8_t>& stream) {
    w.write<uint32_t>(static_cast<uint32_t>(stream.size()));
    w.writeArray(stream);
    w.padTo(4);
}

// Version 4's stencil table (formats/tbls.md, "Compact encodings"): the weights as indices
// into the table's distinct values (Catmull-Clark's masks repeat a few hundred values), the
// sources as varint differences from the previous source (a row's sources are neighbours), the
// rows as varint lengths: about a third of the plain layout, with the same numbers once read.
void writeStencilTable(ByteWriter& w, const StencilTable& t, bool weights, bool compact) {
    if (!compact) { // versions 1 to 3
        w.write<uint32_t>(static_cast<uint32_t>(t.rows()));
        w.write<uint32_t>(static_cast<uint32_t>(t.indices.size()));
        w.write<uint32_t>(weights ? 1u : 0u);
        w.write<uint32_t>(0);
        w.writeArray(t.start);
        w.writeArray(t.indices);
        if (weights) w.writeArray(t.weights);
        return;
    }
    std::vector<float> palette;
    std::unordered_map<uint32_t, uint32_t> slot; // a weight's bits -> its palette index
    std::vector<uint8_t> stream;
    stream.reserve(t.indices.size() * 3 + t.rows());
    int64_t previousFirst = 0;
    for (size_t r = 0; r < t.rows(); ++r) {
        writeVarint(stream, t.start[r + 1] - t.start[r]);
        int64_t previous = previousFirst;
        for (uint32_t k = t.start[r]; k < t.start[r + 1]; ++k) {
            writeVarint(stream, zigzag(int64_t(t.indices[k]) - previous));
            previous = t.indices[k];
            if (k == t.start[r]) previousFirst = previous;
            if (!weights) continue;
            const uint32_t bits = std::bit_cast<uint32_t>(t.weights[k]);
            auto [it, added] = slot.try_emplace(bits, static_cast<uint32_t>(palette.size()));
            if (added) palette.push_back(t.weights[k]);
            writeVarint(stream, it->second);
        }
    }
    w.write<uint32_t>(static_cast<uint32_t>(t.rows()));
    w.write<uint32_t>(static_cast<uint32_t>(t.indices.size()));
    w.write<uint32_t>(weights ? 1u : 0u);
    w.write<uint32_t>(static_cast<uint32_t>(palette.size()));
    w.writeArray(palette);
    writeStream(w, stream);
}

StencilTable readStencilTable(ByteReader& r, bool compact, const std::string& what, uint32_t rows, bool weights,
                              uint32_t lo0, uint32_t hi0, uint32_t lo1, uint32_t hi1) {
    StencilTable t;
    uint32_t n = r.read<uint32_t>(), entries = r.read<uint32_t>(), hasWeights = r.read<uint32_t>();
    const uint32_t fourth = r.read<uint32_t>(); // version 4: the palette's size; before: reserved
    if (!compact && fourth != 0) r.fail(what + ": reserved field is not zero");
    if (n != rows)
        r.fail(what + ": " + std::to_string(n) + " rows, expected " + std::to_string(rows));
    if (hasWeights != (weights ? 1u : 0u)) r.fail(what + ": weight flag is wrong");
    if (compact) {
        if (!weights && fourth != 0) r.fail(what + ": a palette without weights");
        const std::vector<float> palette = r.readArray<float>(fourth, (what + " palette").c_str());
        for (float x : palette)
            if (!(std::abs(x) <= kMaxStencilWeight))
                r.fail(what + ": a palette weight is " + cli::shortNumber(x) +
                       "; a stencil weight must be finite and within +-1e6");
        StreamReader in(r, what);
        // Every entry takes at least one byte (two when weighted), every row one.
        if (rows > in.size() || entries > in.size() / (weights ? 2 : 1))
            in.fail(std::to_string(entries) + " entries do not fit in " + std::to_string(in.size()) + " bytes");
        t.start.reserve(uint64_t(rows) + 1); // holds its leading 0
        t.indices.reserve(entries);
        if (weights) t.weights.reserve(entries);
        uint32_t previousFirst = 0;
        for (uint32_t i = 0; i < rows; ++i) {
            const uint64_t length = in.varint();
            if (length > (1u << 16) || length > entries - t.indices.size())
                in.fail("row " + std::to_string(i) + " has a bad length");
            uint32_t previous = previousFirst;
            for (uint32_t k = 0; k < length; ++k) {
                previous = in.after(previous, "a source index");
                t.indices.push_back(previous);
                if (k == 0) previousFirst = previous;
                if (!weights) continue;
                const uint64_t p = in.varint();
                if (p >= palette.size()) in.fail("a weight is not in the palette");
                t.weights.push_back(palette[p]);
            }
            t.start.push_back(static_cast<uint32_t>(t.indices.size()));
        }
        if (t.indices.size() != entries)
            in.fail(std::to_string(t.indices.size()) + " entries, expected " + std::to_string(entries));
        in.finish();
    } else {
        t.start = r.readArray<uint32_t>(uint64_t(rows) + 1, (what + " starts").c_str());
        t.indices = r.readArray<uint32_t>(entries, (what + " indices").c_str());
        if (weights) t.weights = r.readArray<float>(entries, (what + " weights").c_str());
    }
    checkStencilTable(r, t, what, rows, weights, lo0, hi0, lo1, hi1);
    return t;
}

void checkStencilTable(ByteReader& r, const StencilTable& t, const std::string& what, uint32_t rows, bool weights,
                       uint32_t lo0, uint32_t hi0, uint32_t lo1, uint32_t hi1) {
    const uint32_t entries = static_cast<uint32_t>(t.indices.size());
    if (t.start.size() != uint64_t(rows) + 1)
        r.fail(what + ": " + std::to_string(t.start.size() - 1) + " rows, expected " + std::to_string(rows));
    if (t.start[0] != 0 || t.start[rows] != entries)
        r.fail(what + ": row starts do not span the " + std::to_string(entries) + " entries");
    for (uint32_t i = 0; i < rows; ++i)
        if (t.start[i + 1] < t.start[i] || t.start[i + 1] - t.start[i] > (1u << 16))
            r.fail(what + ": row " + std::to_string(i) + " has a bad length");
    for (uint32_t i = 0; i < entries; ++i) {
        uint32_t x = t.indices[i];
        if (!((x >= lo0 && x < hi0) || (x >= lo1 && x < hi1)))
            r.fail(what + ": entry " + std::to_string(i) + " reads vertex " + std::to_string(x) +
                   " outside the levels it may read");
        // Catmull-Clark's masks (refinement and limit, any valence) have weights of order 1; a
        // finite 3e38 can only come from a damaged file, and the GPU's float sums would be NaN.
        if (weights && !(std::abs(t.weights[i]) <= kMaxStencilWeight))
            r.fail(what + ": entry " + std::to_string(i) + " has weight " + cli::shortNumber(t.weights[i]) +
                   "; a stencil weight must be finite and within +-1e6");
    }
    for (uint32_t i = 0; !weights && i < rows; ++i)
        if (t.start[i + 1] == t.start[i])
            r.fail(what + ": face point " + std::to_string(i) + " is empty");
}

StencilTable shiftedStencilTable(const StencilTable& previous, uint32_t grandFirst, uint32_t parentFirst,
                                 uint32_t first) {
    StencilTable t = previous;
    // Unsigned arithmetic wraps; a source moved out of its level is refused by checkStencilTable.
    for (uint32_t& x : t.indices) x += x < parentFirst ? parentFirst - grandFirst : first - parentFirst;
    return t;
}

bool isShiftedStencilTable(const StencilTable& t, const StencilTable& previous, uint32_t grandFirst,
                           uint32_t parentFirst, uint32_t first) {
    if (t.start != previous.start || t.weights.size() != previous.weights.size() ||
        (!t.weights.empty() && std::memcmp(t.weights.data(), previous.weights.data(), t.weights.size() * sizeof(float))))
        return false;
    for (size_t k = 0; k < t.indices.size(); ++k) {
        const uint32_t x = previous.indices[k];
        if (t.indices[k] != x + (x < parentFirst ? parentFirst - grandFirst : first - parentFirst)) return false;
    }
    return true;
}

// Version 4's patch records (formats/limn.md): a patch's control points are neighbours at one
// level, so each is a varint difference from its first corner P11 (0 stays 0, a phantom), P11
// from the previous record's, the ptex face from the previous record's, the domain in units of
// 2^-16, the packed word, and the sharpness only for a single-crease patch.
void writePatchStream(ByteWriter& w, const std::vector<Patch>& patches, bool domains) {
    std::vector<uint8_t> s;
    s.reserve(patches.size() * 32);
    uint32_t corner = 0, ptex = 0;
    auto units = [](float x) {
        const double u = double(x) * 65536.0;
        if (!(u >= 0 && u <= 65536.0 && u == std::floor(u)))
            throw std::logic_error("patch domain is not a multiple of 2^-16");
        return static_cast<uint64_t>(u);
    };
    for (const Patch& p : patches) {
        writeVarint(s, zigzag(int64_t(p.cv[5]) - corner));
        corner = p.cv[5];
        for (int i = 0; i < 16; ++i)
            if (i != 5) writeVarint(s, p.cv[i] == 0 ? 0 : zigzag(int64_t(p.cv[i]) - p.cv[5]) + 1);
        if (domains) {
            writeVarint(s, zigzag(int64_t(p.ptex) - ptex));
            ptex = p.ptex;
            writeVarint(s, units(p.u0));
            writeVarint(s, units(p.v0));
            writeVarint(s, units(p.size));
        }
        writeVarint(s, uint32_t(p.level) | uint32_t(p.boundary) << 8 | uint32_t(p.crease) << 16);
        if (p.crease) {
            const uint32_t bits = std::bit_cast<uint32_t>(p.sharpness);
            for (int i = 0; i < 4; ++i) s.push_back(static_cast<uint8_t>(bits >> (8 * i)));
        }
    }
    writeStream(w, s);
}

StreamReader::StreamReader(ByteReader& r, std::string what) : r_(r), what_(std::move(what)) {
    const uint32_t bytes = r.read<uint32_t>();
    data_ = r.readBytes(bytes, (what_ + " stream").c_str());
    for (uint32_t pad = (4 - bytes % 4) % 4; pad > 0; --pad)
        if (r.read<uint8_t>() != 0) fail("padding is not zero");
}

uint64_t StreamReader::varint() {
    uint64_t x = 0;
    for (int shift = 0; shift < 64; shift += 7) {
        if (at_ == data_.size()) fail("the stream ends inside a number");
        const uint8_t b = data_[at_++];
        if (shift == 63 && b > 1) break;
        x |= uint64_t(b & 0x7F) << shift;
        if (!(b & 0x80)) return x;
    }
    fail("a number in the stream is longer than 64 bits");
}

uint32_t StreamReader::after(uint32_t previous, const char* what) {
    const uint64_t z = varint();
    // A difference beyond +-2^32 is out of range from any u32; refused before the sum, which
    // for one near +-2^63 would overflow int64 (undefined behaviour).
    if ((z >> 1) > 0xFFFFFFFFull) fail(std::string(what) + " out of range");
    const int64_t x = int64_t(previous) + unzigzag(z);
    if (x < 0 || x > int64_t(0xFFFFFFFFu)) fail(std::string(what) + " out of range");
    return static_cast<uint32_t>(x);
}

uint8_t StreamReader::rawByte() {
    if (at_ == data_.size()) fail("the stream ends inside a record");
    return data_[at_++];
}

void writeLevels(ByteWriter& w, const std::vector<LevelInfo>& levels, bool stream) {
    if (!stream) {
        for (const LevelInfo& L : levels)
            for (uint32_t x : {L.first, L.facePoints, L.edgePoints, L.vertexPoints, L.regularPatches, L.irregularFaces})
                w.write<uint32_t>(x);
        return;
    }
    std::vector<uint8_t> s;
    for (const LevelInfo& L : levels)
        for (uint32_t x : {L.facePoints, L.edgePoints, L.vertexPoints, L.regularPatches, L.irregularFaces})
            writeVarint(s, x);
    writeStream(w, s);
}

std::vector<LevelInfo> readLevels(ByteReader& r, uint32_t count, bool stream) {
    std::vector<LevelInfo> levels(count);
    if (!stream) {
        for (LevelInfo& L : levels)
            for (uint32_t* x : {&L.first, &L.facePoints, &L.edgePoints, &L.vertexPoints, &L.regularPatches,
                                &L.irregularFaces})
                *x = r.read<uint32_t>();
        return levels;
    }
    StreamReader in(r, "levels");
    uint64_t sum = 0;
    for (LevelInfo& L : levels) {
        L.first = static_cast<uint32_t>(std::min<uint64_t>(sum, 0xFFFFFFFFu));
        for (uint32_t* x : {&L.facePoints, &L.edgePoints, &L.vertexPoints, &L.regularPatches, &L.irregularFaces}) {
            const uint64_t v = in.varint();
            if (v > 0xFFFFFFFFu) in.fail("a count out of range");
            *x = static_cast<uint32_t>(v);
        }
        sum += uint64_t(L.facePoints) + L.edgePoints + L.vertexPoints;
    }
    in.finish();
    return levels;
}

float StreamReader::rawFloat() {
    if (data_.size() - at_ < 4) fail("the stream ends inside a number");
    uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) bits |= uint32_t(data_[at_++]) << (8 * i);
    return std::bit_cast<float>(bits);
}

// Version 6: bit l set when level l's three stencil tables are level l - 1's shifted one level
// (shiftedStencilTable), with as many face, edge and vertex points; level 1 never is.
uint32_t repeatedLevels(const Tables& t) {
    uint32_t bits = 0;
    for (uint32_t l = 2; l < t.levels.size(); ++l) {
        const LevelInfo &a = t.levels[l - 1], &b = t.levels[l];
        if (a.facePoints != b.facePoints || a.edgePoints != b.edgePoints || a.vertexPoints != b.vertexPoints)
            continue;
        const uint32_t g = t.levels[l - 2].first;
        if (isShiftedStencilTable(t.facePoints[l - 1], t.facePoints[l - 2], g, a.first, b.first) &&
            isShiftedStencilTable(t.edgePoints[l - 1], t.edgePoints[l - 2], g, a.first, b.first) &&
            isShiftedStencilTable(t.vertexPoints[l - 1], t.vertexPoints[l - 2], g, a.first, b.first))
            bits |= 1u << l;
    }
    return bits;
}

void appendRepeatedLevel(ByteReader& r, Tables& t, uint32_t l) {
    const LevelInfo &P = t.levels[l - 1], &L = t.levels[l];
    const std::string lv = "level " + std::to_string(l);
    if (P.facePoints != L.facePoints || P.edgePoints != L.edgePoints || P.vertexPoints != L.vertexPoints)
        r.fail(lv + " repeats level " + std::to_string(l - 1) + " but has other point counts");
    const uint32_t g = t.levels[l - 2].first, parentEnd = P.first + P.count(), faceEnd = L.first + L.facePoints;
    t.facePoints.push_back(shiftedStencilTable(t.facePoints.back(), g, P.first, L.first));
    t.edgePoints.push_back(shiftedStencilTable(t.edgePoints.back(), g, P.first, L.first));
    t.vertexPoints.push_back(shiftedStencilTable(t.vertexPoints.back(), g, P.first, L.first));
    checkStencilTable(r, t.facePoints.back(), lv + " face points", L.facePoints, false, P.first, parentEnd);
    checkStencilTable(r, t.edgePoints.back(), lv + " edge points", L.edgePoints, true, P.first, parentEnd, L.first,
                      faceEnd);
    checkStencilTable(r, t.vertexPoints.back(), lv + " vertex points", L.vertexPoints, true, P.first, parentEnd,
                      L.first, faceEnd);
}

} // namespace limn
