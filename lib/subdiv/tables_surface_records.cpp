#include "subdiv/tables_surface_records.h"

#include "subdiv/irregular_basis.h"
#include "subdiv/tables_chain_records.h"
#include "subdiv/tables_program_dictionary.h"
#include "subdiv/tables_stream.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace limn {

// A program has 2n + 17 rows (the band's support, the sub-patches' other points and the face
// points they read) of about five entries each (formats/limn.md); these bounds leave room and
// keep a hostile program's expansion small (rows x support doubles, entries x support x K
// operations).
static constexpr uint32_t kMaxProgramRowsPerPoint = 2;
static constexpr uint32_t kMaxProgramEntriesPerRow = 16;

void writeProgram(ByteWriter& w, const BasisProgram& program) {
    const BasisProgram* p = &program;
    std::vector<float> palette;
    std::unordered_map<uint32_t, uint32_t> slot; // a weight's bits -> its palette index
    std::vector<uint8_t> s;
    writeVarint(s, p->rows());
    for (uint32_t r = 0; r < p->rows(); ++r) {
        writeVarint(s, uint64_t(p->start[r + 1] - p->start[r]) << 1 | p->averaged[r]);
        for (uint32_t e = p->start[r]; e < p->start[r + 1]; ++e) {
            writeVarint(s, p->source[e]);
            if (p->averaged[r]) continue;
            const auto [it, added] =
                slot.try_emplace(std::bit_cast<uint32_t>(p->weight[e]), static_cast<uint32_t>(palette.size()));
            if (added) palette.push_back(p->weight[e]);
            writeVarint(s, it->second);
        }
    }
    for (uint32_t x : p->controlRow) writeVarint(s, x);
    for (uint32_t x : p->nextSupport) writeVarint(s, x);
    w.write<uint32_t>(static_cast<uint32_t>(palette.size()));
    w.writeArray(palette);
    writeStream(w, s);
}

namespace {

// The program of basis b: its own, or (an interior basis read from TBLS before version 5) the one
// buildIrregularBasis makes for its valence, if that expands to its weights.
const BasisProgram& programOf(const IrregularBasis& b, IrregularBasis& built) {
    if (b.program.rows() != 0) return b.program;
    if (b.configuration.boundary) throw std::logic_error("TBLS: a boundary basis without its program");
    built = buildIrregularBasis(b.valence, b.levels);
    if (built.weights.size() != b.weights.size() ||
        std::memcmp(built.weights.data(), b.weights.data(), b.weights.size() * sizeof(float)) != 0)
        throw std::logic_error("TBLS: a valence-" + std::to_string(b.valence) +
                               " basis is not this limn's; it cannot be written as a program");
    return built.program;
}

} // namespace

void writeBasisProgram(ByteWriter& w, const IrregularBasis& b) {
    if (b.configuration.boundary)
        throw std::logic_error("TBLS: a boundary configuration's basis needs version 7");
    IrregularBasis built;
    const BasisProgram& p = programOf(b, built);
    w.write<uint32_t>(b.valence);
    w.write<uint32_t>(b.levels);
    writeProgram(w, p);
}

void writeConfigurationBasis(ByteWriter& w, const IrregularBasis& b, ProgramDictionary* dictionary) {
    IrregularBasis built;
    const BasisProgram& p = programOf(b, built);
    w.write<uint32_t>(b.valence);
    w.write<uint32_t>(b.configuration.code());
    w.write<uint32_t>(b.supportSize());
    w.write<uint32_t>(b.levels);
    if (!dictionary) return writeProgram(w, p);
    std::vector<uint32_t> moved;
    std::vector<uint8_t> s;
    writeDictionaryProgram(s, canonicalProgram(p, b.supportSize(), moved), *dictionary);
    writeStream(w, s);
}

