#include "subdiv/tables_chunk.h"

#include "subdiv/tables_stream.h"
#include "subdiv/crease_basis.h"
#include "subdiv/tables_chain_records.h"
#include "subdiv/tables_program_dictionary.h"
#include "subdiv/tables_surface_records.h"

#include "base/bytes.h"
#include "base/cli.h"
#include "base/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

namespace limn {

namespace {

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

Chunk encodeTablesChunk(const Tables& t, uint32_t version) {
    // Tables with irregular bases are written as version 9 (their programs through the chunk's
    // dictionary); others as version 7, which readers since boundary bases know.
    if (version == 0) version = t.irregularBases.empty() ? kTablesChunkVersion : kTablesChunkDictionaryVersion;
    if (version < 3 || version > kTablesChunkDictionaryVersion)
        throw std::logic_error("TBLS: only versions 3 to 9 are written");
    if (version < 5)
        for (uint32_t i = 0; i < t.irregularNodes.size(); ++i)
            for (uint32_t c : t.irregularNodes[i])
                if (c != kNodeNone && (c & ~kNodeIndexMask) == kNodeBasis && !(i < t.irregular.size() && smoothRoot(t.irregularNodes[i])))
                    throw std::logic_error("TBLS: smooth faces below level N need version 5");
    const bool compact = version >= 4;
    const bool programs = version >= 5; // bases as programs, compact nodes and smooth faces
    for (const IrregularBasis& b : t.irregularBases)
        if (!programs && !b.hasWeights())
            throw std::logic_error("TBLS: bases built without their weights need version 5 or later");
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
    writeLevels(w, t.levels, version >= kTablesChunkDictionaryVersion);
    const uint32_t repeats = version >= 6 ? repeatedLevels(t) : 0u;
    if (version >= 6) w.write<uint32_t>(repeats);
    // Version 9: a table of no rows (a level below N where no quadtree refines) is not written.
    auto writeTable = [&](const StencilTable& x, bool weights) {
        if (version < kTablesChunkDictionaryVersion || x.rows() != 0) writeStencilTable(w, x, weights, compact);
    };
    for (uint32_t l = 0; l + 1 < t.levels.size(); ++l) {
        if (repeats >> (l + 1) & 1) continue; // level l + 1 is level l's, shifted
        writeTable(t.facePoints[l], false);
        writeTable(t.edgePoints[l], true);
        writeTable(t.vertexPoints[l], true);
    }
    auto writeFace = [&](const IrregularFace& q) {
        w.writeArray(std::span<const uint32_t>(q.corner, 4));
        w.write<uint32_t>(q.ptex);
        w.write<float>(q.u0);
        w.write<float>(q.v0);
        w.write<float>(q.size);
    };
    auto writeRecords = [&](const std::vector<Patch>& patches, bool domains) {
        if (compact) return writePatchStream(w, patches, domains);
        for (const Patch& p : patches) {
            w.writeArray(std::span<const uint32_t>(p.cv, 16));
            w.write<uint32_t>(p.ptex);
            w.write<float>(p.u0);
            w.write<float>(p.v0);
            w.write<float>(p.size);
            w.write<uint32_t>(uint32_t(p.level) | uint32_t(p.boundary) << 8 | uint32_t(p.crease) << 16);
            w.write<float>(p.sharpness);
        }
    };
    writeRecords(t.patches, true);
    for (const auto& q : t.irregular) writeFace(q);
    // Version 3: the irregular faces' quadtrees (docs/irregular.md).
    w.write<uint32_t>(static_cast<uint32_t>(t.subPatches.size()));
    writeRecords(t.subPatches, version < 6); // version 6: domains from the quadtrees
    w.write<uint32_t>(static_cast<uint32_t>(t.irregularNodes.size()));
    if (programs)
        writeNodeStream(w, t.irregularNodes);
    else
        for (const auto& n : t.irregularNodes) w.writeArray(std::span<const uint32_t>(n.data(), 4));
    w.write<uint32_t>(static_cast<uint32_t>(t.irregularLeaves.size()));
    for (const auto& q : t.irregularLeaves) writeFace(q);
    w.write<uint32_t>(static_cast<uint32_t>(t.irregularBases.size()));
    ChainProgramIndex chainPrograms;
    ProgramDictionary dictionaryOf;
    ProgramDictionary* dictionary = version >= kTablesChunkDictionaryVersion ? &dictionaryOf : nullptr;
    for (const auto& b : t.irregularBases) {
        if (b.chain) {
            if (version < kTablesChunkChainVersion)
                throw std::logic_error("TBLS: decaying-crease chains need version 8");
            w.write<uint32_t>(b.chain->end == CreaseEnd::Smooth ? b.chain->valence : 0u);
            w.write<uint32_t>(kChainConfigurationCode);
            w.write<uint32_t>(b.supportSize());
            w.write<uint32_t>(b.levels);
            writeChainBasis(w, b, chainPrograms, dictionary);
            continue;
        }
        if (programs) { // version 7: with its configuration (boundary bases)
            if (version >= 7)
                writeConfigurationBasis(w, b, dictionary);
            else
                writeBasisProgram(w, b);
            continue;
        }
        // Version 4: each of the k·48 sub-patch control points names its row of weights, and
        // equal rows are stored once (the three sub-patches of a band share half their points).
        if (!compact) {
            w.write<uint32_t>(b.valence);
            w.write<uint32_t>(b.levels);
            w.writeArray(b.weights);
            continue;
        }
        const size_t M = b.supportSize(), count = size_t(b.levels) * 48;
        // Rows are numbered in the order first met; equal means equal bits: the key is the
        // row's bytes, viewed in place in the basis's weights.
        std::unordered_map<std::string_view, uint16_t> rowOf;
        rowOf.reserve(count);
        std::vector<uint16_t> pick(count);
        std::vector<float> rows;
        for (size_t j = 0; j < count; ++j) {
            const float* row = b.weights.data() + j * M;
            const std::string_view bytes(reinterpret_cast<const char*>(row), M * sizeof(float));
            const auto [it, added] = rowOf.try_emplace(bytes, static_cast<uint16_t>(rowOf.size()));
            if (added) rows.insert(rows.end(), row, row + M);
            pick[j] = it->second;
        }
        w.write<uint32_t>(b.valence);
        w.write<uint32_t>(b.levels);
        w.write<uint32_t>(static_cast<uint32_t>(rowOf.size()));
        w.writeArray(pick);
        w.writeArray(rows);
    }
    w.write<uint32_t>(static_cast<uint32_t>(t.smoothIrregular.size()));
    if (programs)
        writeSmoothFaces(w, t);
    else
        for (const auto& f : t.smoothIrregular)
            for (uint32_t x : {f.basis, f.corner, f.first}) w.write<uint32_t>(x);
    w.write<uint32_t>(static_cast<uint32_t>(t.smoothPoints.size()));
    if (programs) writeSmoothPoints(w, t);
    if (!compact) w.writeArray(t.smoothPoints);
    if (compact && !programs) { // version 4: differences from the previous point
        std::vector<uint8_t> points;
        uint32_t previous = 0;
        for (uint32_t v : t.smoothPoints) {
            writeVarint(points, zigzag(int64_t(v) - previous));
            previous = v;
        }
        writeStream(w, points);
    }
    writeTable(t.limitPosition, true);
    writeTable(t.limitTangent1, true);
    writeTable(t.limitTangent2, true);
    w.writeArray(t.limitVertex);
    for (uint8_t e : t.limitExact) w.write<uint32_t>(e ? 0u : 1u); // bit 0: approximate
    return {kTablesChunk, version, w.take()};
}

Tables decodeTablesChunk(const Chunk& chunk, const Mesh* mesh) {
    // Version 1 has no single-crease patches: its patch records end before the sharpness.
    if (chunk.version > kTablesChunkDictionaryVersion || chunk.version == 0)
        throwBadInput("chunk TBLS version " + std::to_string(chunk.version) + " is " +
                      (chunk.version ? "newer than" : "not one") + " this limn reads (1 to " +
                      std::to_string(kTablesChunkDictionaryVersion) + ")" +
                      (chunk.version ? "; upgrade limn" : ""));
    const uint32_t patchBytes = chunk.version >= 2 ? 88 : 84;
    const bool compact = chunk.version >= 4; // compact stencil tables and bases
    const bool programs = chunk.version >= 5; // bases as programs, compact nodes and smooth faces
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
    const std::vector<LevelInfo> levels = readLevels(r, D + 1, chunk.version >= kTablesChunkDictionaryVersion);
    for (uint32_t l = 0; l <= D; ++l) {
        const LevelInfo& L = levels[l];
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
    // Version 9: a table of no rows is not stored.
    auto readTable = [&](const std::string& what, uint32_t rows, bool weights, uint32_t lo0, uint32_t hi0,
                         uint32_t lo1 = 0, uint32_t hi1 = 0) {
        if (chunk.version >= kTablesChunkDictionaryVersion && rows == 0) return StencilTable{};
        return readStencilTable(r, compact, what, rows, weights, lo0, hi0, lo1, hi1);
    };
    // Version 6: levels whose stencil tables are the previous level's, shifted (levels 2..D).
    const uint32_t repeats = chunk.version >= 6 ? r.read<uint32_t>() : 0u;
    if (repeats & ~(((2u << D) - 1u) & ~3u)) // D <= 16, checked above
        r.fail("repeated levels " + std::to_string(repeats) + " name a level without a previous one");
    for (uint32_t l = 1; l <= D; ++l) {
        const LevelInfo &P = t.levels[l - 1], &L = t.levels[l];
        std::string lv = "level " + std::to_string(l);
        uint32_t parentEnd = P.first + P.count(), faceEnd = L.first + L.facePoints;
        if (repeats >> l & 1) {
            appendRepeatedLevel(r, t, l);
            continue;
        }
        t.facePoints.push_back(
            readTable(lv + " face points", L.facePoints, false, P.first, parentEnd));
        t.edgePoints.push_back(readTable(lv + " edge points", L.edgePoints, true, P.first,
                                         parentEnd, L.first, faceEnd));
        t.vertexPoints.push_back(readTable(lv + " vertex points", L.vertexPoints, true, P.first,
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
    // Version 4's records come from a stream (writePatches); earlier ones are plain.
    StreamReader* in = nullptr;
    uint32_t lastCorner = 0, lastPtex = 0;
    auto readPatch = [&](Patch& p, const std::string& what, bool drawn, bool domains) {
        uint32_t packed = 0;
        if (in) {
            p.cv[5] = lastCorner = in->after(lastCorner, "a control point");
            for (int i = 0; i < 16; ++i) {
                if (i == 5) continue;
                const uint64_t z = in->varint();
                const int64_t x = z == 0 ? 0 : int64_t(p.cv[5]) + unzigzag(z - 1);
                if (x < 0 || x > int64_t(0xFFFFFFFFu)) in->fail(what + ": a control point out of range");
                p.cv[i] = static_cast<uint32_t>(x);
            }
            if (domains) p.ptex = lastPtex = in->after(lastPtex, "a ptex face");
            float* domain[3] = {&p.u0, &p.v0, &p.size};
            for (float* x : domain) {
                if (!domains) break;
                const uint64_t u = in->varint();
                if (u > 65536) in->fail(what + ": a domain outside its ptex face");
                *x = static_cast<float>(double(u) / 65536.0);
            }
            const uint64_t word = in->varint();
            if (word > 0xFFFFFFu) in->fail(what + ": bad level or boundary mask");
            packed = static_cast<uint32_t>(word);
            p.sharpness = (packed >> 16) & 0xFF ? in->rawFloat() : 0.0f;
        } else {
            for (uint32_t& cv : p.cv) cv = r.read<uint32_t>();
            p.ptex = r.read<uint32_t>();
            p.u0 = r.read<float>();
            p.v0 = r.read<float>();
            p.size = r.read<float>();
            packed = r.read<uint32_t>();
        }
        p.level = static_cast<uint8_t>(packed & 0xFF);
        p.boundary = static_cast<uint8_t>((packed >> 8) & 0xFF);
        p.crease = static_cast<uint8_t>((packed >> 16) & 0xFF);
        if ((packed >> 24) != 0 || p.boundary > 15 || (drawn ? p.level > t.depth : p.level <= t.depth || p.level > D))
            r.fail(what + ": bad level or boundary mask");
        if (chunk.version >= 2 && !in) p.sharpness = r.read<float>();
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
        if (domains) checkDomain(p.ptex, p.u0, p.v0, p.size, what, drawn);
    };
    // At least 20 bytes a record in a stream (16 control points, ptex, domain, packed word), 17
    // without the domain (version 6's sub-patches: assignSubPatchDomains sets it).
    auto readPatches = [&](std::vector<Patch>& out, uint32_t count, const std::string& what, bool drawn) {
        std::optional<StreamReader> stream;
        const bool domains = drawn || chunk.version < 6;
        if (compact) {
            stream.emplace(r, what + "es");
            if (count > stream->size() / (domains ? 20 : 17))
                r.fail(what + " count " + std::to_string(count) + " is too large");
            in = &*stream;
            lastCorner = lastPtex = 0;
        } else if (count > r.remaining() / patchBytes) {
            r.fail(what + " count " + std::to_string(count) + " is too large");
        }
        out.resize(count);
        for (uint32_t i = 0; i < count; ++i) readPatch(out[i], what + " " + std::to_string(i), drawn, domains);
        if (stream) stream->finish();
        in = nullptr;
    };
    readPatches(t.patches, patches, "patch", true);
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
        readPatches(t.subPatches, subs, "sub-patch", false);
        const uint32_t nodes = r.read<uint32_t>();
        if (!programs && nodes > r.remaining() / 16) r.fail("irregular node count is too large");
        if (nodes && nodes < irregular) r.fail("an irregular face has no quadtree");
        std::vector<uint32_t> codes;
        if (programs) {
            for (const auto& n : readNodeStream(r, nodes)) codes.insert(codes.end(), n.begin(), n.end());
        } else {
            codes = r.readArray<uint32_t>(uint64_t(nodes) * 4, "irregular nodes");
        }
        t.irregularNodes.resize(nodes);
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
        ChainPrograms chainPrograms;
        ProgramDictionary dictionary; // version 9
        // The bases' K x 48 x M weights are drawn from one GPU storage buffer (WebGPU: 128 MiB at
        // most), and a chain naming programs read before expands ~90 bytes to up to 1.6 MB (16
        // bands over 528 points): a small damaged file must not ask for gigabytes.
        uint64_t weights = 0;
        for (uint32_t i = 0; i < bases; ++i) {
            t.irregularBases.push_back(
                chunk.version >= 7 ? readConfigurationBasis(r, "irregular basis " + std::to_string(i), t.irregularBases,
                                                            chunk.version >= 8 ? &chainPrograms : nullptr,
                                                            chunk.version >= 9 ? &dictionary : nullptr)
                : programs         ? readBasisProgram(r, i, t.irregularBases)
                                   : readBasisWeights(r, i, compact, t.irregularBases));
            weights += t.irregularBases.back().weights.size();
            if (weights * sizeof(float) > kMaxBasisWeightBytes)
                r.fail("irregular bases 0 to " + std::to_string(i) + " expand to more than 128 MiB of weights");
        }
        const uint32_t smooth = r.read<uint32_t>();
        if (!programs && smooth > r.remaining() / 12) r.fail("smooth irregular face count is too large");
        if (programs) t.smoothIrregular = readSmoothFaces(r, smooth, t.irregularBases);
        for (uint32_t i = 0; !programs && i < smooth; ++i) {
            Tables::SmoothIrregular f{r.read<uint32_t>(), r.read<uint32_t>(), r.read<uint32_t>()};
            if (f.basis >= bases || f.corner > 3) r.fail("smooth irregular face " + std::to_string(i) + " is bad");
            t.smoothIrregular.push_back(f);
        }
        const uint32_t points = r.read<uint32_t>();
        if (programs) {
            t.smoothPoints = readSmoothPoints(r, points, t);
        } else if (compact) {
            StreamReader pts(r, "smooth irregular points");
            if (points > pts.size()) pts.fail("count " + std::to_string(points) + " is too large");
            t.smoothPoints.reserve(points);
            for (uint32_t i = 0, previous = 0; i < points; ++i)
                t.smoothPoints.push_back(previous = pts.after(previous, "a point"));
            pts.finish();
        } else {
            t.smoothPoints = r.readArray<uint32_t>(points, "smooth irregular points");
        }
        for (const auto& f : t.smoothIrregular)
            if (uint64_t(f.first) + t.irregularBases[f.basis].supportSize() > points)
                r.fail("a smooth irregular face's points run past the end");
        // Basis codes name a smooth face: roots (all four alike), and from version 5 deeper
        // nodes; each face's points at its level.
        if (const std::string bad = checkSmoothFaceLevels(t, chunk.version); !bad.empty()) r.fail(bad);
        if (chunk.version >= 6)
            if (const std::string bad = assignSubPatchDomains(t); !bad.empty()) r.fail(bad);
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
    t.limitPosition = readTable("limit positions", limits, true, lo, hi, lo1, hi1);
    t.limitTangent1 = readTable("limit tangents 1", limits, true, lo, hi, lo1, hi1);
    t.limitTangent2 = readTable("limit tangents 2", limits, true, lo, hi, lo1, hi1);
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
