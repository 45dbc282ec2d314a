// The glTF feature corpus (tests/data/gltf/features, written by its make_corpus.py with the
// libraries' own encoders): each feature read or refused as glTF 2.0 says, expected values from
// the geometry the generator wrote (a unit cube, a strip of two unit squares), not from limn.
#include "base/error.h"
#include "mesh/gltf.h"
#include "mesh/import.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <set>

using namespace limn;

namespace {

std::string feature(const std::string& name) { return test::modelPath("gltf/features/" + name).string(); }

Mesh read(const std::string& name, Warnings* warnings = nullptr, GltfPolygons* polygons = nullptr) {
    Warnings local;
    const auto bytes = test::readBytes(feature(name));
    return importMesh(feature(name), bytes, warnings ? *warnings : local, nullptr, nullptr, polygons);
}

std::string refusal(const std::string& name) {
    try {
        read(name);
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        return e.what();
    }
    ADD_FAILURE() << name << " was accepted";
    return {};
}

// Every face of `a` has a face of `b` whose corners (positions and UVs, in the same cyclic
// order) are within `tolerance`, and the face counts agree.
void expectSameFaces(const Mesh& a, const Mesh& b, double tolerance) {
    ASSERT_EQ(a.faceCount(), b.faceCount());
    ASSERT_EQ(a.hasUVs(), b.hasUVs());
    for (size_t f = 0; f < a.faceCount(); ++f) {
        bool found = false;
        for (size_t g = 0; g < b.faceCount() && !found; ++g) {
            if (a.faceSize(f) != b.faceSize(g)) continue;
            const size_t n = a.faceSize(f);
            for (size_t shift = 0; shift < n && !found; ++shift) {
                bool same = true;
                for (size_t k = 0; k < n && same; ++k) {
                    const size_t ka = k, kb = (k + shift) % n;
                    same = glm::length(a.positions[a.face(f)[ka]] - b.positions[b.face(g)[kb]]) <= tolerance;
                    if (same && a.hasUVs())
                        same = glm::length(a.uvs[a.faceUVs(f)[ka]] - b.uvs[b.faceUVs(g)[kb]]) <= tolerance;
                }
                found = same;
            }
        }
        EXPECT_TRUE(found) << "face " << f << " has no match";
    }
}

// The volume a closed mesh encloses, positive when its faces wind counter-clockwise seen from
// outside (fan triangulation of each face).
double signedVolume(const Mesh& m) {
    double v = 0;
    for (size_t f = 0; f < m.faceCount(); ++f) {
        auto c = m.face(f);
        for (size_t k = 1; k + 1 < c.size(); ++k)
            v += glm::dot(m.positions[c[0]], glm::cross(m.positions[c[k]], m.positions[c[k + 1]])) / 6.0;
    }
    return v;
}

bool hasPosition(const Mesh& m, glm::dvec3 p) {
    return std::any_of(m.positions.begin(), m.positions.end(), [&](const glm::dvec3& q) { return glm::length(p - q) < 1e-12; });
}

TEST(GltfFeatures, ReferenceCubeIsTheCubeTheGeneratorWrote) {
    const Mesh cube = read("cube.gltf");
    EXPECT_EQ(cube.vertexCount(), 8u);
    EXPECT_EQ(cube.faceCount(), 12u);
    EXPECT_NEAR(signedVolume(cube), 1.0, 1e-12);
}

// Draco's quantization: 14 bits over the unit cube (a step of 1/16383) for positions, 12 bits
// for UVs (1/4095): half a step is the most a decoded value may be off.
TEST(GltfFeatures, DracoDecodesToTheUncompressedCube) {
    Warnings w;
    const Mesh draco = read("cube_draco.gltf", &w);
    EXPECT_TRUE(w.empty());
    expectSameFaces(draco, read("cube.gltf"), 0.5 / 4095 + 1e-9);
    EXPECT_EQ(draco.vertexCount(), 8u);
}

TEST(GltfFeatures, DracoInAGlbToo) {
    std::string json = test::readFile(feature("cube_draco.gltf"));
    while (json.size() % 4) json += ' ';
    std::vector<uint8_t> glb(20 + json.size());
    auto put = [&](size_t at, uint32_t v) { std::memcpy(glb.data() + at, &v, 4); };
    put(0, 0x46546C67u); // "glTF"
    put(4, 2);
    put(8, uint32_t(glb.size()));
    put(12, uint32_t(json.size()));
    put(16, 0x4E4F534Au); // "JSON"
    std::memcpy(glb.data() + 20, json.data(), json.size());
    Warnings w;
    expectSameFaces(readGltf(glb, true, "", w), read("cube.gltf"), 0.5 / 4095 + 1e-9);
}

// meshopt's codecs are lossless without filters: the decoded cube is the cube, bit for bit.
TEST(GltfFeatures, MeshoptDecodesToTheUncompressedCube) {
    for (const char* name : {"cube_meshopt.gltf", "cube_meshopt_khr.gltf"}) {
        SCOPED_TRACE(name);
        const Mesh m = read(name);
        expectSameFaces(m, read("cube.gltf"), 0.0);
        EXPECT_EQ(m, read("cube.gltf"));
    }
}

TEST(GltfFeatures, SparseAccessorSubstitutes) {
    const Mesh m = read("sparse.gltf");
    EXPECT_EQ(m.vertexCount(), 6u);
    EXPECT_TRUE(hasPosition(m, {1, 1, 0.5}));
    EXPECT_TRUE(hasPosition(m, {2, 1, 0.5}));
    EXPECT_TRUE(hasPosition(m, {0, 1, 0}));
    EXPECT_FALSE(hasPosition(m, {1, 1, 0}));
}

TEST(GltfFeatures, AccessorWithoutBufferViewIsZeros) {
    const Mesh m = read("no_buffer_view.gltf");
    EXPECT_EQ(m.vertexCount(), 6u);
    EXPECT_TRUE(hasPosition(m, {0, 0, 0})); // not substituted: zero
    for (glm::dvec3 p : {glm::dvec3(1, 0, 0), {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}) EXPECT_TRUE(hasPosition(m, p));
}

// Default weights (0.25, 0.5): target 0 lifts the top row by 1, target 1 moves vertex 2 by +x.
TEST(GltfFeatures, MorphTargetsTakeTheMeshsDefaultWeights) {
    const Mesh m = read("morph_targets.gltf");
    EXPECT_EQ(m.vertexCount(), 6u);
    for (glm::dvec3 p : {glm::dvec3(0, 0, 0), {1, 0, 0}, {2.5, 0, 0}, {0, 1, 0.25}, {1, 1, 0.25}, {2, 1, 0.25}})
        EXPECT_TRUE(hasPosition(m, p)) << p.x << " " << p.y << " " << p.z;
}

// Scale (0.5, 0.5) then offset (0.5, 0) on glTF's UVs; limn's v is up (1 - v).
TEST(GltfFeatures, TextureTransformMovesTheUVs) {
    const Mesh m = read("texture_transform.gltf");
    std::set<std::pair<double, double>> uvs;
    for (const auto& uv : m.uvs) uvs.insert({uv.x, uv.y});
    const std::set<std::pair<double, double>> expected = {{0.5, 0.5}, {0.75, 0.5}, {1, 0.5}, {0.5, 1}, {0.75, 1}, {1, 1}};
    EXPECT_EQ(uvs, expected);
}

// glTF 2.0, 3.7.4: a mirroring node reverses the winding. Both cubes face outward, so the
// whole encloses twice the unit volume (without the reversal the two would cancel to 0).
TEST(GltfFeatures, MirroredNodeIsRightSideOut) {
    const Mesh m = read("mirrored_node.gltf");
    EXPECT_EQ(m.vertexCount(), 16u); // the mirrored cube spans x = -2 .. -1
    EXPECT_EQ(m.faceCount(), 24u);
    EXPECT_NEAR(signedVolume(m), 2.0, 1e-12);
    EXPECT_TRUE(hasPosition(m, {-2, 1, 1}));
}

TEST(GltfFeatures, NodeGraphsThatAreNotTreesAreRefusedAtOnce) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NE(refusal("dag.gltf").find("would draw more than 1000000 node instances"), std::string::npos);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
    EXPECT_NE(refusal("cycle.gltf").find("the node graph has a cycle (1 -> 2 -> 1)"), std::string::npos);
}

TEST(GltfFeatures, RequiredExtensionIsNamedOptionalOneWarned) {
    EXPECT_NE(refusal("requires_unknown.gltf").find("requires KHR_texture_basisu, which limn does not read"),
              std::string::npos);
    Warnings w;
    EXPECT_EQ(read("uses_unknown.gltf", &w).faceCount(), 12u);
    ASSERT_EQ(w.messages.size(), 1u);
    EXPECT_NE(w.messages[0].find("uses KHR_materials_clearcoat, which limn does not read (optional; ignored)"),
              std::string::npos);
}

TEST(GltfFeatures, NgonEncodingRebuildsPolygons) {
    GltfPolygons off;
    EXPECT_EQ(read("ngon_encoding.gltf", nullptr, &off).faceCount(), 5u);
    EXPECT_TRUE(off.fileHasNgonEncoding);
    GltfPolygons on;
    on.rebuildNgons = true;
    const Mesh m = read("ngon_encoding.gltf", nullptr, &on);
    ASSERT_EQ(m.faceCount(), 2u);
    // Welding keeps the file's vertex order here (every position is new when first met).
    EXPECT_EQ(std::vector<uint32_t>(m.face(0).begin(), m.face(0).end()), (std::vector<uint32_t>{0, 1, 4, 3}));
    EXPECT_EQ(std::vector<uint32_t>(m.face(1).begin(), m.face(1).end()), (std::vector<uint32_t>{1, 2, 5, 6, 4}));
    EXPECT_EQ(on.ngonsRebuilt, 2u);
    GltfPolygons cube;
    cube.rebuildNgons = true;
    read("cube.gltf", nullptr, &cube);
    EXPECT_FALSE(cube.fileHasNgonEncoding);
}

} // namespace

