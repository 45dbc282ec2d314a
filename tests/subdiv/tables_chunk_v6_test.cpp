// TBLS versions 6 and 7 (formats/tbls.md, "Repeated levels", "Sub-patch domains", "Boundary
// configurations"): what version 6 leaves out of version 5 is read back as the builder's tables,
// version 7's boundary bases and version 8's crease chains expand to the builder's weights, and
// hostile input is refused by name.
#include "base/error.h"
#include "mesh/import.h"
#include "subdiv/crease_basis.h"
#include "subdiv/evaluate.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/tables_build.h"
#include "subdiv/tables_chunk.h"
#include "subdiv/tables_program_dictionary.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
#include <filesystem>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>

using namespace limn;

namespace {

Mesh loadModel(const std::string& model) {
    Warnings w;
    return importMeshFile(test::modelPath(model).string(), w);
}

// Tables version 6 can hold: without boundary bases.
Tables buildAt(const Mesh& m, int depth) {
    Warnings w;
    TablesOptions o;
    o.depth = depth;
    o.boundaryBases = o.basisRimFeatures = o.creaseChains = false; // version 6's tables
    return buildTables(m, resolveSchemeOptions(m.tags, {}), o, w);
}

// Every basis of `back` expands to `good`'s weights and kinds, bit for bit; "" or what differs.
std::string sameBases(const Tables& good, const Tables& back) {
    if (back.irregularBases.size() != good.irregularBases.size()) return "basis count";
    for (size_t i = 0; i < good.irregularBases.size(); ++i) {
        const IrregularBasis &a = back.irregularBases[i], &b = good.irregularBases[i];
        if (a.weights.size() != b.weights.size() || a.kinds.size() != b.kinds.size() ||
            std::memcmp(a.weights.data(), b.weights.data(), a.weights.size() * sizeof(float)) != 0)
            return "basis " + std::to_string(i) + "'s weights";
        for (size_t k = 0; k < a.kinds.size(); ++k)
            if (a.kinds[k].crease != b.kinds[k].crease || a.kinds[k].boundary != b.kinds[k].boundary ||
                std::bit_cast<uint32_t>(a.kinds[k].sharpness) != std::bit_cast<uint32_t>(b.kinds[k].sharpness))
                return "basis " + std::to_string(i) + "'s kinds";
    }
    return {};
}


// Version 6 stores a level whose three stencil tables are the previous level's shifted one level
// as a bit (formats/tbls.md, "Repeated levels"): xord_boundary at depth 1 repeats levels 5 to 7
// below its boundary's extraordinary vertices (0xE0), the car at depth 3 level 6 below its
// decaying sharpness-6 creases and 9 below its smooth corners (0x240). The tables read back are
// the builder's, entry by entry (the builder refined every level; the reader copied them), and
// write version 5's bytes again.
TEST(TablesChunk, RepeatedLevelsReadAsTheBuildersTables) {
    for (auto [model, depth, bits] : {std::tuple{"quad/osd_catmark_xord_boundary.obj", 1, 0xE0u},
                                      std::tuple{"osd/catmark/catmark_car.obj", 3, 0x240u}}) {
        SCOPED_TRACE(model);
        Mesh m = loadModel(model);
        const Tables t = buildAt(m, depth);
        const Chunk v5 = encodeTablesChunk(t, 5), v6 = encodeTablesChunk(t, 6);
        ASSERT_EQ(v6.version, 6u);
        uint32_t repeats = 0;
        std::memcpy(&repeats, v6.payload.data() + 40 + 24 * t.levels.size(), 4);
        EXPECT_EQ(repeats, bits);
        EXPECT_LT(v6.payload.size(), v5.payload.size());
        const Tables back = decodeTablesChunk(v6, &m);
        ASSERT_EQ(back.edgePoints.size(), t.edgePoints.size());
        for (size_t l = 0; l < t.edgePoints.size(); ++l)
            for (auto [a, b] : {std::pair{&back.facePoints[l], &t.facePoints[l]}, {&back.edgePoints[l], &t.edgePoints[l]},
                                {&back.vertexPoints[l], &t.vertexPoints[l]}}) {
                EXPECT_EQ(a->start, b->start) << "level " << l + 1;
                EXPECT_EQ(a->indices, b->indices) << "level " << l + 1;
                EXPECT_EQ(a->weights, b->weights) << "level " << l + 1;
            }
        EXPECT_EQ(encodeTablesChunk(back, 5).payload, v5.payload);
        EXPECT_EQ(encodeTablesChunk(decodeTablesChunk(v5, &m), 6).payload, v6.payload);
    }
}

// A repeated level's bit is refused where there is no previous level's tables to copy (level 1,
// levels past N + K), where the counts differ, and where it is set on a level whose tables are
// stored (the stream then holds tables the reader does not expect); never read as other tables.
TEST(TablesChunk, HostileRepeatedLevelsAreRefused) {
    Mesh m = loadModel("quad/osd_catmark_xord_boundary.obj");
    const Tables t = buildAt(m, 1);
    const Chunk c = encodeTablesChunk(t);
    const size_t at = 40 + 24 * t.levels.size();
    auto with = [&](uint32_t repeats) {
        Chunk bad = c;
        std::memcpy(bad.payload.data() + at, &repeats, 4);
        return bad;
    };
    auto refused = [&](uint32_t repeats, const std::string& message) {
        try {
            decodeTablesChunk(with(repeats), &m);
            ADD_FAILURE() << "accepted repeated levels " << repeats;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    };
    const uint32_t D = static_cast<uint32_t>(t.levels.size() - 1), repeats = 0xE0u;
    ASSERT_NE(t.levels[1].count(), t.levels[2].count());
    refused(repeats | 2u, "name a level without a previous one");
    refused(repeats | 1u, "name a level without a previous one");
    refused(repeats | 2u << D, "name a level without a previous one");
    refused(repeats | 4u, "level 2 repeats level 1 but has other point counts");
    for (uint32_t l = 2; l <= D; ++l) // every other bit flipped: refused, whatever the reason
        if (!(repeats >> l & 1)) {
            EXPECT_THROW(decodeTablesChunk(with(repeats | 1u << l), &m), Error) << l;
        }
    for (uint32_t l = 2; l <= D; ++l) // a repeated level's tables missing from the stream
        if (repeats >> l & 1) {
            EXPECT_THROW(decodeTablesChunk(with(repeats & ~(1u << l)), &m), Error) << l;
        }
}

// Version 6's sub-patches hold no ptex face or domain: the reader takes each from its node's
// quadrant (formats/tbls.md, "Sub-patch domains"), and gets the builder's (compared here field by
// field on a mesh with boundary, crease and single-crease sub-patches). A sub-patch named twice
// or by no node, a node below the roots named by none, and a sub-patch whose level is not its
// node's plus one are refused by name.
TEST(TablesChunk, SubPatchDomainsComeFromTheQuadtrees) {
    Mesh m = loadModel("osd/catmark/catmark_single_crease.obj");
    const Tables good = buildAt(m, 2);
    ASSERT_FALSE(good.subPatches.empty());
    const Tables back = decodeTablesChunk(encodeTablesChunk(good), &m);
    ASSERT_EQ(back.subPatches.size(), good.subPatches.size());
    for (size_t i = 0; i < good.subPatches.size(); ++i) {
        const Patch &a = back.subPatches[i], &b = good.subPatches[i];
        EXPECT_TRUE(a.ptex == b.ptex && a.u0 == b.u0 && a.v0 == b.v0 && a.size == b.size && a.level == b.level)
            << "sub-patch " << i;
    }
    EXPECT_LT(encodeTablesChunk(good).payload.size(), encodeTablesChunk(good, 5).payload.size());
    // A node naming a sub-patch and one naming a child node.
    uint32_t sub = kNone, subQ = 0, child = kNone, childQ = 0;
    for (uint32_t i = 0; i < good.irregularNodes.size(); ++i)
        for (uint32_t q = 0; q < 4; ++q) {
            const uint32_t c = good.irregularNodes[i][q];
            if (c == kNodeNone) continue;
            if ((c & ~kNodeIndexMask) == kNodeSubPatch && sub == kNone) sub = i, subQ = q;
            if ((c & ~kNodeIndexMask) == kNodeChild && child == kNone) child = i, childQ = q;
        }
    ASSERT_NE(sub, kNone);
    ASSERT_NE(child, kNone);
    for (int which = 0; which < 4; ++which) {
        Tables t = good;
        std::array<uint32_t, 4>& node = t.irregularNodes[sub];
        if (which == 0) node[(subQ + 1) % 4] = node[subQ];
        if (which == 1) node[subQ] = kNodeNone;
        if (which == 2) t.irregularNodes[child][childQ] = kNodeNone;
        if (which == 3) { // two sub-patch codes of different levels swapped
            const auto level = [&](uint32_t c) { return t.subPatches[c & kNodeIndexMask].level; };
            uint32_t* other = nullptr;
            for (auto& n : t.irregularNodes)
                for (uint32_t& c : n)
                    if (!other && c != kNodeNone && (c & ~kNodeIndexMask) == kNodeSubPatch && level(c) != level(node[subQ]))
                        other = &c;
            ASSERT_NE(other, nullptr);
            std::swap(*other, node[subQ]);
        }
        const char* want[4] = {"is named twice", "is in no quadtree", "is in no quadtree", "its node's quadrant at"};
        try {
            decodeTablesChunk(encodeTablesChunk(t), &m);
            ADD_FAILURE() << "accepted case " << which;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(want[which]), std::string::npos) << which << ": " << e.what();
        }
    }
}

// Version 7 stores each basis with its configuration and support size, as FVSF version 3 does:
// tables with boundary bases (cube_no_bottom at depth 1: smooth boundary vertices of 2 to 4
// faces; edge-and-corner catmark_edgecorner's corners) read back with the builder's weights, to
// the bit; version 6 cannot hold them; tables without them read the same from versions 6 and 7.
// A configuration that is not one (a place beyond its fan, a fan of more than kMaxBasisValence
// faces), one twice, and weights outside [-4, 5] are refused by name.
TEST(TablesChunk, BoundaryBasesReadAsTheBuildersAndHostileOnesAreRefused) {
    Mesh m = loadModel("tri/cube_no_bottom.obj");
    Warnings w;
    TablesOptions o;
    o.depth = 1;
    o.boundaryBases = o.basisRimFeatures = true;
    const Tables good = buildTables(m, resolveSchemeOptions(m.tags, {}), o, w);
    size_t boundary = 0;
    for (const IrregularBasis& b : good.irregularBases) boundary += b.configuration.boundary;
    ASSERT_GT(boundary, 0u);
    const Chunk c = encodeTablesChunk(good);
    ASSERT_EQ(c.version, kTablesChunkDictionaryVersion);
    EXPECT_EQ(sameBases(good, decodeTablesChunk(encodeTablesChunk(good, 7), &m)), "");
    const Tables back = decodeTablesChunk(c, &m);
    ASSERT_EQ(back.irregularBases.size(), good.irregularBases.size());
    for (size_t i = 0; i < good.irregularBases.size(); ++i) {
        const IrregularBasis &a = back.irregularBases[i], &b = good.irregularBases[i];
        EXPECT_TRUE(a.configuration == b.configuration && a.supportSize() == b.supportSize()) << "basis " << i;
        ASSERT_EQ(a.weights.size(), b.weights.size());
        EXPECT_EQ(std::memcmp(a.weights.data(), b.weights.data(), a.weights.size() * sizeof(float)), 0) << "basis " << i;
    }
    EXPECT_EQ(encodeTablesChunk(back).payload, c.payload);
    EXPECT_THROW(encodeTablesChunk(good, 6), std::logic_error);
    const Tables plain = buildAt(m, 1);
    EXPECT_EQ(encodeTablesChunk(decodeTablesChunk(encodeTablesChunk(plain, 6), &m)).payload,
              encodeTablesChunk(plain).payload);
    size_t first = good.irregularBases.size();
    for (size_t i = 0; i < good.irregularBases.size() && first == good.irregularBases.size(); ++i)
        if (good.irregularBases[i].configuration.boundary) first = i;
    for (int which = 0; which < 4; ++which) {
        Tables t = good;
        IrregularBasis& b = t.irregularBases[first];
        if (which == 0) b.configuration.position = b.valence;
        if (which == 1) b.valence = b.configuration.valence = kMaxBasisValence + 1;
        if (which == 2) t.irregularBases.push_back(b);
        if (which == 3)
            for (uint32_t r = 0; r < b.program.rows(); ++r)
                if (!b.program.averaged[r]) b.program.weight[b.program.start[r]] *= 4.0f;
        const char* want[4] = {"bad configuration", "bad configuration", "repeats a configuration",
                               "has a weight outside [-4, 5]"};
        try {
            decodeTablesChunk(encodeTablesChunk(t), &m);
            ADD_FAILURE() << "accepted case " << which;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(want[which]), std::string::npos) << which << ": " << e.what();
        }
    }
}

} // namespace