IrregularBasis readConfigurationBasis(ByteReader& r, const std::string& what, const std::vector<IrregularBasis>& earlier,
                                      ChainPrograms* chains, ProgramDictionary* dictionary) {
    IrregularBasis x;
    x.valence = r.read<uint32_t>();
    const uint32_t code = r.read<uint32_t>();
    const uint32_t M = r.read<uint32_t>();
    x.levels = r.read<uint32_t>();
    if (chains && code == kChainConfigurationCode)
        return readChainBasis(r, what, x.valence, M, x.levels, earlier, *chains, dictionary);
    BasisConfiguration& c = x.configuration;
    c = {x.valence, (code & 1) != 0, code >> 2, (code & 2) != 0};
    if (c.code() != code || x.valence < 1 || x.valence > kMaxBasisValence || x.levels < 1 ||
        x.levels > uint32_t(kMaxDepth) || (c.boundary && c.position >= x.valence) ||
        (!c.boundary && (x.valence < 3 || x.valence == 4 || M != 2 * x.valence + 8)) || M < 4 ||
        M > 2 * kMaxBasisValence + 8)
        r.fail(what + " has a bad configuration, support size or level count");
    for (const IrregularBasis& other : earlier)
        if (other.configuration == c) r.fail(what + " repeats a configuration");
    if (c.boundary) x.support = M;
    // A boundary sub-patch has at most 7 phantom points, each one row.
    const uint32_t phantomRows = c.boundary ? 21 : 0;
    if (dictionary) { // version 9
        StreamReader in(r, what);
        x.program = readDictionaryProgram(in, M, uint64_t(kMaxProgramRowsPerPoint) * M + phantomRows, M, false, *dictionary);
        in.finish();
    } else {
        x.program = readProgram(r, what, M, phantomRows);
    }
    x.weights = expandIrregularBasis(x.program, M, x.levels);
    const float lo = c.boundary ? -4.0f : 0.0f, hi = c.boundary ? 5.0f : 1.0f;
    for (float wt : x.weights)
        if (!(wt >= lo && wt <= hi))
            r.fail(what + " has a weight outside [" + std::to_string(int(lo)) + ", " + std::to_string(int(hi)) + "]");
    return x;
}