namespace {

// The morph-target animation as control-point sets (the library side of limn-render --frames):
// frame k equals the mesh read with that frame's weights as its default weights.
TEST(GltfFeatures, MorphAnimationFramesAreTheMeshWithThoseWeights) {
    const std::string json = test::readFile(feature("morph_animation.gltf"));
    auto bytes = [](const std::string& s) { return std::span(reinterpret_cast<const uint8_t*>(s.data()), s.size()); };
    auto withWeight = [&](double w) { // the file with its default weight replaced
        std::string s = json;
        const size_t at = s.find("\"weights\": [\n    0.25\n   ]");
        EXPECT_NE(at, std::string::npos);
        s.replace(at, std::string("\"weights\": [\n    0.25\n   ]").size(), "\"weights\": [" + std::to_string(w) + "]");
        Warnings w2;
        return readGltf(bytes(s), false, "", w2);
    };
    Warnings w;
    const GltfMorphFrames keys = readGltfMorphFrames(bytes(json), false, "", w);
    EXPECT_EQ(keys.times, (std::vector<double>{0, 1, 2}));
    const GltfMorphFrames sampled = readGltfMorphFrames(bytes(json), false, "", w, {.fps = 2.0});
    EXPECT_EQ(sampled.times, (std::vector<double>{0, 0.5, 1, 1.5, 2}));
    const double expected[] = {0, 0.5, 1, 0.75, 0.5}; // linear between 0, 1, 0.5
    const Mesh reference = withWeight(0.25);
    for (size_t k = 0; k < sampled.times.size(); ++k) {
        SCOPED_TRACE(k);
        const Mesh m = withWeight(expected[k]);
        ASSERT_EQ(m.faceVertices, reference.faceVertices); // one topology for every frame
        EXPECT_EQ(sampled.positions[k], m.positions);
    }
    EXPECT_EQ(sampled.base, reference.positions);
    EXPECT_EQ(sampled.unwelded, 0u);
    EXPECT_TRUE(w.empty());
    // Without an animation: a clear refusal.
    const auto cube = test::readBytes(feature("cube.gltf"));
    EXPECT_THROW(readGltfMorphFrames(cube, false, "", w), Error);
}

} // namespace

