// limn-render --mesh-out FILE.{ply,obj,gltf,glb} as users run it, on lavapipe. The PLY
// is read with drawn_ply.h (from its documented layout), the OBJ and the glTF with exported_mesh.h
// (a parser, and tinygltf's reader; both in tests/support); the three must carry the same floats bit for bit. Expected UVs come from the
// OBJ text of the model, and the glTF is checked by the Khronos glTF-Validator.
#include "mesh_export_checks.h"

using namespace limn::test;
using namespace limn::mesh_export_test;

namespace {

TEST(MeshExport, SpotRoundTripsInEveryFormatWithItsTextureUVs) {
    ScratchDir dir;
    const std::string model = modelPath("quad/spot_control_mesh.obj").string();
    auto limn = prepare(dir, model, 2, "spot");
    Exported e = exportAll(dir, limn, "spot");
    ASSERT_TRUE(e.ply.hasST);
    // Nothing approximate: no flag in any format.
    EXPECT_FALSE(e.ply.hasApproximate);
    EXPECT_TRUE(e.glb.approximate.empty());
    EXPECT_TRUE(e.gltf.approximate.empty());
    EXPECT_EQ(e.obj.approximateCount, 0u);
    EXPECT_TRUE(e.obj.approximateV.empty());
    ASSERT_GT(e.ply.triangles.size(), 1000u);
    expectAllEqual(e);

    // Closed: welded by position, every edge in exactly two triangles (also the glTF's).
    auto w = weldedEdges(e.ply);
    EXPECT_EQ(w.open, 0u);
    EXPECT_EQ(w.over, 0u);
    auto wg = weldedEdges(drawnFromGltf(e.glb));
    EXPECT_EQ(wg.open, 0u);
    EXPECT_EQ(wg.over, 0u);
    // Split at UV seams: more vertices than distinct positions.
    EXPECT_GT(e.ply.vertices.size(), e.obj.v.size());

    // Texture UVs within the range of the mesh's own UVs (spot's reach -0.052 and 1.00065, so not
    // [0, 1]: linear interpolation in each face chart stays inside it); at control-mesh corners (Ptex (u, v) at a corner of a quad's domain)
    // the UVs drawn at that point are the OBJ's face-varying UVs of the control vertex.
    ObjUVs obj = readObjUVs(readFile(model));
    // OpenSubdiv's Ptex numbering: a quad has one Ptex face, an n-gon n (sub-face k has the
    // face's corner k at its (0, 0); its other corners are edge midpoints and the centroid).
    std::vector<std::pair<size_t, int>> ptexFace; // (face, sub-face or -1 for a quad)
    for (size_t f = 0; f < obj.faces.size(); ++f) {
        if (obj.faces[f].size() == 4)
            ptexFace.push_back({f, -1});
        else
            for (size_t k = 0; k < obj.faces[f].size(); ++k) ptexFace.push_back({f, int(k)});
    }
    std::array<float, 2> lo = obj.vt.at(0), hi = lo;
    for (const auto& uv : obj.vt)
        for (size_t k = 0; k < 2; ++k) lo[k] = std::min(lo[k], uv[k]), hi[k] = std::max(hi[k], uv[k]);
    EXPECT_LT(lo[0], 0.0f); // the reason the range is not [0, 1]
    size_t outside = 0;
    std::map<std::array<uint32_t, 3>, int> cornerVertex; // drawn position -> control vertex
    for (const auto& v : e.ply.vertices) {
        for (size_t k = 0; k < 2; ++k) outside += !(v.st[k] >= lo[k] && v.st[k] <= hi[k]);
        const bool u0 = v.uv[0] == 0.0f, u1 = v.uv[0] == 1.0f, v0 = v.uv[1] == 0.0f,
                   v1 = v.uv[1] == 1.0f;
        if (!((u0 || u1) && (v0 || v1))) continue;
        // A quad's Ptex domain has its corners 0..3 at (0,0) (1,0) (1,1) (0,1).
        const auto [f, sub] = ptexFace.at(size_t(v.ptex));
        if (sub >= 0 && !(u0 && v0)) continue;
        const size_t corner = sub >= 0 ? size_t(sub) : u0 ? (v0 ? 0 : 3) : (v0 ? 1 : 2);
        cornerVertex[{std::bit_cast<uint32_t>(v.p[0]), std::bit_cast<uint32_t>(v.p[1]),
                      std::bit_cast<uint32_t>(v.p[2])}] = obj.faces[f].at(corner).first;
    }
    EXPECT_EQ(outside, 0u);
    EXPECT_EQ(cornerVertex.size(), obj.vertices);
    std::map<int, std::set<std::array<float, 2>>> drawnUVs, expectedUVs;
    for (const auto& v : e.ply.vertices) {
        auto it = cornerVertex.find({std::bit_cast<uint32_t>(v.p[0]), std::bit_cast<uint32_t>(v.p[1]),
                                     std::bit_cast<uint32_t>(v.p[2])});
        if (it != cornerVertex.end()) drawnUVs[it->second].insert({v.st[0], v.st[1]});
    }
    for (const auto& f : obj.faces)
        for (auto [vertex, vt] : f) expectedUVs[vertex].insert(obj.vt.at(size_t(vt)));
    size_t seamVertices = 0, wrong = 0;
    for (const auto& [vertex, uvs] : drawnUVs) {
        seamVertices += uvs.size() > 1;
        wrong += uvs != expectedUVs[vertex];
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(seamVertices, 10u); // spot's UV seams were split

    expectValid({e.glbPath, e.gltfPath});

    // ASCII PLY carries the same s, t.
    const std::string ascii = (dir / "spot_ascii.ply").string();
    auto r = renderMesh(limn, ascii, {"--mesh-ascii"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string text = readFile(ascii);
    EXPECT_NE(text.find("property float v\nproperty float s\nproperty float t\n"), std::string::npos);
    std::istringstream values(text.substr(text.find("end_header\n") + 11));
    size_t differ = 0;
    for (const auto& v : e.ply.vertices) {
        std::string f[11];
        for (auto& x : f) values >> x;
        differ += !same(parseFloat(f[9]), v.st[0]) || !same(parseFloat(f[10]), v.st[1]);
    }
    EXPECT_EQ(differ, 0u);
}

// Edges used by one face only, from the input's own faces (vertex ids).
size_t boundaryEdges(const std::vector<std::vector<int>>& faces) {
    std::map<std::pair<int, int>, int> uses;
    for (const auto& f : faces)
        for (size_t i = 0; i < f.size(); ++i) {
            int a = f[i], b = f[(i + 1) % f.size()];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    size_t n = 0;
    for (const auto& [e, u] : uses) n += u == 1;
    return n;
}

TEST(MeshExport, CarAndAvocadoRoundTripAndValidate) {
    ScratchDir dir;
    std::vector<std::string> files;
    for (auto [model, name] : {std::pair{"osd/catmark/catmark_car.obj", "car"},
                               std::pair{"gltf/Avocado/Avocado.gltf", "avocado"}}) {
        SCOPED_TRACE(name);
        const std::string path = modelPath(model).string();
        auto limn = prepare(dir, path, 1, name);
        // The fixed grids (--edge-pixels 0): their open edges are exactly two per boundary edge
        // of the input at depth 1, and shared points are shared vertices.
        Exported e = exportAll(dir, limn, name, {"--edge-pixels", "0"});
        ASSERT_FALSE(e.ply.triangles.empty());
        expectAllEqual(e);
        // Both are open: welded by position, the drawn surface's open edges are the input's
        // boundary edges, each drawn as 2^depth segments (the tessellation's grid along a base
        // edge), in every format; nothing else is open (no crack) and no edge is overused.
        const size_t boundary = boundaryEdges(std::string(name) == "car" ? objFaces(path) : gltfFaces(path));
        EXPECT_GT(boundary, 0u);
        auto w = weldedEdges(e.ply), wg = weldedEdges(drawnFromGltf(e.glb));
        EXPECT_EQ(w.open, 2 * boundary);
        EXPECT_EQ(wg.open, 2 * boundary);
        EXPECT_EQ(w.over, 0u);
        EXPECT_EQ(wg.over, 0u);
        files.push_back(e.glbPath);
        files.push_back(e.gltfPath);
    }
    expectValid(files);
}

TEST(MeshExport, ControlMeshAndBlendingSurface) {
    ScratchDir dir;
    const std::string model = modelPath("quad/spot_control_mesh.obj").string();
    // The control mesh: one vertex per face corner, its texture UV the corner's UV.
    auto limn = prepare(dir, model, 1, "spot");
    Exported c = exportAll(dir, limn, "control", {"--surface", "control"});
    ASSERT_TRUE(c.ply.hasST);
    expectAllEqual(c);
    ObjUVs obj = readObjUVs(readFile(model));
    size_t corners = 0;
    for (const auto& f : obj.faces) corners += f.size();
    ASSERT_EQ(c.ply.vertices.size(), corners);
    for (size_t f = 0, i = 0; f < obj.faces.size(); ++f)
        for (size_t k = 0; k < obj.faces[f].size(); ++k, ++i) {
            const auto& uv = obj.vt.at(size_t(obj.faces[f][k].second));
            EXPECT_EQ(c.ply.vertices[i].st[0], uv[0]);
            EXPECT_EQ(c.ply.vertices[i].st[1], uv[1]);
        }

    // The blending surface shares its vertices across faces: no texture UVs, still valid.
    auto cl = run({bin("limn-classify"), model});
    ASSERT_EQ(cl.exitCode, 0) << cl.err;
    auto bl = run({bin("limn-blend"), "--quadrangulate", "-o", (dir / "blend.limn").string()}, cl.out);
    ASSERT_EQ(bl.exitCode, 0) << bl.err;
    Exported b = exportAll(dir, (dir / "blend.limn").string(), "blend", {"--grid", "2"});
    EXPECT_FALSE(b.ply.hasST);
    EXPECT_TRUE(b.glb.uvs.empty());
    EXPECT_TRUE(b.obj.vt.empty());
    expectAllEqual(b);
    expectValid({b.glbPath, c.glbPath});
}

TEST(MeshExport, WithoutUVsThereAreNoTextureCoordinates) {
    ScratchDir dir;
    auto limn = prepare(dir, modelPath("osd/catmark/catmark_pole8.obj").string(), 2, "pole");
    // The fixed grids (--edge-pixels 0), where each surface point is one vertex; view-adaptive
    // tessellation writes each element's copy of its side points (same bits, welded by position).
    Exported e = exportAll(dir, limn, "pole", {"--edge-pixels", "0"});
    ASSERT_FALSE(e.ply.triangles.empty());
    EXPECT_FALSE(e.ply.hasST);
    EXPECT_TRUE(e.glb.uvs.empty());
    EXPECT_TRUE(e.gltf.uvs.empty());
    EXPECT_TRUE(e.obj.vt.empty());
    expectAllEqual(e);
    // No split without UVs: one vertex per position.
    EXPECT_EQ(e.ply.vertices.size(), e.obj.v.size());
    expectValid({e.glbPath, e.gltfPath});
}

} // namespace
