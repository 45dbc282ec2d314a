#include "subdiv/tables_chunk.h"

#include "base/bytes.h"
#include "base/cli.h"
#include "base/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <unordered_set>

namespace limn {

namespace {

constexpr float kMaxStencilWeight = 1e6f;

void writeTable(ByteWriter& w, const StencilTable& t, bool weights) {
    w.write<uint32_t>(static_cast<uint32_t>(t.rows()));
    w.write<uint32_t>(static_cast<uint32_t>(t.indices.size()));
    w.write<uint32_t>(weights ? 1u : 0u);
    w.write<uint32_t>(0);
    w.writeArray(t.start);
    w.writeArray(t.indices);
    if (weights) w.writeArray(t.weights);
}

// Reads a stencil table with `rows` rows whose sources must lie in [lo0, hi0) or [lo1, hi1).
StencilTable readTable(ByteReader& r, const std::string& what, uint32_t rows, bool weights,
                       uint32_t lo0, uint32_t hi0, uint32_t lo1 = 0, uint32_t hi1 = 0) {
    StencilTable t;
    uint32_t n = r.read<uint32_t>(), entries = r.read<uint32_t>(), hasWeights = r.read<uint32_t>();
    if (r.read<uint32_t>() != 0) r.fail(what + ": reserved field is not zero");
    if (n != rows)
        r.fail(what + ": " + std::to_string(n) + " rows, expected " + std::to_string(rows));
    if (hasWeights != (weights ? 1u : 0u)) r.fail(what + ": weight flag is wrong");
    t.start = r.readArray<uint32_t>(uint64_t(rows) + 1, (what + " starts").c_str());
    t.indices = r.readArray<uint32_t>(entries, (what + " indices").c_str());
    if (weights) t.weights = r.readArray<float>(entries, (what + " weights").c_str());
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
    return t;
}

bool isDyadic(float x, uint32_t maxDepth) {
    float scaled = x * float(1u << maxDepth);
    return std::isfinite(x) && scaled == std::floor(scaled);
}

} // namespace

uint32_t ptexFaceCount(const Mesh& mesh) {
    uint32_t n = 0;
    for (size_t f = 0; f < mesh.faceCount(); ++f) n += mesh.faceSize(f) == 4 ? 1 : mesh.faceSize(f);
    return n;
}

Chunk encodeTablesChunk(const Tables& t) {
    ByteWriter w;
    // The size of the layout below, reserved so a large table is written in one pass.
    auto tableBytes = [](const StencilTable& table, bool weights) {
        return 16 + 4 * (table.start.size() + table.indices.size() + (weights ? table.weights.size() : 0));
    };
    size_t size = 40 + 24 * t.levels.size() + 88 * t.patches.size() + 32 * t.irregular.size() +
                  4 * (t.limitVertex.size() + t.limitExact.size()) + 12 + 88 * t.subPatches.size() +
                  16 * t.irregularNodes.size() + 32 * t.irregularLeaves.size() + 12 +
                  12 * t.smoothIrregular.size() + 4 * t.smoothPoints.size();
    for (const auto& b : t.irregularBases) size += 8 + 4 * b.weights.size();
    for (uint32_t l = 0; l + 1 < t.levels.size(); ++l)
        size += tableBytes(t.facePoints[l], false) + tableBytes(t.edgePoints[l], true) +
                tableBytes(t.vertexPoints[l], true);
    for (const auto* table : {&t.limitPosition, &t.limitTangent1, &t.limitTangent2})
        size += tableBytes(*table, true);
    w.reserve(size);
    w.write<uint32_t>(t.depth);
    w.write<uint32_t>(t.uniform ? 1u : 0u);
    w.write<uint8_t>(static_cast<uint8_t>(t.options.boundary));
    w.write<uint8_t>(static_cast<uint8_t>(t.options.creaseMethod));
    w.write<uint8_t>(static_cast<uint8_t>(t.options.triangles));
    w.write<uint8_t>(static_cast<uint8_t>(t.options.fvar));
    w.write<uint32_t>(t.irregularLevels);
    w.write<uint64_t>(t.topologyHash);
    w.write<uint32_t>(t.totalVertices);
    w.write<uint32_t>(static_cast<uint32_t>(t.patches.size()));
    w.write<uint32_t>(static_cast<uint32_t>(t.irregular.size()));
    w.write<uint32_t>(static_cast<uint32_t>(t.limitPosition.rows()));
    for (const auto& L : t.levels)
        for (uint32_t x : {L.first, L.facePoints, L.edgePoints, L.vertexPoints, L.regularPatches,
                           L.irregularFaces})
            w.write<uint32_t>(x);
    for (uint32_t l = 0; l + 1 < t.levels.size(); ++l) {
        writeTable(w, t.facePoints[l], false);
        writeTable(w, t.edgePoints[l], true);
        writeTable(w, t.vertexPoints[l], true);
    }
    auto writePatch = [&](const Patch& p) {
        w.writeArray(std::span<const uint32_t>(p.cv, 16));
        w.write<uint32_t>(p.ptex);
        w.write<float>(p.u0);
        w.write<float>(p.v0);
        w.write<float>(p.size);
        w.write<uint32_t>(uint32_t(p.level) | uint32_t(p.boundary) << 8 | uint32_t(p.crease) << 16);
        w.write<float>(p.sharpness);
    };
    auto writeFace = [&](const IrregularFace& q) {
        w.writeArray(std::span<const uint32_t>(q.corner, 4));
        w.write<uint32_t>(q.ptex);
        w.write<float>(q.u0);
        w.write<float>(q.v0);
        w.write<float>(q.size);
    };
    for (const auto& p : t.patches) writePatch(p);
    for (const auto& q : t.irregular) writeFace(q);
    // Version 3: the irregular faces' quadtrees (docs/irregular.md).
    w.write<uint32_t>(static_cast<uint32_t>(t.subPatches.size()));
    for (const auto& p : t.subPatches) writePatch(p);
    w.write<uint32_t>(static_cast<uint32_t>(t.irregularNodes.size()));
    for (const auto& n : t.irregularNodes) w.writeArray(std::span<const uint32_t>(n.data(), 4));
    w.write<uint32_t>(static_cast<uint32_t>(t.irregularLeaves.size()));
    for (const auto& q : t.irregularLeaves) writeFace(q);
    w.write<uint32_t>(static_cast<uint32_t>(t.irregularBases.size()));
    for (const auto& b : t.irregularBases) {
        w.write<uint32_t>(b.valence);
        w.write<uint32_t>(b.levels);
        w.writeArray(b.weights);
    }
    w.write<uint32_t>(static_cast<uint32_t>(t.smoothIrregular.size()));
    for (const auto& f : t.smoothIrregular)
        for (uint32_t x : {f.basis, f.corner, f.first}) w.write<uint32_t>(x);
    w.write<uint32_t>(static_cast<uint32_t>(t.smoothPoints.size()));
    w.writeArray(t.smoothPoints);
    writeTable(w, t.limitPosition, true);
    writeTable(w, t.limitTangent1, true);
    writeTable(w, t.limitTangent2, true);
    w.writeArray(t.limitVertex);
    for (uint8_t e : t.limitExact) w.write<uint32_t>(e ? 0u : 1u); // bit 0: approximate
    return {kTablesChunk, kTablesChunkVersion, w.take()};
}

Tables decodeTablesChunk(const Chunk& chunk, const Mesh* mesh) {
    // Version 1 has no single-crease patches: its patch records end before the sharpness.
    if (chunk.version > kTablesChunkVersion || chunk.version == 0)
        throwBadInput("chunk TBLS version " + std::to_string(chunk.version) + " is " +
                      (chunk.version ? "newer than" : "not one") + " this limn reads (1 to " +
                      std::to_string(kTablesChunkVersion) + ")" +
                      (chunk.version ? "; upgrade limn" : ""));
    const uint32_t patchBytes = chunk.version >= 2 ? 88 : 84;
    ByteReader r(chunk.payload, "chunk TBLS");
    Tables t;
    t.depth = r.read<uint32_t>();
    if (t.depth > uint32_t(kMaxDepth))
        r.fail("depth " + std::to_string(t.depth) + " is out of range");
    uint32_t flags = r.read<uint32_t>();
    if (flags > 1) r.fail("unknown flags");
    t.uniform = flags & 1;
    uint8_t b = r.read<uint8_t>(), m = r.read<uint8_t>(), tri = r.read<uint8_t>(),
            fv = r.read<uint8_t>();
    if (b > 2 || m > 1 || tri > 1 || fv > 5) r.fail("scheme option out of range");
    t.options = {static_cast<BoundaryRule>(b), static_cast<CreaseMethod>(m),
                 static_cast<TriangleSubdivision>(tri), static_cast<FVarRule>(fv)};
    const uint32_t extra = r.read<uint32_t>(); // version 3: levels beyond depth; before: reserved
    if (chunk.version < 3 && extra != 0) r.fail("reserved field is not zero");
    if (extra > uint32_t(kMaxDepth) - t.depth || (extra && t.uniform))
        r.fail("irregular levels " + std::to_string(extra) + " out of range");
    t.irregularLevels = extra;
    const uint32_t D = t.depth + extra;
    t.topologyHash = r.read<uint64_t>();
    if (mesh && t.topologyHash != topologyHash(*mesh, t.options))
        throwBadInput("the subdivision tables were built for a different mesh topology or tags; "
                      "re-run limn-tables",
                      "chunk TBLS");
    t.totalVertices = r.read<uint32_t>();
    uint32_t patches = r.read<uint32_t>(), irregular = r.read<uint32_t>(),
             limits = r.read<uint32_t>();
    uint64_t sum = 0;
    for (uint32_t l = 0; l <= D; ++l) {
        LevelInfo L;
        L.first = r.read<uint32_t>();
        L.facePoints = r.read<uint32_t>();
        L.edgePoints = r.read<uint32_t>();
        L.vertexPoints = r.read<uint32_t>();
        L.regularPatches = r.read<uint32_t>();
        L.irregularFaces = r.read<uint32_t>();
        if (L.first != sum)
            r.fail("level " + std::to_string(l) + " does not start where the previous ends");
        sum += uint64_t(L.facePoints) + L.edgePoints + L.vertexPoints;
        if (sum > t.totalVertices) r.fail("level vertex counts exceed the total");
        t.levels.push_back(L);
    }
    if (sum != t.totalVertices) r.fail("level vertex counts do not add up to the total");
    if (mesh && t.levels[0].count() != mesh->vertexCount())
        r.fail("level 0 has " + std::to_string(t.levels[0].count()) + " vertices, the mesh " +
               std::to_string(mesh->vertexCount()));
    for (uint32_t l = 1; l <= D; ++l) {
        const LevelInfo &P = t.levels[l - 1], &L = t.levels[l];
        std::string lv = "level " + std::to_string(l);
        uint32_t parentEnd = P.first + P.count(), faceEnd = L.first + L.facePoints;
        t.facePoints.push_back(
            readTable(r, lv + " face points", L.facePoints, false, P.first, parentEnd));
        t.edgePoints.push_back(readTable(r, lv + " edge points", L.edgePoints, true, P.first,
                                         parentEnd, L.first, faceEnd));
        t.vertexPoints.push_back(readTable(r, lv + " vertex points", L.vertexPoints, true, P.first,
                                           parentEnd, L.first, faceEnd));
    }
    const uint32_t ptexCount = mesh ? ptexFaceCount(*mesh) : 0xFFFFFFFFu;
    // Every domain is a dyadic square of the ptex face at the tables' resolution R = 2^depth:
    // side W = 2^-k R (k <= depth), corner on the W grid. The tessellation divides by W.
    const uint32_t R = 1u << t.depth;
    struct Square {
        uint32_t ptex, W, U0, V0;
    };
    std::vector<Square> squares;
    auto checkDomain = [&](uint32_t ptex, float u0, float v0, float size, const std::string& what,
                           bool drawn = true) {
        if (ptex >= ptexCount)
            r.fail(what + " refers to ptex face " + std::to_string(ptex) + " that does not exist");
        const uint32_t most = drawn ? t.depth : D;
        if (!(size > 0) || !isDyadic(size, most) || !isDyadic(u0, most) ||
            !isDyadic(v0, most) || u0 < 0 || v0 < 0 || u0 + size > 1 || v0 + size > 1)
            r.fail(what + " has a domain outside its ptex face or finer than the tables' depth");
        if (!drawn) return; // sub-patches and leaves lie inside the irregular faces
        const uint32_t W = uint32_t(double(size) * R), U0 = uint32_t(double(u0) * R),
                       V0 = uint32_t(double(v0) * R);
        if ((W & (W - 1)) != 0 || U0 % W != 0 || V0 % W != 0)
            r.fail(what + " has a domain that is not a cell of its ptex face's quadtree");
        squares.push_back({ptex, W, U0, V0});
    };
    if (patches > r.remaining() / patchBytes)
        r.fail("patch count " + std::to_string(patches) + " is too large");
    auto readPatch = [&](Patch& p, const std::string& what, bool drawn) {
        for (uint32_t& cv : p.cv) cv = r.read<uint32_t>();
        p.ptex = r.read<uint32_t>();
        p.u0 = r.read<float>();
        p.v0 = r.read<float>();
        p.size = r.read<float>();
        uint32_t packed = r.read<uint32_t>();
        p.level = static_cast<uint8_t>(packed & 0xFF);
        p.boundary = static_cast<uint8_t>((packed >> 8) & 0xFF);
        p.crease = static_cast<uint8_t>((packed >> 16) & 0xFF);
        if ((packed >> 24) != 0 || p.boundary > 15 || (drawn ? p.level > t.depth : p.level <= t.depth || p.level > D))
            r.fail(what + ": bad level or boundary mask");
        if (chunk.version >= 2) p.sharpness = r.read<float>();
        // A single-crease patch: one crease edge, a finite sharpness > 0, no boundary.
        const bool oneBit = p.crease != 0 && (p.crease & (p.crease - 1)) == 0 && p.crease <= 8;
        if (p.crease ? !(oneBit && p.boundary == 0 && p.sharpness > 0 &&
                         p.sharpness < kInfiniteSharpness)
                     : p.sharpness != 0)
            r.fail(what + ": bad crease edge or sharpness");
        const LevelInfo& L = t.levels[p.level];
        for (uint32_t cv : p.cv)
            if (cv >= t.totalVertices || (cv != 0 && (cv < L.first || cv >= L.first + L.count())))
                r.fail(what + " has a control point outside its level");
        checkDomain(p.ptex, p.u0, p.v0, p.size, what, drawn);
    };
    t.patches.resize(patches);
    for (uint32_t i = 0; i < patches; ++i) readPatch(t.patches[i], "patch " + std::to_string(i), true);
    auto readFace = [&](IrregularFace& q, const std::string& what, bool drawn) {
        for (uint32_t& c : q.corner) {
            c = r.read<uint32_t>();
            if (c >= limits) r.fail(what + " refers to a missing limit point");
        }
        q.ptex = r.read<uint32_t>();
        q.u0 = r.read<float>();
        q.v0 = r.read<float>();
        q.size = r.read<float>();
        checkDomain(q.ptex, q.u0, q.v0, q.size, what, drawn);
    };
    if (irregular > r.remaining() / 32) r.fail("irregular face count is too large");
    t.irregular.resize(irregular);
    for (uint32_t i = 0; i < irregular; ++i) readFace(t.irregular[i], "irregular face " + std::to_string(i), true);
    if (chunk.version >= 3) {
        const uint32_t subs = r.read<uint32_t>();
        if (subs > r.remaining() / patchBytes) r.fail("sub-patch count " + std::to_string(subs) + " is too large");
        t.subPatches.resize(subs);
        for (uint32_t i = 0; i < subs; ++i) readPatch(t.subPatches[i], "sub-patch " + std::to_string(i), false);
        const uint32_t nodes = r.read<uint32_t>();
        if (nodes > r.remaining() / 16) r.fail("irregular node count is too large");
        if (nodes && nodes < irregular) r.fail("an irregular face has no quadtree");
        t.irregularNodes.resize(nodes);
        std::vector<uint32_t> codes = r.readArray<uint32_t>(uint64_t(nodes) * 4, "irregular nodes");
        const uint32_t leaves = r.read<uint32_t>();
        if (leaves > r.remaining() / 32) r.fail("irregular leaf count is too large");
        for (uint32_t i = 0; i < nodes; ++i)
            for (int q = 0; q < 4; ++q) {
                const uint32_t c = codes[4 * i + q], x = c & kNodeIndexMask, kind = c & ~kNodeIndexMask;
                // Children come after their parent, so every walk ends.
                const bool ok = c == kNodeNone || kind == kNodeBasis || (kind == kNodeSubPatch && x < subs) ||
                                (kind == kNodeChild && x > i && x < nodes) || (kind == kNodeLeaf && x < leaves);
                if (!ok) r.fail("irregular node " + std::to_string(i) + " has a bad child");
                t.irregularNodes[i][q] = c;
            }
        t.irregularLeaves.resize(leaves);
        for (uint32_t i = 0; i < leaves; ++i) readFace(t.irregularLeaves[i], "irregular leaf " + std::to_string(i), false);
        const uint32_t bases = r.read<uint32_t>();
        if (bases > r.remaining() / 8) r.fail("irregular basis count is too large");
        for (uint32_t i = 0; i < bases; ++i) {
            IrregularBasis basis;
            basis.valence = r.read<uint32_t>();
            basis.levels = r.read<uint32_t>();
            if (basis.valence < 3 || basis.valence > kMaxStencilValence || basis.levels < 1 ||
                basis.levels > uint32_t(kMaxDepth))
                r.fail("irregular basis " + std::to_string(i) + " has a bad valence or level count");
            basis.weights = r.readArray<float>(uint64_t(basis.levels) * 48 * basis.supportSize(),
                                               "irregular basis weights");
            for (float x : basis.weights)
                if (!(std::abs(x) <= kMaxStencilWeight))
                    r.fail("irregular basis " + std::to_string(i) + " has a bad weight");
            t.irregularBases.push_back(std::move(basis));
        }
        const uint32_t smooth = r.read<uint32_t>();
        if (smooth > r.remaining() / 12) r.fail("smooth irregular face count is too large");
        for (uint32_t i = 0; i < smooth; ++i) {
            Tables::SmoothIrregular f{r.read<uint32_t>(), r.read<uint32_t>(), r.read<uint32_t>()};
            if (f.basis >= bases || f.corner > 3) r.fail("smooth irregular face " + std::to_string(i) + " is bad");
            t.smoothIrregular.push_back(f);
        }
        const uint32_t points = r.read<uint32_t>();
        t.smoothPoints = r.readArray<uint32_t>(points, "smooth irregular points");
        const LevelInfo& LN = t.levels[t.depth];
        for (uint32_t v : t.smoothPoints)
            if (v < LN.first || v >= LN.first + LN.count()) r.fail("a smooth irregular point is not at the last level");
        for (const auto& f : t.smoothIrregular)
            if (uint64_t(f.first) + t.irregularBases[f.basis].supportSize() > points)
                r.fail("a smooth irregular face's points run past the end");
        // Basis codes name a smooth face, and only roots hold them (all four alike).
        for (uint32_t i = 0; i < nodes; ++i)
            for (uint32_t c : t.irregularNodes[i])
                if (c != kNodeNone && (c & ~kNodeIndexMask) == kNodeBasis &&
                    (i >= irregular || (c & kNodeIndexMask) >= smooth || t.irregularNodes[i][0] != c ||
                     t.irregularNodes[i][3] != c))
                    r.fail("irregular node " + std::to_string(i) + " has a bad basis code");
    }
    // The domains tile every ptex face exactly once, or not at all (a face without a limit
    // surface): no square inside another, areas adding up to R^2 (paper 000, 4.1: each face is
    // drawn by its patches and its irregular remainder).
    if (mesh) {
        std::sort(squares.begin(), squares.end(),
                  [](const Square& x, const Square& y) { return x.ptex < y.ptex; });
        std::unordered_set<uint64_t> present; // (log2 W, U0 / W, V0 / W) within one ptex face
        auto key = [](uint32_t W, uint32_t U0, uint32_t V0) {
            return uint64_t(std::countr_zero(W)) << 40 | uint64_t(U0 / W) << 20 | (V0 / W);
        };
        for (size_t first = 0, end = 0; first < squares.size(); first = end) {
            const uint32_t ptex = squares[first].ptex;
            present.clear();
            uint64_t area = 0;
            for (end = first; end < squares.size() && squares[end].ptex == ptex; ++end) {
                const Square& q = squares[end];
                if (!present.insert(key(q.W, q.U0, q.V0)).second)
                    r.fail("two domains cover the same square of ptex face " +
                           std::to_string(ptex));
                area += uint64_t(q.W) * q.W;
            }
            for (size_t k = first; k < end; ++k)
                for (uint32_t W = squares[k].W * 2; W <= R; W *= 2)
                    if (present.count(key(W, squares[k].U0 / W * W, squares[k].V0 / W * W)))
                        r.fail("a domain lies inside another one of ptex face " +
                               std::to_string(ptex));
            if (area != uint64_t(R) * R)
                r.fail("the domains do not cover ptex face " + std::to_string(ptex) +
                       " exactly once");
        }
    }
    // Limit points read level N (the irregular faces' corners) or level D (the leaves').
    const LevelInfo &LN = t.levels[t.depth], &LD = t.levels[D];
    uint32_t lo = LN.first, hi = LN.first + LN.count(), lo1 = LD.first, hi1 = LD.first + LD.count();
    t.limitPosition = readTable(r, "limit positions", limits, true, lo, hi, lo1, hi1);
    t.limitTangent1 = readTable(r, "limit tangents 1", limits, true, lo, hi, lo1, hi1);
    t.limitTangent2 = readTable(r, "limit tangents 2", limits, true, lo, hi, lo1, hi1);
    t.limitVertex = r.readArray<uint32_t>(limits, "limit vertices");
    for (uint32_t v : t.limitVertex)
        if (!((v >= lo && v < hi) || (v >= lo1 && v < hi1)))
            r.fail("a limit point's vertex is not at the last level");
    auto flags32 = r.readArray<uint32_t>(limits, "limit flags");
    for (uint32_t f : flags32) {
        if (f > 1) r.fail("unknown limit point flag");
        t.limitExact.push_back(f ? 0 : 1);
    }
    // Counted once per surface point, as buildTables does: those of the irregular faces' corners
    // (a leaf's corners repeat them deeper).
    std::vector<uint8_t> cornerOf(limits, 0);
    for (const auto& q : t.irregular)
        for (uint32_t c : q.corner) cornerOf[c] = 1;
    for (uint32_t i = 0; i < limits; ++i) t.approximateLimitPoints += cornerOf[i] && !t.limitExact[i];
    if (!r.atEnd())
        r.fail(std::to_string(r.remaining()) + " unexpected bytes after the last field");
    return t;
}

} // namespace limn
