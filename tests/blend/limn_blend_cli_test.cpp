// limn-blend as users run it: conventions of docs/contributing.md (help, exit codes, atomic
// output, determinism, pass-through of unknown chunks, depfile) and its refusals.
#include "blend/blend_chunk.h"
#include "container/container.h"
#include "mesh/mesh_chunks.h"
#include "test_meshes.h"
#include "test_support.h"
#include "topology/classification.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace limn;
namespace fs = std::filesystem;

namespace {

std::string blendTool() { return test::tool("limn-blend").string(); }

// limn-classify output for a shared model, as bytes.
std::string classified(const std::string& model) {
    auto r = test::run({test::tool("limn-classify").string(), test::modelPath(model).string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return r.out;
}

std::string classifiedObj(const std::string& objText) {
    auto r = test::run({test::tool("limn-classify").string(), "-q", "-"}, objText);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return r.out;
}

Container parse(const std::string& bytes) {
    return parseContainer({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()});
}

} // namespace

TEST(BlendCli, HelpAndVersion) {
    auto r = test::run({blendTool(), "--help"});
    EXPECT_EQ(r.exitCode, 0);
    for (const char* s : {"Usage: limn-blend", "--weights", "cubic|quintic", "--quadrangulate", "--chart",
                          "--depfile", "-o, --output", "Exit codes", "[default: cubic]"})
        EXPECT_NE(r.out.find(s), std::string::npos) << s;
    r = test::run({blendTool(), "--version"});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(r.out.rfind("limn-blend ", 0), 0u);
}

TEST(BlendCli, UsageErrorsExit2) {
    for (std::vector<std::string> args : {std::vector<std::string>{"--weights", "septic"},
                                          {"--bogus"}, {"a", "b"}, {"--chart"}}) {
        args.insert(args.begin(), blendTool());
        auto r = test::run(args);
        EXPECT_EQ(r.exitCode, 2) << args[1];
        EXPECT_NE(r.err.find("limn-blend: error:"), std::string::npos) << r.err;
    }
}

TEST(BlendCli, BadInputExits1) {
    // A mesh is classified with the defaults first; a triangle is no quad mesh.
    auto r = test::run({blendTool(), "-"}, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("limn-blend: error: <stdin>: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--quadrangulate"), std::string::npos) << r.err;
    r = test::run({blendTool(), "-"}, "not a mesh at all");
    EXPECT_EQ(r.exitCode, 1);
    r = test::run({blendTool(), "/nonexistent/x.limn"});
    EXPECT_EQ(r.exitCode, 1);
    // A truncated container.
    std::string spot = classified("quad/osd_catmark_cube.obj");
    r = test::run({blendTool()}, spot.substr(0, spot.size() - 8));
    EXPECT_EQ(r.exitCode, 1);
}

TEST(BlendCli, RefusesNonQuadsNamingTheFace) {
    auto r = test::run({blendTool()}, classified("quad/spot_control_mesh.obj"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("face "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--quadrangulate"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST(BlendCli, RefusesNonManifoldNamingTheEdgeOrVertex) {
    // Three quads on the edge (1,2) (OBJ is 1-based).
    auto r = test::run({blendTool()}, classifiedObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 -1 0\nv 0 -1 0\n"
                                                    "v 1 0 1\nv 0 0 1\nf 1 2 3 4\nf 2 1 6 5\nf 1 2 7 8\n"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("edge (0,1) is non-manifold"), std::string::npos) << r.err;
    r = test::run({blendTool()}, classifiedObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0 0\nv -1 -1 0\n"
                                               "v 0 -1 0\nf 1 2 3 4\nf 1 5 6 7\n"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("vertex 0 is non-manifold"), std::string::npos) << r.err;
}

TEST(BlendCli, QuadrangulatesSpotAndRewritesTheMeshChunks) {
    auto r = test::run({blendTool(), "--quadrangulate", "--weights", "quintic"},
                       classified("quad/spot_control_mesh.obj"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Container c = parse(r.out);
    Mesh mesh = loadMesh(c);
    EXPECT_EQ(mesh.faceCount(), 732u); // 4·4 + 160·4 + 16·5 corners of spot
    EXPECT_TRUE(mesh.hasUVs());
    Classification clsf = decodeClassificationChunk(*c.find(kClassificationChunk), mesh);
    EXPECT_EQ(clsf.faceFlags.size(), 732u);
    blend::BlendSurface s = blend::loadBlendSurface(c, mesh);
    EXPECT_EQ(s.weights, blend::WeightKind::Quintic);
    std::vector<std::string> order;
    for (const auto& ch : c.chunks) order.push_back(ch.type.str());
    EXPECT_EQ(order, (std::vector<std::string>{"MESH", "FVUV", "TAGS", "CLSF", "BLND"}));
}

TEST(BlendCli, QuadMeshIsLeftAsItIs) {
    std::string in = classified("quad/osd_catmark_torus.obj");
    auto r = test::run({blendTool(), "--quadrangulate"}, in);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Container before = parse(in), after = parse(r.out);
    ASSERT_EQ(after.chunks.size(), before.chunks.size() + 1);
    for (size_t i = 0; i < before.chunks.size(); ++i)
        EXPECT_EQ(after.chunks[i].payload, before.chunks[i].payload) << before.chunks[i].type.str();
}

TEST(BlendCli, PassesUnknownChunksThroughUnchanged) {
    Container c = parse(classified("quad/osd_catmark_cube.obj"));
    Chunk extra{FourCC("ZZ_9"), 7, {1, 2, 3, 4, 5}};
    c.chunks.insert(c.chunks.begin() + 1, extra);
    auto bytes = serializeContainer(c);
    auto r = test::run({blendTool()}, std::string(bytes.begin(), bytes.end()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Container out = parse(r.out);
    ASSERT_GE(out.chunks.size(), 2u);
    EXPECT_EQ(out.chunks[1].type, extra.type);
    EXPECT_EQ(out.chunks[1].version, 7u);
    EXPECT_EQ(out.chunks[1].payload, extra.payload);
    EXPECT_TRUE(out.has(blend::kBlendChunk));
    // Running limn-blend again replaces BLND instead of adding a second one.
    auto again = test::run({blendTool(), "--weights", "quintic"}, r.out);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(parse(again.out).chunks.size(), out.chunks.size());
}

TEST(BlendCli, DeterministicAtomicAndDepfile) {
    test::ScratchDir dir;
    test::writeFile(dir / "in.limn", classified("quad/blub_control_mesh.obj"));
    std::string in = (dir / "in.limn").string(), a = (dir / "a.limn").string(),
                b = (dir / "b.limn").string(), d = (dir / "a.d").string();
    auto r1 = test::run({blendTool(), "--quadrangulate", "-o", a, "--depfile", d, in});
    auto r2 = test::run({blendTool(), "--quadrangulate", "-o", b, in});
    ASSERT_EQ(r1.exitCode, 0) << r1.err;
    ASSERT_EQ(r2.exitCode, 0) << r2.err;
    EXPECT_EQ(test::readFile(a), test::readFile(b));
    EXPECT_EQ(test::readFile(d), a + ": " + in + "\n");
    // A failed run leaves an existing output untouched and no temporary file behind.
    test::writeFile(dir / "keep.limn", "old");
    auto bad = test::run({blendTool(), "-o", (dir / "keep.limn").string(), in}); // blub has triangles
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_EQ(test::readFile(dir / "keep.limn"), "old");
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir.path())) files += e.is_regular_file();
    EXPECT_EQ(files, 5u); // in, a, b, a.d, keep
}