namespace {

Tables buildChains(const Mesh& m, int depth, bool chains = true, bool weights = true) {
    Warnings w;
    TablesOptions o;
    o.depth = depth;
    o.creaseChains = chains;
    o.basisWeights = weights;
    return buildTables(m, resolveSchemeOptions(m.tags, {}), o, w);
}

} // namespace

// TBLS version 8's decaying-crease chains (formats/tbls.md, "Decaying-crease chains"): a damaged
// chain is refused naming what is wrong (a kind with two crease edges, more bands than levels, a
// smooth end naming no basis or another valence's, or whose next support is not its basis's, a
// control point or a regular end's row that names no row of its program), never expanded; and random bit flips are refused or read as
// tables whose chains expand (ASan run: no read out of bounds).
TEST(TablesChunk, HostileCreaseChainsAreRefused) {
    const Mesh m = loadModel("osd/catmark/catmark_chaikin0.obj");
    const Tables good = buildChains(m, 2);
    ASSERT_EQ(encodeTablesChunk(good).version, kTablesChunkDictionaryVersion);
    for (const uint32_t version : {kTablesChunkChainVersion, kTablesChunkDictionaryVersion}) {
        SCOPED_TRACE("version " + std::to_string(version));
        const Chunk c = encodeTablesChunk(good, version);
        int smooth = -1, regular = -1;
        for (size_t b = 0; b < good.irregularBases.size(); ++b)
            if (good.irregularBases[b].chain)
                (good.irregularBases[b].chain->end == CreaseEnd::Smooth ? smooth : regular) = int(b);
        ASSERT_GE(smooth, 0);
        ASSERT_GE(regular, 0);
        auto expectRefused = [&](int basis, const std::function<void(CreaseChain&)>& damage, const std::string& why) {
            Tables t = good;
            auto chain = std::make_shared<CreaseChain>(*t.irregularBases[size_t(basis)].chain);
            damage(*chain);
            t.irregularBases[size_t(basis)].chain = chain;
            try {
                decodeTablesChunk(encodeTablesChunk(t, version), &m);
                ADD_FAILURE() << "accepted: " << why;
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
            }
        };
        expectRefused(smooth, [](CreaseChain& x) { x.bands[0].kind[0] = {0, 3, 2.0f}; }, "bad patch kind");
        expectRefused(smooth, [](CreaseChain& x) { x.bands[0].kind[1] = {1, 1, 2.0f}; }, "bad patch kind");
        expectRefused(smooth, [&](CreaseChain& x) { x.bands.resize(good.irregularLevels + 1, x.bands.back()); },
                      "bad end, band count");
        expectRefused(smooth, [](CreaseChain& x) { x.valence = x.valence == 3 ? 5 : 3; }, "smooth end names basis");
        expectRefused(smooth, [](CreaseChain& x) { x.endBasis = 1000; }, "names a missing basis");
        expectRefused(smooth, [](CreaseChain& x) { x.bands.back().program.nextSupport.pop_back(); }, "bad next support");
        expectRefused(smooth, [](CreaseChain& x) { x.bands[0].program.controlRow[5] = x.bands[0].program.rows(); },
                      "names a missing row");
        expectRefused(regular, [](CreaseChain& x) { x.bands.back().centreRow[3] = x.bands.back().program.rows(); },
                      "names a missing row");
        expectRefused(regular, [](CreaseChain& x) { x.bands.back().centreKind = {0, 1, 1.5f}; }, "has a crease");
        std::mt19937 rng(8);
        size_t rejected = 0;
        for (int trial = 0; trial < 1500; ++trial) {
            Chunk bad = c;
            for (int k = 0; k < 1 + trial % 3; ++k)
                bad.payload[rng() % bad.payload.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
            try {
                const Tables t = decodeTablesChunk(bad, &m);
                for (const IrregularBasis& b : t.irregularBases)
                    ASSERT_EQ(b.weights.size(), size_t(b.levels) * 48 * b.supportSize());
            } catch (const Error&) {
                ++rejected;
            }
        }
        EXPECT_GT(rejected, 500u);
    }
}


// The encoder writes the bases' and chains' programs with their rows in a canonical order, so
// that the same program built with its rows in another order (another face's numbering) is
// stored once, and version 9 through the chunk's program dictionary: the reader expands versions
// 7 or 8 and 9 to the builder's weights and kinds, bit for bit, and the bytes read back write the
// same bytes. catmark_bishop d2 (68 chains, sharpness-6 creases; smooth ends), chaikin0 d2
// (regular ends) and xord_boundary d2 (boundary bases). LIMN_CHAIN_SWEEP=1 runs every catmark
// shape limn accepts at depths 1-3. Tables built without the bases' weights (limn-tables:
// TablesOptions::basisWeights) write the same bytes, so the weights read back from them are the
// builder's too.
TEST(TablesChunk, ProgramDictionaryExpandsToTheBuildersWeights) {
    std::vector<std::pair<std::string, int>> cases = {{"osd/catmark/catmark_bishop.obj", 2},
                                                      {"osd/catmark/catmark_chaikin0.obj", 2},
                                                      {"osd/catmark/catmark_xord_boundary.obj", 2}};
    if (std::getenv("LIMN_CHAIN_SWEEP")) {
        cases.clear();
        for (const auto& e : std::filesystem::directory_iterator(test::modelPath("osd/catmark")))
            if (e.path().extension() == ".obj")
                for (int d = 1; d <= 3; ++d) cases.emplace_back("osd/catmark/" + e.path().filename().string(), d);
        std::sort(cases.begin(), cases.end());
    }
    size_t chains = 0, tables = 0;
    for (const auto& [model, depth] : cases) {
        Tables good;
        Mesh m;
        try {
            m = loadModel(model);
            good = buildChains(m, depth);
        } catch (const Error&) {
            continue; // a shape limn refuses
        }
        for (const IrregularBasis& b : good.irregularBases) chains += b.chain != nullptr;
        ++tables;
        const Chunk c = encodeTablesChunk(good);
        const Tables back = decodeTablesChunk(c, &m);
        EXPECT_EQ(sameBases(good, back), "") << model << " d" << depth;
        EXPECT_EQ(encodeTablesChunk(buildChains(m, depth, true, false)).payload, c.payload) << model << " d" << depth;
        const bool chained = std::any_of(good.irregularBases.begin(), good.irregularBases.end(),
                                         [](const IrregularBasis& b) { return b.chain != nullptr; });
        const Chunk older = encodeTablesChunk(good, chained ? kTablesChunkChainVersion : 7);
        EXPECT_EQ(sameBases(good, decodeTablesChunk(older, &m)), "") << model << " d" << depth << " v" << older.version;
        if (!good.irregularBases.empty()) {
            EXPECT_LT(c.payload.size(), older.payload.size()) << model << " d" << depth << " " << c.payload.size() << " " << older.payload.size() << " v" << c.version << " v" << older.version << " bases " << good.irregularBases.size();
        }
        EXPECT_EQ(encodeTablesChunk(back).payload, c.payload) << model << " d" << depth;
    }
    EXPECT_GT(chains, 0u);
    // Version 9's levels are a stream of counts (each level's first implied): counts past the
    // total and a stream cut short are refused by name.
    const Mesh m = loadModel("osd/catmark/catmark_chaikin0.obj");
    const Tables good = buildChains(m, 2);
    Tables more = good;
    more.levels[1].edgePoints += 1;
    EXPECT_THROW(
        try { decodeTablesChunk(encodeTablesChunk(more), &m); } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("level vertex counts"), std::string::npos) << e.what();
            throw;
        },
        Error);
    Chunk cut = encodeTablesChunk(good);
    cut.payload[40] = 2; // the levels stream's length: 2 bytes
    EXPECT_THROW(decodeTablesChunk(cut, &m), Error);
    RecordProperty("tables", int(tables));
    RecordProperty("chains", int(chains));
}

