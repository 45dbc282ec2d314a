// limn-render --mesh-out's options and edge cases: the format from the extension, non-finite
// values, the approximate flags in every format, the same bytes twice, an unknown extension, and
// the image beside the mesh (the round trips: mesh_export_cli_test.cpp).
#include "mesh_export_checks.h"

using namespace limn::test;
using namespace limn::mesh_export_test;

namespace {

TEST(MeshExport, FormatsByExtensionAndEdgeCases) {
    using limn::exporting::ExportFormat;
    using limn::exporting::exportFormatFromPath;
    EXPECT_EQ(exportFormatFromPath("a.ply"), ExportFormat::Ply);
    EXPECT_EQ(exportFormatFromPath("-"), ExportFormat::Ply);
    EXPECT_EQ(exportFormatFromPath("dir/A.OBJ"), ExportFormat::Obj);
    EXPECT_EQ(exportFormatFromPath("x.y.gltf"), ExportFormat::Gltf);
    EXPECT_EQ(exportFormatFromPath("x.Glb"), ExportFormat::Glb);
    for (const char* bad : {"x", "x.stl", "dir.glb/x", "x.glb.tmp", ".", "x."})
        EXPECT_FALSE(exportFormatFromPath(bad).has_value()) << bad;

    // Nothing drawn: a glTF asset without scenes (accessors cannot be empty).
    limn::exporting::DrawnMesh empty;
    auto glb = limn::exporting::encodeGltf(empty, true);
    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn, glb.data(), unsigned(glb.size()))) << err;
    EXPECT_TRUE(m.meshes.empty());
    EXPECT_TRUE(m.scenes.empty());
    EXPECT_EQ(m.asset.version, "2.0");
    ScratchDir dir;
    const std::string emptyGlb = (dir / "empty.glb").string();
    writeFile(emptyGlb, std::string(glb.begin(), glb.end()));
    expectValid({emptyGlb});
    // A triangle naming a vertex that is not there is refused, not written.
    limn::exporting::DrawnMesh bad;
    bad.vertices.resize(2);
    bad.triangles = {0, 1, 2};
    EXPECT_THROW(limn::exporting::encodeObj(bad), std::exception);
    EXPECT_THROW(limn::exporting::encodeGltf(bad, false), std::exception);
    // A vertex the GPU's float overflowed (NaN or Inf) is refused in every format: a glTF's
    // POSITION min/max would be null, a PLY or OBJ would carry "nan".
    limn::exporting::DrawnMesh overflowed;
    overflowed.vertices.resize(3);
    overflowed.vertices[1].y = std::numeric_limits<float>::quiet_NaN();
    overflowed.vertices[2].x = 1;
    overflowed.triangles = {0, 1, 2};
    for (auto format : {ExportFormat::Ply, ExportFormat::Obj, ExportFormat::Gltf, ExportFormat::Glb})
        for (bool ascii : {false, true}) {
            try {
                limn::exporting::encodeMesh(overflowed, format, ascii);
                ADD_FAILURE() << "a NaN vertex was encoded, format " << int(format);
            } catch (const limn::Error& e) {
                EXPECT_NE(std::string(e.what()).find("drawn vertex 1 is not finite"), std::string::npos) << e.what();
            }
        }
    overflowed.vertices[1].y = 0;
    overflowed.vertices[2].nz = -std::numeric_limits<float>::infinity();
    EXPECT_THROW(limn::exporting::encodeMesh(overflowed, ExportFormat::Glb, false), limn::Error);
    overflowed.vertices[2].nz = 1;
    EXPECT_NO_THROW(limn::exporting::encodeMesh(overflowed, ExportFormat::Glb, false));
}

