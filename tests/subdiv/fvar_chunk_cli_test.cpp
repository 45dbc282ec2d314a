// The FVSF chunk through the tools: limn-tables writes it for smooth UVs only, limn-classify
// with another rule drops it with the tables, limn-info calls one made for other UVs stale.
#include "base/error.h"
#include "container/container.h"
#include "mesh/import.h"
#include "subdiv/fvar_chunk.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <functional>

using namespace limn;

namespace {

Container parse(const std::string& bytes) {
    return parseContainer({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()});
}

// limn-tables writes it for smooth UVs only; limn-classify with another rule drops it with the
// tables; limn-info checks it and calls one made for another mesh stale.
TEST(FvarSurfaceChunk, ToolsWriteDropAndCheckIt) {
    const std::string obj = test::modelPath("quad/osd_catmark_fvar_bound1.obj").string();
    std::string smooth;
    for (const char* rule : {"boundaries", "all"}) {
        auto classified = test::run({test::tool("limn-classify").string(), "--fvar", rule, obj});
        ASSERT_EQ(classified.exitCode, 0) << classified.err;
        auto tables = test::run({test::tool("limn-tables").string(), "--depth", "1"}, classified.out);
        ASSERT_EQ(tables.exitCode, 0) << tables.err;
        EXPECT_EQ(parse(tables.out).find(kFvarSurfaceChunk) != nullptr, std::string(rule) != "all") << rule;
        if (std::string(rule) != "all") smooth = tables.out;
    }
    auto again = test::run({test::tool("limn-classify").string(), "--fvar", "corners-only", "-"}, smooth);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_FALSE(parse(again.out).has(kFvarSurfaceChunk));
    EXPECT_FALSE(parse(again.out).has(FourCC{"TBLS"}));
    auto info = test::run({test::tool("limn-info").string(), "-"}, smooth);
    EXPECT_EQ(info.exitCode, 0) << info.err;
    EXPECT_EQ(info.err.find("stale"), std::string::npos) << info.err;
    // Its UVs moved after limn-tables: the chunk's UV hash no longer matches.
    Container k = parse(smooth);
    Warnings w;
    Mesh m = importMeshFile(obj, w);
    m.tags.fvar = FVarRule::Boundaries;
    m.uvs[0].x += 0.5;
    const SchemeOptions o = resolveSchemeOptions(m.tags, {});
    k.set(encodeFvarSurfaceChunk(makeFvarSurfaceChunk(m, o, 1, /*irregular levels K, the default*/ 6, w)));
    const std::vector<uint8_t> bytes = serializeContainer(k);
    auto stale = test::run({test::tool("limn-info").string(), "-"}, std::string(bytes.begin(), bytes.end()));
    EXPECT_EQ(stale.exitCode, 0) << stale.err;
    EXPECT_NE(stale.err.find("the FVSF chunk was made from other tables, tags or UVs (stale)"), std::string::npos) << stale.err;
}

// A hole (0xFFFFFFFF) in place of a face's quadtree that the tables draw: structurally valid,
// but a walk from a drawn point ends in it (limn-web-render's seam fix threw a bare Error from
// there). limn-info refuses it naming the chunk, as limn-web-render does.
TEST(FvarSurfaceChunk, LimnInfoRefusesAHoleWhereTheTablesDraw) {
    const std::string obj = test::modelPath("quad/osd_catmark_fvar_bound1.obj").string();
    auto classified = test::run({test::tool("limn-classify").string(), "--fvar", "boundaries", obj});
    ASSERT_EQ(classified.exitCode, 0) << classified.err;
    auto tables = test::run({test::tool("limn-tables").string(), "--depth", "1"}, classified.out);
    ASSERT_EQ(tables.exitCode, 0) << tables.err;
    Container k = parse(tables.out);
    FvarSurfaceChunk f = decodeFvarSurfaceChunk(*k.find(kFvarSurfaceChunk), nullptr, nullptr);
    // A node naming a stored element (a patch) of ptex face `root`, the first root whose
    // subtree has one; with smooth faces (version 3: along the UV boundary too) a hole in place
    // of a whole root would be refused first for the smooth faces it leaves unnamed.
    std::function<uint32_t(uint32_t)> storedLeaf = [&](uint32_t n) -> uint32_t {
        const uint32_t v = f.surface.nodes[n];
        if (v == 0xFFFFFFFFu) return kNone;
        if (v & 0x80000000u) return (v & 0x7FFFFFFFu) < f.elementCount ? n : kNone;
        for (uint32_t q = 0; q < 4; ++q)
            if (const uint32_t x = storedLeaf(v + q); x != kNone) return x;
        return kNone;
    };
    uint32_t root = 0;
    while (root + 1 < f.ptexCount && storedLeaf(root) == kNone) ++root;
    ASSERT_NE(storedLeaf(root), kNone);
    for (uint32_t node : {storedLeaf(root)}) {
        SCOPED_TRACE(node);
        FvarSurfaceChunk holed = f;
        ASSERT_LT(node, holed.surface.nodes.size());
        holed.surface.nodes[node] = 0xFFFFFFFFu;
        k.set(encodeFvarSurfaceChunk(holed));
        const std::vector<uint8_t> bytes = serializeContainer(k);
        auto info = test::run({test::tool("limn-info").string(), "-"}, std::string(bytes.begin(), bytes.end()));
        EXPECT_EQ(info.exitCode, 1) << info.err;
        EXPECT_NE(info.err.find("chunk FVSF: no UV element where the tables draw ptex face " + std::to_string(root)),
                  std::string::npos)
            << info.err;
    }
}

} // namespace