// Chains against the quadtrees they replace, on the small crease shapes where every face around a
// crease's end is its own configuration: version 8's chains were up to 40% bigger there (torus_
// creases1 d2 11,728 bytes against 9,860, chaikin2 d3 18,748 against 13,416, tent_creases0 d1 5,056
// against 3,740); version 9's program dictionary names their rows, so torus_creases1 is smaller
// with chains and the other two within 6% (measured 5.0% and 2.4%), while shared chains still
// halve chaikin0's (docs/irregular-crease-trees.md, "Chains that do not pay off").
TEST(TablesChunk, CreaseChainsTakeNoBytes) {
    for (const auto& [model, depth, slack] : {std::tuple{"catmark_torus_creases1.obj", 2, 1.0},
                                              std::tuple{"catmark_chaikin2.obj", 3, 1.06},
                                              std::tuple{"catmark_tent_creases0.obj", 1, 1.06}}) {
        SCOPED_TRACE(std::string(model) + " depth " + std::to_string(depth));
        const Mesh m = loadModel(std::string("osd/catmark/") + model);
        EXPECT_LE(double(encodeTablesChunk(buildChains(m, depth)).payload.size()),
                  slack * double(encodeTablesChunk(buildChains(m, depth, false)).payload.size()));
    }
    const Mesh m = loadModel("osd/catmark/catmark_chaikin0.obj");
    EXPECT_LT(encodeTablesChunk(buildChains(m, 2)).payload.size(),
              encodeTablesChunk(buildChains(m, 2, false)).payload.size() * 6 / 10);
}

