// The built-in examples: what each is built to exercise, counted independently of limn (closed
// forms from the construction, the reference OBJ reader and OpenSubdiv), plus byte determinism.
#include "reference_mesh.h"
#include "test_support.h"
#include "mesh/examples.h"
#include "mesh/import.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <set>
#include <sstream>

using namespace limn;

namespace {

struct Expected {
    std::string name;
    int vertices, faces, edges, boundaryEdges, boundaryLoops, uvSeamEdges;
    std::map<int, int> faceSizes;
};

// From the construction in lib/mesh/examples.h: quad sphere n = 4 (6n^2+2 vertices, 6n^2 faces,
// 12n^2 edges, seams on 12 cube edges of n segments), torus 16 x 8 (seams along one ring and one
// tube loop), pentagon tower (5 spokes, 5 floor edges and 1 wall edge are seams), a 2 x 2-per-face
// box, an 8 x 8 grid without its middle 2 x 2 quads (32 outer and 8 inner boundary edges).
const std::vector<Expected> kExamples = {
    {"cube", 8, 6, 12, 0, 0, 12, {{4, 6}}},
    {"quad_sphere", 98, 96, 192, 0, 0, 48, {{4, 96}}},
    {"torus", 128, 128, 256, 0, 0, 24, {{4, 128}}},
    {"pentagon_tower", 11, 11, 20, 0, 0, 11, {{3, 5}, {4, 5}, {5, 1}}},
    {"creased_cube", 26, 24, 48, 0, 0, 24, {{4, 24}}},
    {"grid_with_hole", 80, 60, 140, 40, 2, 0, {{4, 60}}},
};

class ExamplesDir : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = new test::ScratchDir;
        auto r = test::run({test::tool("limn-examples").string(), "-o", (*dir_ / "a").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::string path(const std::string& name) {
        return (*dir_ / "a" / (name + ".obj")).string();
    }
    static test::ScratchDir* dir_;
};
test::ScratchDir* ExamplesDir::dir_ = nullptr;

double signedVolume(const test::ReferenceObj& obj) {
    auto cross = [](auto a, auto b) {
        return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                     a[0] * b[1] - a[1] * b[0]};
    };
    double volume = 0;
    for (const auto& f : obj.faces)
        for (size_t k = 1; k + 1 < f.size(); ++k) {
            auto c = cross(obj.positions[f[k]], obj.positions[f[k + 1]]);
            const auto& a = obj.positions[f[0]];
            volume += (a[0] * c[0] + a[1] * c[1] + a[2] * c[2]) / 6;
        }
    return volume;
}

// Closed loops formed by the edges that only one face uses.
int boundaryLoops(const test::ReferenceObj& obj) {
    std::map<std::pair<int, int>, int> uses;
    for (const auto& f : obj.faces)
        for (size_t k = 0; k < f.size(); ++k) {
            int a = f[k], b = f[(k + 1) % f.size()];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    std::vector<int> parent(obj.vertexCount);
    for (int v = 0; v < obj.vertexCount; ++v) parent[v] = v;
    auto find = [&](int v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    std::set<int> onBoundary;
    for (const auto& [e, n] : uses)
        if (n == 1) {
            parent[find(e.first)] = find(e.second);
            onBoundary.insert(e.first);
            onBoundary.insert(e.second);
        }
    std::set<int> roots;
    for (int v : onBoundary) roots.insert(find(v));
    return static_cast<int>(roots.size());
}

TEST_F(ExamplesDir, ListNamesEveryFileWritten) {
    auto r = test::run({test::tool("limn-examples").string(), "--list"});
    ASSERT_EQ(r.exitCode, 0);
    std::set<std::string> listed, written;
    std::istringstream in(r.out);
    for (std::string name; std::getline(in, name);) listed.insert(name + ".obj");
    // --list-sequences names the animations, each a folder of frames.
    r = test::run({test::tool("limn-examples").string(), "--list-sequences"});
    ASSERT_EQ(r.exitCode, 0);
    std::istringstream seq(r.out);
    for (std::string name; std::getline(seq, name);) listed.insert(name + "/");
    for (const auto& e : std::filesystem::directory_iterator(*dir_ / "a"))
        written.insert(e.path().filename().string() + (e.is_directory() ? "/" : ""));
    EXPECT_EQ(listed, written);
    EXPECT_EQ(listed.size(), kExamples.size() + 1);
}

// The animation: frames of one topology (same faces and UVs, only positions move), numbered from
// 0 and looping (frame 24 would be frame 0's surface: the tube's ellipse turns half a turn).
TEST_F(ExamplesDir, TwistFramesShareTheirTopologyAndMove) {
    std::vector<Mesh> frames;
    for (int k = 0;; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "twist_%04d.obj", k);
        const auto p = *dir_ / "a" / "twist" / name;
        if (!std::filesystem::exists(p)) break;
        Warnings w;
        frames.push_back(importMeshFile(p.string(), w));
    }
    ASSERT_EQ(frames.size(), 24u);
    for (size_t k = 1; k < frames.size(); ++k) {
        EXPECT_EQ(frames[k].faceOffsets, frames[0].faceOffsets);
        EXPECT_EQ(frames[k].faceVertices, frames[0].faceVertices);
        EXPECT_EQ(frames[k].uvIndices, frames[0].uvIndices);
        EXPECT_EQ(frames[k].uvs, frames[0].uvs);
        EXPECT_NE(frames[k].positions, frames[k - 1].positions) << k;
    }
    // Looping: frame 24 of 24 (not written) is frame 0 with every tube loop's vertices moved half
    // way round (vertex (i, j) at (i, j + 6); index j * 24 + i), the same surface, up to the
    // 6-decimal rounding.
    const Mesh wrap = makeTwistingTorus(24, 12, 24, 24);
    ASSERT_EQ(wrap.positions.size(), frames[0].positions.size());
    double worst = 0;
    for (size_t j = 0; j < 12; ++j)
        for (size_t i = 0; i < 24; ++i)
            worst = std::max(worst, glm::length(wrap.positions[j * 24 + i] - frames[0].positions[((j + 6) % 12) * 24 + i]));
    EXPECT_LT(worst, 2e-6);
}

TEST_F(ExamplesDir, SameBytesEveryRun) {
    auto r = test::run({test::tool("limn-examples").string(), "-o", (*dir_ / "b").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const auto& e : kExamples)
        EXPECT_EQ(test::readFile(path(e.name)), test::readFile(*dir_ / "b" / (e.name + ".obj")))
            << e.name;
}

TEST_F(ExamplesDir, OnlyWritesTheNamedExamples) {
    std::string out = (*dir_ / "only").string();
    auto r = test::run({test::tool("limn-examples").string(), "-o", out, "--only", "torus,cube"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::set<std::string> written;
    for (const auto& e : std::filesystem::directory_iterator(out))
        written.insert(e.path().filename().string());
    EXPECT_EQ(written, (std::set<std::string>{"cube.obj", "torus.obj"}));
    EXPECT_EQ(test::readFile(out + "/torus.obj"), test::readFile(path("torus")));

    auto bad = test::run({test::tool("limn-examples").string(), "-o", out, "--only", "teapot"});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("limn-examples: error: --only: no example named 'teapot'"),
              std::string::npos)
        << bad.err;
}

TEST_F(ExamplesDir, EachExampleIsWhatItClaims) {
    for (const auto& e : kExamples) {
        SCOPED_TRACE(e.name);
        test::ReferenceObj obj = test::readReferenceObj(path(e.name));
        test::ReferenceCounts ref = test::referenceCounts(obj);
        EXPECT_EQ(ref.vertices, e.vertices);
        EXPECT_EQ(ref.faces, e.faces);
        EXPECT_EQ(ref.edges, e.edges);
        EXPECT_EQ(ref.boundaryEdges, e.boundaryEdges);
        EXPECT_EQ(boundaryLoops(obj), e.boundaryLoops);
        EXPECT_EQ(ref.faceSizes, e.faceSizes);
        EXPECT_EQ(ref.nonManifoldEdges, 0); // OpenSubdiv also flags inconsistent orientation
        EXPECT_EQ(obj.firstDegenerateFace(), -1);
        ASSERT_TRUE(obj.hasUVs());
        EXPECT_EQ(ref.uvSeamEdges, e.uvSeamEdges);
        for (const auto& [u, v] : obj.uvs) {
            EXPECT_TRUE(u >= 0 && u <= 1 && v >= 0 && v <= 1) << u << " " << v;
        }
        // Counter-clockwise seen from outside: closed meshes enclose a positive volume.
        if (e.boundaryEdges == 0) {
            EXPECT_GT(signedVolume(obj), 0.5);
        }
        // Euler characteristic: spheres 2, the torus and the annulus-like grid 0.
        int chi = e.vertices - e.edges + e.faces;
        EXPECT_EQ(chi, e.name == "torus" || e.name == "grid_with_hole" ? 0 : 2);

        // And limn sees them as OpenSubdiv does.
        auto r = test::run({test::tool("limn-info").string(), "--json", path(e.name)});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_TRUE(r.err.empty()) << r.err;
        for (const auto& m : test::infoMismatches(ref, r.out)) ADD_FAILURE() << m;
    }
}

TEST_F(ExamplesDir, FeaturesTheLaterStagesNeed) {
    auto count = [](const auto& r) { return test::referenceCounts(r); };
    // Extraordinary vertices: exactly the 8 cube corners of the quad sphere; none on the torus.
    EXPECT_EQ(count(test::readReferenceObj(path("quad_sphere"))).extraordinary, 8);
    test::ReferenceCounts torus = count(test::readReferenceObj(path("torus")));
    EXPECT_EQ(torus.extraordinary, 0);
    EXPECT_EQ(torus.regularFaces, 128);

    // Creases: semi-sharp and infinitely sharp tags, each naming an edge of the mesh, and a
    // semi-sharp corner.
    test::ReferenceObj creased = test::readReferenceObj(path("creased_cube"));
    std::set<std::pair<int, int>> edges;
    for (const auto& f : creased.faces)
        for (size_t k = 0; k < f.size(); ++k)
            edges.insert(std::minmax(f[k], f[(k + 1) % f.size()]));
    int infinite = 0, semi = 0;
    for (const auto& [pair, w] : creased.creases) {
        EXPECT_TRUE(edges.count(std::minmax(pair.first, pair.second)))
            << pair.first << "-" << pair.second;
        (w >= 10 ? infinite : semi) += 1;
        if (w < 10) {
            EXPECT_GT(w, 0);
        }
    }
    EXPECT_EQ(infinite, 8);
    EXPECT_EQ(semi, 8);
    ASSERT_EQ(creased.corners.size(), 1u);
    EXPECT_GT(creased.corners[0].second, 0);
    EXPECT_LT(creased.corners[0].second, 10);

    // The open grid carries an edge-and-corner boundary rule (OBJ tag value 1).
    EXPECT_EQ(test::readReferenceObj(path("grid_with_hole")).interpolateBoundary, 1);
}

} // namespace
