// The TBLS chunk: lossless round trip, a function of topology only, and hostile input.
#include "base/error.h"
#include "container/container.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "subdiv/tables_chunk.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/tables_stream.h"
#include "subdiv/tables_surface_records.h"
#include "tess/tessellation.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <random>

using namespace limn;

namespace {

Mesh load(const std::string& model) {
    Warnings w;
    return importMeshFile(test::modelPath(model).string(), w);
}

Tables build(const Mesh& m, int depth, bool uniform = false, bool smoothBelowDepth = true) {
    Warnings w;
    TablesOptions o;
    o.depth = depth;
    o.uniform = uniform;
    o.smoothFacesBelowDepth = smoothBelowDepth;
    o.creaseChains = false; // the quadtrees' records (and versions before 8) are what these tests read
    // Tables older versions can hold (versions 3 and 4: no smooth face below level N; before 7:
    // no boundary basis).
    o.boundaryBases = o.basisRimFeatures = smoothBelowDepth;
    return buildTables(m, resolveSchemeOptions(m.tags, {}), o, w);
}

TEST(TablesChunk, RoundTripIsLossless) {
    Mesh m = load("osd/catmark/catmark_cubes_semisharp.obj");
    for (bool uniform : {false, true}) {
        Chunk c = encodeTablesChunk(build(m, 3, uniform));
        Tables t = decodeTablesChunk(c, &m);
        EXPECT_EQ(encodeTablesChunk(t).payload, c.payload);
        EXPECT_EQ(t.uniform, uniform);
        EXPECT_EQ(t.depth, 3u);
    }
}

// Version 4 stores the same tables as version 3 in fewer bytes (compact stencil tables, patch
// records and per-valence bases), version 5 in fewer still (bases as their programs, compact
// nodes and smooth faces): all three read back to the same tables, weights to the bit, on meshes
// whose irregular faces take every kind of surface (bases, sub-patch quadtrees with boundaries,
// creases and single-crease sub-patches, leaves). Tables read from versions 3 and 4 are written
// as version 5 with the program of each basis's valence. (Tables without smooth faces below
// level N: versions 3 and 4 cannot hold those; SmoothFacesBelowRootsAreChecked round-trips them.)
TEST(TablesChunk, OlderVersionsReadAsVersionFive) {
    for (const char* model : {"osd/catmark/catmark_smoothtris0.obj", "osd/catmark/catmark_cubes_semisharp.obj",
                              "quad/osd_catmark_xord_boundary.obj", "osd/catmark/catmark_single_crease.obj"}) {
        SCOPED_TRACE(model);
        Mesh m = load(model);
        for (int depth : {1, 2}) {
            const Tables t = build(m, depth, false, false);
            const Chunk v3 = encodeTablesChunk(t, 3), v4 = encodeTablesChunk(t, 4), v5 = encodeTablesChunk(t, 5);
            ASSERT_EQ(v4.version, 4u);
            ASSERT_EQ(v5.version, 5u);
            EXPECT_LT(v4.payload.size(), v3.payload.size() * 3 / 4);
            EXPECT_LE(v5.payload.size(), v4.payload.size());
            if (!t.irregularBases.empty()) {
                EXPECT_LT(v5.payload.size(), v4.payload.size());
            }
            const Tables a = decodeTablesChunk(v3, &m), b = decodeTablesChunk(v4, &m), c = decodeTablesChunk(v5, &m);
            EXPECT_EQ(encodeTablesChunk(c, 3).payload, v3.payload);
            EXPECT_EQ(encodeTablesChunk(c, 4).payload, v4.payload);
            EXPECT_EQ(encodeTablesChunk(a, 5).payload, v5.payload);
            EXPECT_EQ(encodeTablesChunk(b, 5).payload, v5.payload);
            EXPECT_EQ(encodeTablesChunk(c).payload, encodeTablesChunk(t).payload); // version 6
            EXPECT_FALSE(c.subPatches.empty() && c.irregularBases.empty());
            ASSERT_EQ(c.irregularBases.size(), t.irregularBases.size());
            for (size_t i = 0; i < t.irregularBases.size(); ++i) {
                const std::vector<float>&x = t.irregularBases[i].weights, &y = c.irregularBases[i].weights;
                ASSERT_EQ(x.size(), y.size());
                EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "basis " << i;
            }
        }
    }
}

// Version 5's reader expands each basis from its program with the builder's arithmetic: the
// weights the GPU gets are the builder's, to the bit, for every valence a basis is built for
// (checked by hand at K = 16 too).
TEST(TablesChunk, BasisProgramsExpandToTheBuildersWeights) {
    size_t differ = 0;
    for (uint32_t n = 3; n <= kMaxBasisValence; ++n) {
        if (n == 4) continue;
        const IrregularBasis built = buildIrregularBasis(n, 6);
        ByteWriter w;
        writeBasisProgram(w, built);
        const std::vector<uint8_t> bytes = w.take();
        ByteReader r(bytes, "test");
        const IrregularBasis read = readBasisProgram(r, 0, {});
        EXPECT_TRUE(r.atEnd());
        ASSERT_EQ(read.weights.size(), built.weights.size()) << "valence " << n;
        differ += std::memcmp(read.weights.data(), built.weights.data(), built.weights.size() * sizeof(float)) != 0;
    }
    EXPECT_EQ(differ, 0u);
}

// Tables are built from topology alone: moving every vertex changes no byte (paper 000: only the
// GPU passes re-run when an animated mesh moves).
// Version 2 added a sharpness to every patch record, version 3 the irregular faces' surface (six
// counts after the irregular faces, zero for tables without it); a version-1 chunk (the same
// bytes without them) still reads, as tables without single-crease patches and with bilinear
// irregular faces; other versions are refused by name.
TEST(TablesChunk, ReadsVersionOneAndRefusesUnknownVersions) {
    Mesh m = load("osd/catmark/catmark_single_crease.obj");
    Warnings w;
    TablesOptions o;
    o.depth = 3;
    o.singleCreasePatches = false;
    o.irregularLevels = 0;
    Tables t = buildTables(m, resolveSchemeOptions(m.tags, {}), o, w);
    Chunk v2 = encodeTablesChunk(t, 3); // the plain layout of versions 1 to 3
    ASSERT_EQ(v2.version, 3u);
    // The patch records follow the header, the levels and the level stencil tables.
    auto tableBytes = [](const StencilTable& table, bool weights) {
        return 16 + 4 * (table.start.size() + table.indices.size() + (weights ? table.weights.size() : 0));
    };
    size_t at = 40 + 24 * t.levels.size();
    for (uint32_t l = 0; l < t.depth; ++l)
        at += tableBytes(t.facePoints[l], false) + tableBytes(t.edgePoints[l], true) +
              tableBytes(t.vertexPoints[l], true);
    Chunk v1{v2.type, 1, {}};
    v1.payload.assign(v2.payload.begin(), v2.payload.begin() + at);
    for (size_t i = 0; i < t.patches.size(); ++i, at += 88)
        v1.payload.insert(v1.payload.end(), v2.payload.begin() + at, v2.payload.begin() + at + 84);
    const size_t faces = at + 32 * t.irregular.size();
    v1.payload.insert(v1.payload.end(), v2.payload.begin() + at, v2.payload.begin() + faces);
    for (size_t i = 0; i < 24; ++i) ASSERT_EQ(v2.payload[faces + i], 0) << "version 3's counts";
    v1.payload.insert(v1.payload.end(), v2.payload.begin() + faces + 24, v2.payload.end());
    EXPECT_EQ(encodeTablesChunk(decodeTablesChunk(v1, &m), 3).payload, v2.payload);
    EXPECT_EQ(encodeTablesChunk(decodeTablesChunk(v1, &m)).payload, encodeTablesChunk(t).payload);

    o.singleCreasePatches = true;
    Tables crease = buildTables(m, resolveSchemeOptions(m.tags, {}), o, w);
    size_t single = 0;
    for (const Patch& p : crease.patches) single += p.crease != 0;
    EXPECT_GT(single, 0u);
    Tables back = decodeTablesChunk(encodeTablesChunk(crease), &m);
    for (size_t i = 0; i < back.patches.size(); ++i) {
        EXPECT_EQ(back.patches[i].crease, crease.patches[i].crease);
        EXPECT_EQ(back.patches[i].sharpness, crease.patches[i].sharpness);
    }
    for (uint32_t version : {0u, kTablesChunkDictionaryVersion + 1}) {
        Chunk bad = v2;
        bad.version = version;
        try {
            decodeTablesChunk(bad, &m);
            ADD_FAILURE() << "version " << version << " was read";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("chunk TBLS version " + std::to_string(version)),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(TablesChunk, MovingVerticesChangesNoByte) {
    Mesh m = load("quad/spot_control_mesh.obj");
    Chunk before = encodeTablesChunk(build(m, 4));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (auto& p : m.positions) p += glm::dvec3(jitter(rng), jitter(rng), jitter(rng));
    EXPECT_EQ(encodeTablesChunk(build(m, 4)).payload, before.payload);
}

TEST(TablesChunk, RefusesTablesOfAnotherTopology) {
    Mesh m = load("osd/catmark/catmark_cube_creases0.obj");
    Chunk c = encodeTablesChunk(build(m, 2));
    m.tags.creases.push_back({0, 1, 3.0f});
    EXPECT_THROW(decodeTablesChunk(c, &m), Error);
}

TEST(TablesChunk, EveryTruncationIsRejected) {
    Mesh m = load("quad/osd_catmark_pyramid.obj");
    Chunk c = encodeTablesChunk(build(m, 2));
    for (size_t n = 0; n < c.payload.size(); ++n) {
        Chunk cut{c.type, c.version, {c.payload.begin(), c.payload.begin() + static_cast<long>(n)}};
        EXPECT_THROW(decodeTablesChunk(cut, &m), Error) << "prefix of " << n << " bytes";
    }
    Chunk longer = c;
    longer.payload.push_back(0);
    EXPECT_THROW(decodeTablesChunk(longer, &m), Error);
}

// Random corruption never crashes the reader: it either rejects the chunk or returns tables
// whose every index is in bounds and whose domains tessellate (what limn-render does next; any
// out-of-range access shows under ASan, which scripts/test.sh asan runs).
TEST(TablesChunk, CorruptedBytesAreRejectedOrSafe) {
    Mesh m = load("quad/osd_catmark_xord_boundary.obj");
    Chunk c = encodeTablesChunk(build(m, 2));
    std::mt19937 rng(11);
    size_t rejected = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        Chunk bad = c;
        for (int k = 0; k < 1 + trial % 4; ++k)
            bad.payload[rng() % bad.payload.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
        try {
            Tables t = decodeTablesChunk(bad, &m);
            for (const auto& p : t.patches)
                for (uint32_t cv : p.cv) ASSERT_LT(cv, t.totalVertices);
            buildTessellation(m, t, 4);
        } catch (const Error&) {
            ++rejected;
        }
    }
    EXPECT_GT(rejected, 1500u);
}

// The tessellation divides every ptex face by its domains: they must be cells of the face's
// quadtree at the tables' depth and tile it exactly once (found by fuzz_render_input: a domain
// finer than the depth once reached a division by zero).
TEST(TablesChunk, DomainsMustTileTheirPtexFaces) {
    Mesh m = load("quad/osd_catmark_xord_boundary.obj");
    const Tables good = build(m, 2);
    ASSERT_GE(good.patches.size(), 2u);
    auto expectRefused = [&](const Tables& t, const std::string& why, const std::string& what) {
        try {
            decodeTablesChunk(encodeTablesChunk(t), &m);
            ADD_FAILURE() << "accepted: " << what;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos)
                << what << ": " << e.what();
        }
    };
    Tables t = good;
    t.patches[0].size /= 8; // finer than depth 2
    expectRefused(t, "finer than the tables' depth", "a domain of 1/32");
    t = good;
    auto half = std::find_if(t.patches.begin(), t.patches.end(),
                             [](const Patch& p) { return p.size == 0.5f && p.u0 == 0; });
    ASSERT_NE(half, t.patches.end());
    half->u0 = 0.25f; // inside the face and on the depth-2 grid, but not a cell of size 1/2
    expectRefused(t, "not a cell", "a domain off the grid");
    t = good;
    t.patches[1] = t.patches[0]; // the same square twice, another one missing
    t.patches[1].cv[0] = good.patches[1].cv[0];
    expectRefused(t, "same square", "a duplicated domain");
    t = good;
    // A gap in a face's tiling (a face with no domain at all is a face without a limit surface).
    auto partial =
        std::find_if(t.patches.begin(), t.patches.end(), [](const Patch& p) { return p.size < 1; });
    ASSERT_NE(partial, t.patches.end());
    t.patches.erase(partial);
    expectRefused(t, "exactly once", "a missing domain");
}

TEST(TablesChunk, OutOfRangeIndexNamesTheTable) {
    Mesh m = load("quad/osd_catmark_pyramid.obj");
    Tables t = build(m, 1);
    ASSERT_FALSE(t.edgePoints.empty());
    ASSERT_FALSE(t.edgePoints[0].indices.empty());
    t.edgePoints[0].indices[0] = t.totalVertices + 5;
    try {
        decodeTablesChunk(encodeTablesChunk(t), &m);
        FAIL() << "accepted an out-of-range index";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("edge points"), std::string::npos) << e.what();
    }
}

// Version 4's source indices are zigzag differences: one of 2^63 - 1 (the ten-byte varint
// FE FF .. FF 01) after a previous index of 5 overflowed the int64 sum (UBSan: signed integer
// overflow) before the range check; refused as out of range, like every difference past 2^32.
TEST(TablesChunk, HugeIndexDifferenceIsRefused) {
    for (const std::vector<uint8_t>& varint : {std::vector<uint8_t>{0xFE, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x01},
                                               std::vector<uint8_t>{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x01},
                                               std::vector<uint8_t>{0x80, 0x80, 0x80, 0x80, 0x20}}) { // 2^33: +2^32
        std::vector<uint8_t> bytes = {uint8_t(varint.size()), 0, 0, 0};
        bytes.insert(bytes.end(), varint.begin(), varint.end());
        bytes.resize((bytes.size() + 3) / 4 * 4, 0);
        ByteReader r(bytes, "test");
        StreamReader in(r, "a table");
        EXPECT_THROW(in.after(5, "a source index"), Error);
    }
}

// A finite but huge weight (3e38) read back from a damaged file would make the GPU's float sums
// NaN; the reader refuses it, naming the table. Real tables, with extraordinary vertices,
// boundaries, corners and creases, stay well inside the bound.
// Version 4 stores each distinct basis row once and copies it per use (up to 768 times): a
// basis of a valence limn-tables never builds one for, or one valence twice, would let a small
// file decode to gigabytes. The reader refuses both, naming the basis.
TEST(TablesChunk, BasisOfTooHighOrRepeatedValenceIsRefused) {
    Mesh m = load("quad/osd_catmark_pyramid.obj");
    const Tables good = build(m, 3);
    ASSERT_FALSE(good.irregularBases.empty());
    EXPECT_NO_THROW(decodeTablesChunk(encodeTablesChunk(good), &m));
    for (uint32_t version : {4u, 5u})
        for (int which = 0; which < 2; ++which) {
            Tables t = good;
            if (which == 0) {
                IrregularBasis& b = t.irregularBases[0];
                b.valence = kMaxBasisValence + 1; // version 5 writes its program as it is
                b.weights.assign(size_t(b.levels) * 48 * b.supportSize(), 0.0f);
            } else {
                t.irregularBases.push_back(t.irregularBases[0]);
            }
            try {
                decodeTablesChunk(encodeTablesChunk(t, version), &m);
                ADD_FAILURE() << "accepted basis case " << which << " in version " << version;
            } catch (const Error& e) {
                const std::string want = which == 1 ? "repeats valence"
                                         : version == 4 ? "has valence " + std::to_string(kMaxBasisValence + 1)
                                                        : "bad valence";
                EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
            }
        }
}

// A version-5 basis is a program the reader runs K times over 2n + 8 columns: every count and
// index is checked first (rows within twice the support, entries within 16 a row, sources a
// support point or an earlier row, control and support points existing rows, weights in the
// palette and finite), and the expanded weights are bounded like every stencil weight.
TEST(TablesChunk, HostileBasisProgramIsRefused) {
    Mesh m = load("quad/osd_catmark_pyramid.obj");
    const Tables good = build(m, 3);
    ASSERT_FALSE(good.irregularBases.empty());
    const BasisProgram& g = good.irregularBases[0].program;
    const uint32_t M = good.irregularBases[0].supportSize();
    ASSERT_GT(g.rows(), 0u);
    struct Case {
        const char* why;
        std::function<void(BasisProgram&)> damage;
    };
    const std::vector<Case> cases = {
        {"reads neither a support point nor an earlier row", [&](BasisProgram& p) { p.source[p.start[3]] = M + 3; }},
        {"reads neither a support point nor an earlier row", [&](BasisProgram& p) { p.source.back() = 1u << 30; }},
        {"names a missing row", [&](BasisProgram& p) { p.controlRow[7] = p.rows(); }},
        {"names a missing row", [&](BasisProgram& p) { p.nextSupport[0] = p.rows(); }},
        {"bad row count", [&](BasisProgram& p) {
             while (p.rows() <= 2 * M) {
                 p.source.push_back(0);
                 p.weight.push_back(1.0f);
                 p.averaged.push_back(1);
                 p.start.push_back(uint32_t(p.source.size()));
             }
         }},
        {"has a bad length", [&](BasisProgram& p) {
             const uint32_t extra = 16 * p.rows(); // the last row takes more than all rows may
             p.source.insert(p.source.end(), extra, 0);
             p.weight.insert(p.weight.end(), extra, 0.5f);
             p.start.back() += extra;
         }},
        {"has a bad weight", [&](BasisProgram& p) { p.weight[p.start[p.rows() - 1]] = 3e38f; }},
        // Each band multiplies by 1e5: finite in the palette, past 1 once expanded (version 7
        // bounds an interior basis's weights by [0, 1]).
        {"has a weight outside [0, 1]", [&](BasisProgram& p) {
             for (uint32_t r = 0; r < p.rows(); ++r)
                 if (!p.averaged[r]) p.weight[p.start[r]] = 1e5f;
         }},
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        Tables t = good;
        cases[i].damage(t.irregularBases[0].program);
        try {
            decodeTablesChunk(encodeTablesChunk(t), &m);
            ADD_FAILURE() << "accepted program case " << i;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(cases[i].why), std::string::npos) << "case " << i << ": " << e.what();
        }
    }
}

// Smooth faces below level N (version 5): a basis code below a root in a version-4 chunk, a
// smooth face named twice, one too deep for its basis's bands, and support points at another
// level are each refused by name.
TEST(TablesChunk, SmoothFacesBelowRootsAreChecked) {
    Mesh m = load("osd/catmark/catmark_pyramid_creases0.obj");
    const Tables good = build(m, 2);
    uint32_t node = 0, quadrant = 4;
    for (uint32_t i = 0; i < good.irregularNodes.size() && quadrant == 4; ++i)
        for (uint32_t q = 0; q < 4 && quadrant == 4; ++q)
            if ((good.irregularNodes[i][q] & ~kNodeIndexMask) == kNodeBasis && good.irregularNodes[i][q] != kNodeNone &&
                !(i < good.irregular.size() && smoothRoot(good.irregularNodes[i])))
                node = i, quadrant = q;
    ASSERT_LT(quadrant, 4u) << "no smooth face below level N";
    const uint32_t code = good.irregularNodes[node][quadrant], smooth = code & kNodeIndexMask;
    // Version 5 holds them: its smooth points' runs carry the deeper levels' vertices, and the
    // tables read back as they were written.
    const Chunk v5 = encodeTablesChunk(good);
    const Tables back = decodeTablesChunk(v5, &m);
    EXPECT_EQ(back.irregularNodes, good.irregularNodes);
    EXPECT_EQ(back.smoothPoints, good.smoothPoints);
    ASSERT_EQ(back.smoothIrregular.size(), good.smoothIrregular.size());
    for (size_t i = 0; i < good.smoothIrregular.size(); ++i)
        EXPECT_EQ(back.smoothIrregular[i].first, good.smoothIrregular[i].first);
    EXPECT_EQ(encodeTablesChunk(back).payload, v5.payload);
    const LevelInfo& below = good.levels[good.depth + 1];
    EXPECT_TRUE(std::any_of(good.smoothPoints.begin(), good.smoothPoints.end(),
                            [&](uint32_t v) { return v >= below.first && v - below.first < below.count(); }));
    for (int which = 0; which < 4; ++which) {
        Tables t = good;
        Chunk c;
        if (which == 0) { // version 4's plain node records, one naming the smooth face below N
            for (uint32_t i = 0; i < t.irregularNodes.size(); ++i) // version 4 cannot hold them
                for (uint32_t& x : t.irregularNodes[i])
                    if ((x & ~kNodeIndexMask) == kNodeBasis && x != kNodeNone &&
                        !(i < t.irregular.size() && smoothRoot(good.irregularNodes[i])))
                        x = kNodeNone;
            c = encodeTablesChunk(t, 4);
            const auto* record = reinterpret_cast<const uint8_t*>(t.irregularNodes[node].data());
            const auto at = std::search(c.payload.begin(), c.payload.end(), record, record + 16);
            ASSERT_NE(at, c.payload.end());
            ASSERT_EQ(std::search(at + 1, c.payload.end(), record, record + 16), c.payload.end());
            std::memcpy(&*at + 4 * quadrant, &code, 4); // little-endian, as the chunk
        } else {
            if (which == 1) t.irregularNodes[node][quadrant ^ 1] = code;
            if (which == 2) { // a basis of one band: none left below level N
                IrregularBasis& b = t.irregularBases[t.smoothIrregular[smooth].basis];
                b.levels = 1;
                b.weights.resize(size_t(48) * b.supportSize());
            }
            if (which == 3) t.smoothPoints[t.smoothIrregular[smooth].first] = t.levels[t.depth].first;
            c = encodeTablesChunk(t);
        }
        const char* want[4] = {"basis code below a root", "is named twice", "too deep", "not at its face's level"};
        try {
            decodeTablesChunk(c, &m);
            ADD_FAILURE() << "accepted case " << which;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(want[which]), std::string::npos) << which << ": " << e.what();
        }
    }
}