namespace {

// readGltfEmbedded reads what the bytes hold and no file: embedded buffers and images as readGltf
// does, while a buffer named by a file URI (next to the file, or anywhere) is refused by name.
TEST(GltfFeatures, EmbeddedOnlyReadsNoFile) {
    Warnings w;
    const auto cube = test::readBytes(feature("cube.gltf")); // a data: URI buffer
    EXPECT_EQ(readGltfEmbedded(cube, false, w).positions, readGltf(cube, false, "", w).positions);
    std::optional<MeshMaterial> material;
    const auto box = test::readBytes(test::modelPath("gltf/BoxTextured/BoxTextured.glb"));
    EXPECT_EQ(readGltfEmbedded(box, true, w, &material).faceVertices, readGltf(box, true, "", w).faceVertices);
    EXPECT_TRUE(material && material->hasTexture());
    const std::string dir = test::modelPath("gltf/AnimatedMorphCube").string() + "/";
    const auto external = test::readBytes(dir + "AnimatedMorphCube.gltf"); // AnimatedMorphCube.bin
    EXPECT_EQ(readGltf(external, false, dir, w).vertexCount(), 8u);
    try {
        readGltfEmbedded(external, false, w);
        ADD_FAILURE() << "an external buffer was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("AnimatedMorphCube.bin: this reader reads embedded data only"),
                  std::string::npos)
            << e.what();
    }
    // An absolute path is no way around it, and the animation reader takes the same rule.
    std::string json(external.begin(), external.end());
    json.replace(json.find("\"AnimatedMorphCube.bin\""), 23, "\"" + dir + "AnimatedMorphCube.bin\"");
    const std::span bytes(reinterpret_cast<const uint8_t*>(json.data()), json.size());
    EXPECT_EQ(readGltf(bytes, false, "", w).vertexCount(), 8u);
    EXPECT_THROW(readGltfEmbedded(bytes, false, w), Error);
    EXPECT_EQ(readGltfMorphFrames(bytes, false, "", w).positions.size(), 127u);
    EXPECT_THROW(readGltfMorphFrames(bytes, false, "", w, {.embeddedOnly = true}), Error);
}

} // namespace
