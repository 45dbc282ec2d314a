// Helpers of limn-render --mesh-out's tests (mesh_export_cli_test.cpp,
// mesh_export_options_cli_test.cpp): containers made and meshes written by the tools, the three
// formats read back and compared with the PLY bit for bit, and the Khronos glTF-Validator.
#pragma once

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
#include <cstring>
#include <map>

namespace limn::mesh_export_test {

using namespace limn::test;

inline std::string bin(const std::string& name) {
    return tool(name).string();
}

// classify | tables --depth N into dir/name.limn.
inline std::string prepare(const ScratchDir& dir, const std::string& model, int depth,
                    const std::string& name) {
    std::string out = (dir / (name + ".limn")).string();
    auto c = run({bin("limn-classify"), model});
    EXPECT_EQ(c.exitCode, 0) << c.err;
    auto t = run({bin("limn-tables"), "--depth", std::to_string(depth), "-o", out}, c.out);
    EXPECT_EQ(t.exitCode, 0) << t.err;
    return out;
}

inline RunResult renderMesh(const std::string& limn, const std::string& out,
                     std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {bin("limn-render"), limn, "--size", "16x16", "--mesh-out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
}

inline bool same(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

// ---- the checks ----

// The glTF carries the PLY's vertices and triangles bit for bit (texture v flipped).
inline void expectGltfEqualsPly(const GltfMesh& g, const Drawn& ply) {
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
inline void expectObjEqualsPly(const ObjMesh& o, const Drawn& ply) {
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

inline Drawn drawnFromGltf(const GltfMesh& g) {
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
inline Exported exportAll(const ScratchDir& dir, const std::string& limn, const std::string& name,
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

inline void expectAllEqual(const Exported& e) {
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
inline std::string findNode() {
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
inline void expectValid(const std::vector<std::string>& files) {
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

} // namespace limn::mesh_export_test