// A chain naming programs read before takes a few dozen bytes and expands to K x 48 x M weights:
// copies of chaikin0 d2's largest chain past 128 MiB of weights (the bases' GPU buffer, WebGPU's
// limit) are refused by name once past it, not read on into gigabytes.
TEST(TablesChunk, BasesPastTheirGpuBufferAreRefused) {
    const Mesh m = loadModel("osd/catmark/catmark_chaikin0.obj");
    Tables t = buildChains(m, 2);
    size_t largest = 0;
    for (size_t b = 0; b < t.irregularBases.size(); ++b)
        if (t.irregularBases[b].chain && t.irregularBases[b].weights.size() > t.irregularBases[largest].weights.size())
            largest = b;
    ASSERT_TRUE(t.irregularBases[largest].chain);
    const size_t copies = (size_t(32) << 20) / t.irregularBases[largest].weights.size() + 1;
    t.irregularBases.insert(t.irregularBases.end(), copies, t.irregularBases[largest]);
    const Chunk c = encodeTablesChunk(t);
    RecordProperty("bytes", int(c.payload.size()));
    RecordProperty("copies", int(copies));
    try {
        decodeTablesChunk(c, &m);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("expand to more than 128 MiB of weights"), std::string::npos) << e.what();
    }
}

// Tables built without their bases' weights (TablesOptions::basisWeights, for writing only) are
// refused where the weights would be read: drawn records, CPU evaluation, and TBLS versions that
// store weights (before 5). And the builder takes no basis whose weights would pass the 128 MiB
// that readers accept (addBasis): such faces are refined instead.
TEST(TablesChunk, TablesWithoutBasisWeightsAreOnlyWritten) {
    const Mesh m = loadModel("osd/catmark/catmark_chaikin0.obj");
    const Tables t = buildChains(m, 2, true, false);
    ASSERT_FALSE(t.smoothIrregular.empty());
    for (const IrregularBasis& b : t.irregularBases) {
        EXPECT_FALSE(b.hasWeights());
        EXPECT_GT(b.weightCount(), 0u);
    }
    const uint32_t smooth = 0;
    std::vector<glm::dvec3> V(m.vertexCount(), glm::dvec3(0));
    glm::dvec3 P[4][4];
    EXPECT_THROW(smoothSubPatchControlPoints(t, smooth, V, 1, 1, P), std::logic_error);
    EXPECT_THROW(encodeTablesChunk(t, 4), std::logic_error);
    const Tables full = buildChains(m, 2);
    for (size_t b = 0; b < full.irregularBases.size(); ++b)
        EXPECT_EQ(full.irregularBases[b].weights.size(), t.irregularBases[b].weightCount()) << "basis " << b;

    AdaptiveLevels a;
    IrregularBasis basis = full.irregularBases[0];
    const uint64_t cap = kMaxBasisWeightBytes / sizeof(float);
    a.basisWeightCount = cap - basis.weightCount();
    EXPECT_EQ(addBasis(a, basis), 0); // exactly at the cap
    EXPECT_EQ(a.basisWeightCount, cap);
    EXPECT_EQ(addBasis(a, basis), -2); // one more would pass it
    EXPECT_EQ(a.bases.size(), 1u);
}

