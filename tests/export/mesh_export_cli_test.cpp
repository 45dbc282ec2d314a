// limn-render --mesh-out FILE.{ply,obj,gltf,glb} as users run it, on lavapipe. The PLY
// is read with drawn_ply.h (from its documented layout), the OBJ and the glTF with exported_mesh.h
// (a parser, and tinygltf's reader; both in tests/support); the three must carry the same floats bit for bit. Expected UVs come from the
// OBJ text of the model, and the glTF is checked by the Khronos glTF-Validator.
#include "base/error.h"
#include "drawn_ply.h"
#include "exported_mesh.h"
#include "export/mesh_export.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <cstdlib>

#include <bit>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <set>

using namespace limn::test;

namespace {

std::string bin(const std::string& name) {
    return tool(name).string();
}

// classify | tables --depth N into dir/name.limn.
std::string prepare(const ScratchDir& dir, const std::string& model, int depth,
                    const std::string& name) {
    std::string out = (dir / (name + ".limn")).string();
    auto c = run({bin("limn-classify"), model});
    EXPECT_EQ(c.exitCode, 0) << c.err;
    auto t = run({bin("limn-tables"), "--depth", std::to_string(depth), "-o", out}, c.out);
    EXPECT_EQ(t.exitCode, 0) << t.err;
    return out;
}

RunResult renderMesh(const std::string& limn, const std::string& out,
                     std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {bin("limn-render"), limn, "--size", "16x16", "--mesh-out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
}

bool same(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

// ---- the checks ----

// The glTF carries the PLY's vertices and triangles bit for bit (texture v flipped).
void expectGltfEqualsPly(const GltfMesh& g, const Drawn& ply) {
    ASSERT_EQ(g.positions.size(), ply.vertices.size());
    ASSERT_EQ(g.normals.size(), ply.vertices.size());
    ASSERT_EQ(g.uvs.size(), ply.hasST ? ply.vertices.size() : 0u);
    std::array<float, 3> lo = g.positions.at(0), hi = lo;
    size_t mismatches = 0;
    for (size_t i = 0; i < ply.vertices.size(); ++i) {
        const auto& v = ply.vertices[i];
        for (int k = 0; k < 3; ++k) {
            mismatches += !same(g.positions[i][size_t(k)], v.p[k]);
            mismatches += !same(g.normals[i][size_t(k)], v.n[k]);
            lo[size_t(k)] = std::min(lo[size_t(k)], g.positions[i][size_t(k)]);
            hi[size_t(k)] = std::max(hi[size_t(k)], g.positions[i][size_t(k)]);
        }
        if (ply.hasST) {
            mismatches += !same(g.uvs[i][0], v.st[0]);
            mismatches += !same(g.uvs[i][1], 1.0f - v.st[1]); // glTF's top-left origin
        }
        const auto& n = g.normals[i];
        EXPECT_NEAR(std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]), 1.0, 1e-5)
            << "normal " << i;
    }
    EXPECT_EQ(mismatches, 0u);
    ASSERT_EQ(g.min.size(), 3u);
    ASSERT_EQ(g.max.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(g.min[k], double(lo[k]));
        EXPECT_EQ(g.max[k], double(hi[k]));
    }
    ASSERT_EQ(g.indices.size(), ply.triangles.size() * 3);
    for (size_t t = 0; t < ply.triangles.size(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            ASSERT_LT(g.indices[3 * t + k], g.positions.size());
            ASSERT_EQ(int64_t(g.indices[3 * t + k]), ply.triangles[t][k]);
        }
}

// Every OBJ triangle corner carries the PLY vertex of the same corner.
void expectObjEqualsPly(const ObjMesh& o, const Drawn& ply) {
    ASSERT_EQ(o.triangles.size(), ply.triangles.size());
    EXPECT_EQ(o.vt.empty(), !ply.hasST);
    size_t mismatches = 0;
    for (size_t t = 0; t < o.triangles.size(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            const ObjCorner& c = o.triangles[t][k];
            ASSERT_GE(c.v, 0);
            ASSERT_LT(size_t(c.v), o.v.size());
            ASSERT_GE(c.vn, 0);
            ASSERT_LT(size_t(c.vn), o.vn.size());
            const auto& v = ply.vertices.at(size_t(ply.triangles[t][k]));
            for (size_t i = 0; i < 3; ++i) {
                mismatches += !same(o.v[size_t(c.v)][i], v.p[i]);
                mismatches += !same(o.vn[size_t(c.vn)][i], v.n[i]);
            }
            if (ply.hasST) {
                ASSERT_GE(c.vt, 0);
                ASSERT_LT(size_t(c.vt), o.vt.size());
                mismatches += !same(o.vt[size_t(c.vt)][0], v.st[0]);
                mismatches += !same(o.vt[size_t(c.vt)][1], v.st[1]);
            } else {
                EXPECT_EQ(c.vt, -1);
            }
        }
    EXPECT_EQ(mismatches, 0u);
    // Each distinct position once: seam copies share their v.
    std::set<std::array<uint32_t, 3>> distinct;
    for (const auto& v : ply.vertices)
        distinct.insert({std::bit_cast<uint32_t>(v.p[0]), std::bit_cast<uint32_t>(v.p[1]),
                         std::bit_cast<uint32_t>(v.p[2])});
    EXPECT_EQ(o.v.size(), distinct.size());
}

Drawn drawnFromGltf(const GltfMesh& g) {
    Drawn d;
    d.vertices.resize(g.positions.size());
    for (size_t i = 0; i < g.positions.size(); ++i)
        std::memcpy(d.vertices[i].p, g.positions[i].data(), 12);
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3)
        d.triangles.push_back({int32_t(g.indices[t]), int32_t(g.indices[t + 1]), int32_t(g.indices[t + 2])});
    return d;
}

struct Exported {
    Drawn ply;
    GltfMesh glb, gltf;
    ObjMesh obj;
    std::string glbPath, gltfPath;
};

// Writes the four formats of one render, each in its own run, and reads them back.
Exported exportAll(const ScratchDir& dir, const std::string& limn, const std::string& name,
                   std::vector<std::string> extra = {}) {
    Exported e;
    for (const char* ext : {".ply", ".obj", ".gltf", ".glb"}) {
        std::string path = (dir / (name + ext)).string();
        auto r = renderMesh(limn, path, extra);
        EXPECT_EQ(r.exitCode, 0) << ext << ": " << r.err;
        EXPECT_EQ(r.out, "") << ext << ": --mesh-out without -o writes no image";
        std::string bytes = readFile(path);
        if (std::string(ext) == ".ply") e.ply = parsePly(bytes);
        if (std::string(ext) == ".obj") e.obj = parseObj(bytes);
        if (std::string(ext) == ".gltf") e.gltf = readGltf(bytes, false), e.gltfPath = path;
        if (std::string(ext) == ".glb") e.glb = readGltf(bytes, true), e.glbPath = path;
    }
    return e;
}

void expectAllEqual(const Exported& e) {
    {
        SCOPED_TRACE("glb");
        expectGltfEqualsPly(e.glb, e.ply);
    }
    {
        SCOPED_TRACE("gltf");
        expectGltfEqualsPly(e.gltf, e.ply);
    }
    {
        SCOPED_TRACE("obj");
        expectObjEqualsPly(e.obj, e.ply);
    }
}

// node, looked up on PATH when the test runs: the build may have been configured before
// scripts/setup.sh --tests installed it (scripts/examples.sh configures without node).
std::string findNode() {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path candidate =
            std::filesystem::path(dirs.substr(start, end - start)) / "node";
        if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
        start = end + 1;
    }
    return LIMN_NODE; // where configure found it, if anywhere
}

// Runs the Khronos glTF-Validator on `files`: zero errors and zero warnings.
void expectValid(const std::vector<std::string>& files) {
    const std::string node = findNode();
    ASSERT_TRUE(!node.empty() && std::filesystem::exists(node))
        << "node (nodejs) is not installed: run scripts/setup.sh --tests";
    std::vector<std::string> args = {node, LIMN_GLTF_VALIDATE};
    args.insert(args.end(), files.begin(), files.end());
    auto r = run(args);
    ASSERT_NE(r.exitCode, 3) << r.err << "(the validator is installed by scripts/setup.sh)";
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    for (const auto& f : files)
        EXPECT_NE(r.out.find(f + ": errors 0 warnings 0 "), std::string::npos) << r.out << r.err;
    std::cout << r.out;
}

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