// Version 5's smooth points come in runs, each at one level (N, or a smooth face's level below
// it): a run deeper than the smooth faces can be (level N + K), one of no points or of more than
// are left, and a point outside its run's level are refused by name.
TEST(TablesChunk, HostileSmoothPointRunsAreRefused) {
    Mesh m = load("osd/catmark/catmark_pyramid_creases0.obj");
    const Tables t = build(m, 2);
    const uint32_t K = t.irregularLevels;
    ASSERT_GT(K, 1u);
    std::vector<uint8_t> outside = {0, 2}; // a vertex point 100 past level N's last
    writeVarint(outside, 2 + 3 * zigzag(int64_t(t.levels[t.depth].vertexPoints) + 100));
    const std::vector<std::pair<std::vector<uint8_t>, const char*>> cases = {
        {{uint8_t(K), 1, 0}, "a run at level N + "},
        {{0, 0}, "a run of 0 points"},
        {{0, 3, 0, 0}, "a run of 3 points (2 left)"},
        {outside, "not at its run's level"},
    };
    for (const auto& [s, why] : cases) {
        ByteWriter w;
        writeStream(w, s);
        const std::vector<uint8_t> bytes = w.take();
        ByteReader r(bytes, "test");
        try {
            readSmoothPoints(r, 2, t);
            ADD_FAILURE() << "accepted " << why;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    }
}

TEST(TablesChunk, HugeWeightIsRefused) {
    Mesh m = load("quad/osd_catmark_pyramid.obj");
    for (int which = 0; which < 3; ++which) {
        Tables t = build(m, 2);
        StencilTable& table = which == 0 ? t.edgePoints[0] : which == 1 ? t.vertexPoints[1] : t.limitTangent1;
        ASSERT_FALSE(table.weights.empty());
        table.weights.back() = which == 2 ? -3e38f : 3e38f;
        try {
            decodeTablesChunk(encodeTablesChunk(t), &m);
            ADD_FAILURE() << "accepted weight 3e38 in table " << which;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("must be finite and within +-1e6"), std::string::npos) << e.what();
        }
    }
    for (const char* model : {"quad/osd_catmark_pyramid.obj", "osd/catmark/catmark_car.obj",
                              "osd/catmark/catmark_chaikin2.obj", "osd/catmark/catmark_pole360.obj",
                              "osd/catmark/catmark_edgecorner.obj", "osd/catmark/catmark_val2_interior.obj"}) {
        SCOPED_TRACE(model);
        Mesh mm = load(model);
        EXPECT_NO_THROW(decodeTablesChunk(encodeTablesChunk(build(mm, 3)), &mm));
    }
}

TEST(Tables, DepthZeroNeedsQuads) {
    EXPECT_NO_THROW(build(load("quad/osd_catmark_torus.obj"), 0));
    EXPECT_THROW(build(load("quad/spot_control_mesh.obj"), 0), Error);
}

TEST(Tables, RefusesNonManifoldMeshesNamingTheEdge) {
    try {
        build(load("osd/catmark/catmark_nonman_edge100.obj"), 2);
        FAIL() << "accepted a non-manifold mesh";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("non-manifold"), std::string::npos) << e.what();
    }
}

// Feature-adaptive isolation: past the level where the semi-sharp features decay, each extra level
// adds a bounded amount of work around the extraordinary vertices (paper 000, Figure 14).
TEST(Tables, AdaptiveTablesGrowLinearlyWithDepth) {
    Mesh m = load("quad/spot_control_mesh.obj");
    auto bytes = [&](int d) { return encodeTablesChunk(build(m, d)).payload.size(); };
    size_t b4 = bytes(4), b5 = bytes(5), b6 = bytes(6);
    EXPECT_LT(b6 - b5, 2 * (b5 - b4)); // linear, not 4x per level
    EXPECT_LT(b6, 3 * b4);
}

} // namespace