// canonicalProgram's order (tables_program_dictionary.h) written out by hand for a three-row
// program over four support points, given in row order (each row reads earlier rows) and with
// its last row first (reading later rows: the general rounds); then the dictionary's run
// (formats/tbls.md, "Program dictionary") for the same program written twice.
TEST(TablesChunk, CanonicalProgramOrdersRowsAsWrittenDown) {
    const uint32_t M = 4;
    auto program = [](std::vector<uint32_t> start, std::vector<uint32_t> source, std::vector<float> weight,
                      std::vector<uint8_t> averaged, uint32_t control, std::vector<uint32_t> next) {
        BasisProgram p;
        p.start = std::move(start);
        p.source = std::move(source);
        p.weight = std::move(weight);
        p.averaged = std::move(averaged);
        p.controlRow.fill(kNone);
        p.controlRow[0] = control;
        p.nextSupport = std::move(next);
        return p;
    };
    // a = 0.5 x2 + 0.5 x3, b = the average of x0 and x1, c = 0.25 a + 0.75 b.
    const BasisProgram forward = program({0, 2, 4, 6}, {2, 3, 0, 1, M + 0, M + 1}, {0.5f, 0.5f, 1, 1, 0.25f, 0.75f},
                                         {0, 1, 0}, 2, {0, 1});
    const BasisProgram backward = program({0, 2, 4, 6}, {M + 1, M + 2, 2, 3, 0, 1}, {0.25f, 0.75f, 0.5f, 0.5f, 1, 1},
                                          {0, 0, 1}, 0, {1, 2});
    // Round 0: a and b (a first: not averaged before averaged); round 1: c.
    std::vector<uint32_t> moved;
    for (const auto& [p, expectMoved] : {std::pair{forward, std::vector<uint32_t>{0, 1, 2}},
                                         std::pair{backward, std::vector<uint32_t>{2, 0, 1}}}) {
        const BasisProgram c = canonicalProgram(p, M, moved);
        EXPECT_EQ(moved, expectMoved);
        EXPECT_EQ(c.start, (std::vector<uint32_t>{0, 2, 4, 6}));
        EXPECT_EQ(c.source, (std::vector<uint32_t>{2, 3, 0, 1, M + 0, M + 1}));
        EXPECT_EQ(c.weight, (std::vector<float>{0.5f, 0.5f, 1, 1, 0.25f, 0.75f}));
        EXPECT_EQ(c.averaged, (std::vector<uint8_t>{0, 1, 0}));
        EXPECT_EQ(c.controlRow[0], 2u);
        EXPECT_EQ(c.controlRow[1], kNone);
        EXPECT_EQ(c.nextSupport, (std::vector<uint32_t>{0, 1}));
    }
    // Written twice: the second time the row count, then one run (h = 2 back << 2 | 3, count - 2
    // = 1) and the 48 control and 2 support rows in bit_width(4) = 3 bits each (19 bytes).
    ProgramDictionary d;
    std::vector<uint8_t> first, second;
    writeDictionaryProgram(first, canonicalProgram(forward, M, moved), d);
    writeDictionaryProgram(second, canonicalProgram(backward, M, moved), d);
    ASSERT_EQ(second.size(), 3u + 19u);
    EXPECT_EQ(second[0], 3);
    EXPECT_EQ(second[1], 11);
    EXPECT_EQ(second[2], 1);
    EXPECT_TRUE(std::equal(second.begin() + 3, second.end(), first.end() - 19));
}