// PLY's `approximate` in the other formats: glTF's _APPROXIMATE attribute, per vertex; OBJ's
// comments, per `v` (OBJ has no per-vertex attribute). Tables of --irregular-levels 2 leave the
// surface bilinear within 2^-2 of extraordinary corners, where these segments of a quarter pixel
// land vertices (the default tables none, and then neither the attribute nor the comments:
// SpotRoundTripsInEveryFormatWithItsTextureUVs).
TEST(MeshExport, ApproximateVerticesAreFlaggedInEveryFormat) {
    ScratchDir dir;
    const std::string model = modelPath("osd/catmark/catmark_smoothtris0.obj").string();
    const std::string limn = (dir / "k2.limn").string();
    auto c = run({bin("limn-classify"), model});
    ASSERT_EQ(c.exitCode, 0) << c.err;
    auto t = run({bin("limn-tables"), "--depth", "2", "--irregular-levels", "2", "-o", limn}, c.out);
    ASSERT_EQ(t.exitCode, 0) << t.err;
    Exported e = exportAll(dir, limn, "k2", {"--edge-pixels", "0.25"});
    ASSERT_TRUE(e.ply.hasApproximate);
    expectAllEqual(e);
    using Position = std::array<uint32_t, 3>;
    auto key = [](const float* p) {
        return Position{std::bit_cast<uint32_t>(p[0]), std::bit_cast<uint32_t>(p[1]), std::bit_cast<uint32_t>(p[2])};
    };
    std::set<Position> flagged;
    for (const auto& v : e.ply.vertices)
        if (v.approximate) flagged.insert(key(v.p));
    EXPECT_GT(flagged.size(), 20u);
    for (const GltfMesh* g : {&e.glb, &e.gltf}) {
        ASSERT_EQ(g->approximate.size(), e.ply.vertices.size());
        size_t differ = 0;
        for (size_t i = 0; i < g->approximate.size(); ++i)
            differ += g->approximate[i] != (e.ply.vertices[i].approximate ? 1.0f : 0.0f);
        EXPECT_EQ(differ, 0u);
    }
    std::set<Position> listed;
    for (int v : e.obj.approximateV) {
        ASSERT_GE(v, 0);
        ASSERT_LT(size_t(v), e.obj.v.size());
        listed.insert(key(e.obj.v[size_t(v)].data()));
    }
    EXPECT_EQ(e.obj.approximateV.size(), e.obj.approximateCount);
    EXPECT_EQ(listed, flagged);
    expectValid({e.glbPath, e.gltfPath});
}

TEST(MeshExport, SameBytesTwice) {
    ScratchDir dir;
    auto limn = prepare(dir, modelPath("quad/spot_control_mesh.obj").string(), 1, "spot");
    for (const char* ext : {".glb", ".gltf", ".obj", ".ply"}) {
        std::string a = (dir / (std::string("a") + ext)).string(),
                    b = (dir / (std::string("b") + ext)).string();
        ASSERT_EQ(renderMesh(limn, a).exitCode, 0);
        ASSERT_EQ(renderMesh(limn, b).exitCode, 0);
        EXPECT_TRUE(readBytes(a) == readBytes(b)) << ext;
    }
}

TEST(MeshExport, UnknownExtensionIsAUsageErrorAndWritesNothing) {
    ScratchDir dir;
    auto limn = prepare(dir, modelPath("quad/spot_control_mesh.obj").string(), 1, "spot");
    for (const char* name : {"x.stl", "x", "x.glb.tmp", "x.fbx"}) {
        std::string out = (dir / name).string(), png = (dir / "x.png").string();
        auto r = run({bin("limn-render"), limn, "--mesh-out", out, "-o", png});
        EXPECT_EQ(r.exitCode, 2) << name << ": " << r.err;
        EXPECT_NE(r.err.find("limn-render: error: " + out + ": "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(".ply, .obj, .gltf, .glb"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << name;
        EXPECT_FALSE(std::filesystem::exists(png)) << name;
        EXPECT_EQ(r.out, "");
    }
    // --mesh-ascii is PLY's.
    auto r = run({bin("limn-render"), limn, "--mesh-out", (dir / "x.glb").string(), "--mesh-ascii"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.glb"));
    // Nothing in the directory but the container.
    size_t entries = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) entries += !entry.path().empty();
    EXPECT_EQ(entries, 1u);
}

TEST(MeshExport, ImageOnlyWithOutputAndDepfileNamesTheMesh) {
    ScratchDir dir;
    auto limn = prepare(dir, modelPath("quad/spot_control_mesh.obj").string(), 1, "spot");
    const std::string glb = (dir / "s.glb").string(), dep = (dir / "s.d").string();
    auto r = run({bin("limn-render"), limn, "--size", "16x16", "--mesh-out", glb, "--depfile", dep});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out, ""); // no PNG on standard output
    EXPECT_EQ(readFile(dep), glb + ": " + limn + "\n");
    // With -o - the image still goes to standard output.
    r = run({bin("limn-render"), limn, "--size", "16x16", "--mesh-out", glb, "-o", "-"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    // --mesh-out - is PLY on standard output, and then there is no image.
    r = run({bin("limn-render"), limn, "--size", "16x16", "--mesh-out", "-"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind("ply\n", 0), 0u);
    EXPECT_NO_THROW(parsePly(r.out));
}

} // namespace