BasisProgram readProgram(ByteReader& r, const std::string& what, uint32_t M, uint32_t phantomRows) {
    const uint32_t P = r.read<uint32_t>();
    const std::vector<float> palette = r.readArray<float>(P, (what + " palette").c_str());
    for (float x : palette)
        if (!(std::abs(x) <= kMaxStencilWeight)) r.fail(what + " has a bad weight");
    StreamReader in(r, what);
    BasisProgram p;
    const uint64_t rows = in.varint();
    if (rows == 0 || rows > uint64_t(kMaxProgramRowsPerPoint) * M + phantomRows)
        in.fail("bad row count " + std::to_string(rows));
    const uint64_t maxEntries = rows * kMaxProgramEntriesPerRow;
    p.start.reserve(rows + 1);
    p.averaged.reserve(rows);
    for (uint32_t row = 0; row < rows; ++row) {
        const uint64_t head = in.varint(), length = head >> 1;
        if (length == 0 || length > maxEntries - p.source.size())
            in.fail("row " + std::to_string(row) + " has a bad length");
        const bool averaged = head & 1;
        for (uint64_t e = 0; e < length; ++e) {
            const uint64_t source = in.varint();
            if (source >= uint64_t(M) + row)
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
    auto rowIndex = [&]() {
        const uint64_t x = in.varint();
        if (x >= rows) in.fail("a control point or support point names a missing row");
        return static_cast<uint32_t>(x);
    };
    for (uint32_t& x : p.controlRow) x = rowIndex();
    p.nextSupport.resize(M);
    for (uint32_t& x : p.nextSupport) x = rowIndex();
    in.finish();
    return p;
}

IrregularBasis readBasisProgram(ByteReader& r, uint32_t index, const std::vector<IrregularBasis>& earlier) {
    const std::string what = "irregular basis " + std::to_string(index);
    IrregularBasis b;
    b.valence = r.read<uint32_t>();
    b.levels = r.read<uint32_t>();
    // The expanded weights take K * 48 * (2n + 8) floats from a few hundred bytes: valences
    // beyond kMaxBasisValence (limn-tables builds none) and repeated ones are damage.
    if (b.valence < 3 || b.valence > kMaxBasisValence || b.levels < 1 || b.levels > uint32_t(kMaxDepth))
        r.fail(what + " has a bad valence or level count (valence 3 to " + std::to_string(kMaxBasisValence) +
               ", 1 to " + std::to_string(kMaxDepth) + " levels)");
    for (const IrregularBasis& other : earlier)
        if (other.valence == b.valence && !other.configuration.boundary)
            r.fail(what + " repeats valence " + std::to_string(b.valence));
    b.configuration = {b.valence, false, 0, false};
    const uint32_t M = b.supportSize();
    b.program = readProgram(r, what, M, 0);
    b.weights = expandIrregularBasis(b.program, M, b.levels);
    for (float x : b.weights) // sums of bounded weights can still grow past any bound
        if (!(std::abs(x) <= kMaxStencilWeight)) r.fail(what + " has a bad weight");
    return b;
}

// A node code as a varint: 0 for none, else 1 + kind + 4 * zigzag(index - next[kind]), next[kind]
// being one past the index of the last code of that kind (children, sub-patches, leaves and
// smooth faces are numbered in the order the nodes name them, so the difference is mostly 0).
void writeNodeStream(ByteWriter& w, const std::vector<std::array<uint32_t, 4>>& nodes) {
    std::vector<uint8_t> s;
    s.reserve(nodes.size() * 2);
    uint32_t next[4] = {0, 0, 0, 0};
    auto code = [&](uint32_t c) -> uint64_t {
        if (c == kNodeNone) return 0;
        const uint32_t kind = c >> 30, x = c & kNodeIndexMask;
        const uint64_t z = zigzag(int64_t(x) - next[kind]);
        next[kind] = x + 1;
        return 1 + kind + 4 * z;
    };
    for (const auto& n : nodes) {
        const bool same = n[0] == n[1] && n[0] == n[2] && n[0] == n[3];
        writeVarint(s, code(n[0]) << 1 | (same ? 1 : 0));
        if (!same)
            for (int q = 1; q < 4; ++q) writeVarint(s, code(n[q]));
    }
    writeStream(w, s);
}

std::vector<std::array<uint32_t, 4>> readNodeStream(ByteReader& r, uint32_t count) {
    StreamReader in(r, "irregular nodes");
    if (count > in.size()) in.fail("count " + std::to_string(count) + " is too large"); // a byte a node at least
    uint32_t next[4] = {0, 0, 0, 0};
    auto code = [&](uint64_t z) -> uint32_t {
        if (z == 0) return kNodeNone;
        const uint64_t kind = (z - 1) % 4;
        const int64_t x = int64_t(next[kind]) + unzigzag((z - 1) / 4);
        if (x < 0 || x > int64_t(kNodeIndexMask)) in.fail("a child index out of range");
        next[kind] = static_cast<uint32_t>(x) + 1;
        return static_cast<uint32_t>(kind << 30 | uint64_t(x));
    };
    std::vector<std::array<uint32_t, 4>> nodes(count);
    for (auto& n : nodes) {
        const uint64_t head = in.varint();
        n[0] = code(head >> 1);
        for (int q = 1; q < 4; ++q) n[q] = (head & 1) ? n[0] : code(in.varint());
    }
    in.finish();
    return nodes;
}

void writeSmoothFaces(ByteWriter& w, const Tables& t) {
    std::vector<uint8_t> s;
    s.reserve(t.smoothIrregular.size() * 2);
    uint32_t end = 0; // one past the previous face's points
    for (const Tables::SmoothIrregular& f : t.smoothIrregular) {
        writeVarint(s, uint64_t(f.basis) << 2 | f.corner);
        writeVarint(s, zigzag(int64_t(f.first) - end));
        end = f.first + t.irregularBases[f.basis].supportSize();
    }
    writeStream(w, s);
}

std::vector<Tables::SmoothIrregular> readSmoothFaces(ByteReader& r, uint32_t count,
                                                     const std::vector<IrregularBasis>& bases) {
    StreamReader in(r, "smooth irregular faces");
    if (count > in.size() / 2) in.fail("count " + std::to_string(count) + " is too large"); // two bytes a face
    std::vector<Tables::SmoothIrregular> faces(count);
    uint32_t end = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const uint64_t head = in.varint();
        if ((head >> 2) >= bases.size()) in.fail("face " + std::to_string(i) + " names a missing basis");
        faces[i].basis = static_cast<uint32_t>(head >> 2);
        faces[i].corner = static_cast<uint32_t>(head & 3);
        faces[i].first = in.after(end, "a face's first point");
        end = static_cast<uint32_t>(std::min<uint64_t>(uint64_t(faces[i].first) + bases[faces[i].basis].supportSize(),
                                                       0xFFFFFFFFu));
    }
    in.finish();
    return faces;
}

namespace {

// The start of each class of a level: face points, edge points, vertex points, and the end.
std::array<uint32_t, 4> pointClasses(const LevelInfo& L) {
    return {L.first, L.first + L.facePoints, L.first + L.facePoints + L.edgePoints, L.first + L.count()};
}

// The levels smooth faces' points may be at: N, and below it those of the smooth faces in the
// quadtrees, N + 1 .. N + K - 1 (a face at N + K has no band left).
uint32_t deepestSmoothLevel(const Tables& t) {
    const uint32_t deepest = t.depth + std::max<uint32_t>(t.irregularLevels, 1) - 1;
    return std::min<uint32_t>(deepest, static_cast<uint32_t>(t.levels.size()) - 1);
}

} // namespace

void writeSmoothPoints(ByteWriter& w, const Tables& t) {
    const uint32_t N = t.depth, deepest = deepestSmoothLevel(t);
    auto levelOf = [&](uint32_t v) {
        for (uint32_t l = N; l <= deepest; ++l)
            if (v >= t.levels[l].first && v - t.levels[l].first < t.levels[l].count()) return l;
        throw std::logic_error("TBLS: a smooth point is not at level N or a smooth face's level below it");
    };
    const std::vector<uint32_t>& points = t.smoothPoints;
    std::vector<uint8_t> s;
    s.reserve(points.size() * 2);
    for (size_t i = 0; i < points.size();) {
        // A run: the points up to the next one at another level (one run per level when the
        // faces come by level, as limn-tables writes them).
        const uint32_t l = levelOf(points[i]);
        const std::array<uint32_t, 4> range = pointClasses(t.levels[l]);
        size_t end = i + 1;
        while (end < points.size() && points[end] >= range[0] && points[end] < range[3]) ++end;
        writeVarint(s, l - N);
        writeVarint(s, end - i);
        uint32_t last[3] = {range[0], range[1], range[2]};
        for (; i < end; ++i) {
            const uint32_t v = points[i];
            const int c = v < range[1] ? 0 : v < range[2] ? 1 : 2;
            writeVarint(s, uint64_t(c) + 3 * zigzag(int64_t(v) - last[c]));
            last[c] = v;
        }
    }
    writeStream(w, s);
}

std::vector<uint32_t> readSmoothPoints(ByteReader& r, uint32_t count, const Tables& t) {
    StreamReader in(r, "smooth irregular points");
    if (count > in.size()) in.fail("count " + std::to_string(count) + " is too large"); // a byte a point
    const uint32_t N = t.depth, deepest = deepestSmoothLevel(t);
    std::vector<uint32_t> points(count);
    for (uint32_t i = 0; i < count;) {
        const uint64_t j = in.varint(), n = in.varint();
        if (j > deepest - N)
            in.fail("a run at level N + " + std::to_string(j) + " (levels N to N + " + std::to_string(deepest - N) + ")");
        if (n == 0 || n > count - i) in.fail("a run of " + std::to_string(n) + " points (" + std::to_string(count - i) + " left)");
        const std::array<uint32_t, 4> range = pointClasses(t.levels[N + j]);
        uint32_t last[3] = {range[0], range[1], range[2]};
        for (const uint32_t end = i + static_cast<uint32_t>(n); i < end; ++i) {
            const uint64_t z = in.varint();
            const uint64_t c = z % 3;
            const int64_t x = int64_t(last[c]) + unzigzag(std::min<uint64_t>(z / 3, uint64_t(1) << 40));
            if (x < int64_t(range[c]) || x >= int64_t(range[c + 1])) in.fail("a point is not at its run's level");
            points[i] = last[c] = static_cast<uint32_t>(x);
        }
    }
    in.finish();
    return points;
}

// Smooth faces below level N (version 5). A basis code at a root whose four codes are equal is
// the root's own smooth face (level N); any other names the smooth face of its quadrant, a
// level below its node. Returns what is wrong with the codes and the smooth faces' levels,
// or an empty string: each smooth face named once, its basis bands left at its level (at least
// one), its support points all at its level; before version 5 only roots hold basis codes.
// The code walks are bounded: children come after their parents (checked before).
std::string checkSmoothFaceLevels(const Tables& t, uint32_t version) {
    const uint32_t I = static_cast<uint32_t>(t.irregular.size()), nodes = static_cast<uint32_t>(t.irregularNodes.size());
    const uint32_t N = t.depth, D = t.depth + t.irregularLevels;
    std::vector<uint32_t> depth(nodes, 0), levelOf(t.smoothIrregular.size(), kNone);
    for (uint32_t i = 0; i < nodes; ++i) {
        const auto& node = t.irregularNodes[i];
        const bool root = i < I && smoothRoot(node);
        for (uint32_t c : node) {
            if (c == kNodeNone) continue;
            const uint32_t kind = c & ~kNodeIndexMask, x = c & kNodeIndexMask;
            if (kind == kNodeChild) depth[x] = depth[i] + 1;
            if (kind != kNodeBasis) continue;
            if (x >= t.smoothIrregular.size()) return "irregular node " + std::to_string(i) + " has a bad basis code";
            if (!root && version < 5)
                return "irregular node " + std::to_string(i) + " has a basis code below a root (version 5)";
            const uint32_t below = root ? 0 : depth[i] + 1; // levels below the irregular face
            if (levelOf[x] != kNone && !(root && levelOf[x] == N))
                return "smooth irregular face " + std::to_string(x) + " is named twice";
            const IrregularBasis& b = t.irregularBases[t.smoothIrregular[x].basis];
            if (below && (N + below >= D || below >= b.levels))
                return "irregular node " + std::to_string(i) + " names a smooth face too deep";
            levelOf[x] = N + below;
        }
    }
    for (size_t i = 0; i < t.smoothIrregular.size(); ++i) {
        const auto& f = t.smoothIrregular[i];
        const uint32_t l = levelOf[i] == kNone ? N : levelOf[i];
        const LevelInfo& L = t.levels[l];
        for (uint32_t k = 0; k < t.irregularBases[f.basis].supportSize(); ++k) {
            const uint32_t v = t.smoothPoints[f.first + k];
            if (v < L.first || v >= L.first + L.count())
                return "a smooth irregular point is not at its face's level";
        }
    }
    return {};
}

std::string assignSubPatchDomains(Tables& t) {
    const uint32_t I = static_cast<uint32_t>(t.irregular.size()), nodes = static_cast<uint32_t>(t.irregularNodes.size());
    struct Square {
        uint32_t ptex = kNone, level = 0;
        float u0 = 0, v0 = 0, size = 0;
    };
    std::vector<Square> square(nodes);
    for (uint32_t i = 0; i < std::min(I, nodes); ++i) {
        const IrregularFace& f = t.irregular[i];
        square[i] = {f.ptex, t.depth, f.u0, f.v0, f.size};
    }
    std::vector<uint8_t> named(t.subPatches.size(), 0);
    for (uint32_t i = 0; i < nodes; ++i) {
        const Square& s = square[i];
        if (s.ptex == kNone) return "irregular node " + std::to_string(i) + " is in no quadtree";
        for (int q = 0; q < 4; ++q) {
            const uint32_t c = t.irregularNodes[i][q], kind = c & ~kNodeIndexMask, x = c & kNodeIndexMask;
            if (c == kNodeNone || (kind != kNodeChild && kind != kNodeSubPatch)) continue;
            // Quadrant q = (s >= 1/2) + 2 (t >= 1/2) of the square; halving a dyadic float is exact.
            const float half = s.size / 2;
            const Square child{s.ptex, s.level + 1, s.u0 + (q & 1 ? half : 0.0f), s.v0 + (q & 2 ? half : 0.0f), half};
            if (kind == kNodeChild) {
                if (square[x].ptex != kNone) return "irregular node " + std::to_string(x) + " is named twice";
                square[x] = child;
                continue;
            }
            if (named[x]) return "sub-patch " + std::to_string(x) + " is named twice";
            named[x] = 1;
            Patch& p = t.subPatches[x];
            if (p.level != child.level)
                return "sub-patch " + std::to_string(x) + " is at level " + std::to_string(p.level) + ", its node's quadrant at " +
                       std::to_string(child.level);
            p.ptex = child.ptex;
            p.u0 = child.u0;
            p.v0 = child.v0;
            p.size = child.size;
        }
    }
    for (size_t x = 0; x < named.size(); ++x)
        if (!named[x]) return "sub-patch " + std::to_string(x) + " is in no quadtree";
    return {};
}

IrregularBasis readBasisWeights(ByteReader& r, uint32_t index, bool compact, const std::vector<IrregularBasis>& earlier) {
    IrregularBasis basis;
    basis.valence = r.read<uint32_t>();
    basis.levels = r.read<uint32_t>();
    if (basis.valence < 3 || basis.valence > kMaxStencilValence || basis.levels < 1 ||
        basis.levels > uint32_t(kMaxDepth))
        r.fail("irregular basis " + std::to_string(index) + " has a bad valence or level count");
    const uint64_t M = basis.supportSize(), count = uint64_t(basis.levels) * 48;
    if (compact) {
        // Compact rows are stored once and copied per use, up to 768 times: a basis of
        // valence 32,767 would take 200 MB from 260 KB of file, and a file could hold
        // hundreds. Version 4 came after limn-tables stopped building bases above
        // kMaxBasisValence, and it builds one per valence: anything else is damage.
        if (basis.valence > kMaxBasisValence)
            r.fail("irregular basis " + std::to_string(index) + " has valence " +
                   std::to_string(basis.valence) + "; version 4 bases go up to " +
                   std::to_string(kMaxBasisValence));
        for (const IrregularBasis& other : earlier)
            if (other.valence == basis.valence)
                r.fail("irregular basis " + std::to_string(index) + " repeats valence " +
                       std::to_string(basis.valence));
        const uint32_t distinct = r.read<uint32_t>();
        if (distinct == 0 || distinct > count)
            r.fail("irregular basis " + std::to_string(index) + " has a bad row count");
        const std::vector<uint16_t> pick = r.readArray<uint16_t>(count, "irregular basis rows");
        const std::vector<float> rows = r.readArray<float>(distinct * M, "irregular basis weights");
        basis.weights.resize(count * M);
        for (uint64_t j = 0; j < count; ++j) {
            if (pick[j] >= distinct) r.fail("irregular basis " + std::to_string(index) + " names a missing row");
            std::copy_n(rows.begin() + long(pick[j] * M), M, basis.weights.begin() + long(j * M));
        }
    } else {
        basis.weights = r.readArray<float>(count * M, "irregular basis weights");
    }
    for (float x : basis.weights)
        if (!(std::abs(x) <= kMaxStencilWeight))
            r.fail("irregular basis " + std::to_string(index) + " has a bad weight");
    return basis;
}

} // namespace limn
