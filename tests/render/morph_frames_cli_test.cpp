// limn-render --frames FILE.gltf: a glTF's morph-target animation as a sequence, on Khronos'
// AnimatedMorphCube. A frame's control points are checked against values computed here from the
// .bin (base + sum of weight_i * target_i, under the node's rotation and scale; glTF 2.0, 3.7.2.2),
// and its image against a single render of the glTF with that frame's weights as its default
// weights; bad animations and mismatched inputs are refused before any file is written.
#include "test_support.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstring>
#include <sstream>

using namespace limn::test;

namespace {

std::string limnRender() { return tool("limn-render").string(); }
std::filesystem::path morphCube() { return modelPath("gltf/AnimatedMorphCube/AnimatedMorphCube.gltf"); }

// Little-endian float32s at `offset` of the .bin; the offsets are the buffer views' in
// AnimatedMorphCube.gltf (POSITION 672, target 0 POSITION 1248, target 1 POSITION 2112, the
// animation's output weights 3268, two per keyframe).
std::vector<float> floatsAt(const std::vector<uint8_t>& bin, size_t offset, size_t count) {
    std::vector<float> out(count);
    std::memcpy(out.data(), bin.data() + offset, count * sizeof(float));
    return out;
}

// The 24 glTF vertices of keyframe k, in world space: the node's rotation (quaternion x, y, z, w)
// and scale, applied as v' = q (s v) q* (glTF 2.0, 3.5.2: T * R * S).
std::vector<glm::dvec3> keyframePositions(size_t k) {
    const std::vector<uint8_t> bin = readBytes(modelPath("gltf/AnimatedMorphCube/AnimatedMorphCube.bin"));
    const std::vector<float> base = floatsAt(bin, 672, 72), thin = floatsAt(bin, 1248, 72),
                             angle = floatsAt(bin, 2112, 72), weights = floatsAt(bin, 3268 + 8 * k, 2);
    const glm::dvec3 q(0.0, 0.7071067, -0.7071068);
    const double qw = 0.0;
    std::vector<glm::dvec3> out;
    for (size_t v = 0; v < 24; ++v) {
        glm::dvec3 p;
        for (int c = 0; c < 3; ++c)
            p[c] = 100.0 * (double(base[3 * v + c]) + double(weights[0]) * thin[3 * v + c] +
                            double(weights[1]) * angle[3 * v + c]);
        const glm::dvec3 t = 2.0 * glm::cross(q, p);
        out.push_back(p + qw * t + glm::cross(q, t));
    }
    return out;
}

// The x, y, z of every vertex of an ASCII PLY (limn-render --mesh-out --mesh-ascii).
std::vector<glm::dvec3> plyPositions(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    size_t count = 0;
    bool xFirst = false;
    while (std::getline(in, line) && line != "end_header") {
        if (line.rfind("element vertex ", 0) == 0) count = std::stoul(line.substr(15));
        if (count && !xFirst && line.rfind("property float x", 0) == 0) xFirst = true; // then y, z
    }
    EXPECT_TRUE(xFirst) << text.substr(0, 400);
    std::vector<glm::dvec3> out;
    for (size_t v = 0; v < count && std::getline(in, line); ++v) {
        std::istringstream fields(line);
        glm::dvec3 p;
        fields >> p.x >> p.y >> p.z;
        out.push_back(p);
    }
    return out;
}

const std::vector<std::string> kCamera = {"--size", "80x60", "--eye", "3,2,4", "--target", "0,0,0", "--validate"};

std::vector<std::string> plus(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

} // namespace

TEST(MorphFrames, AFrameIsTheMeshWithThatKeyframesWeights) {
    ScratchDir out;
    const std::string gltf = morphCube().string();
    auto r = run(plus({limnRender(), gltf, "--frames", gltf, "--frame-range", "70-70", "-o",
                       (out / "f_%04d.png").string(), "--mesh-out", (out / "f_%04d.ply").string(), "--mesh-ascii",
                       "--depfile", (out / "f.d").string()},
                      kCamera));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(filesIn(out.path()), (std::vector<std::string>{"f.d", "f_0070.ply", "f_0070.png"}));

    // Every drawn vertex is one of keyframe 70's glTF vertices, and every glTF vertex is drawn.
    const std::vector<glm::dvec3> expected = keyframePositions(70), drawn = plyPositions(readFile(out / "f_0070.ply"));
    ASSERT_FALSE(drawn.empty());
    auto near = [](const std::vector<glm::dvec3>& among, const glm::dvec3& p) {
        for (const glm::dvec3& q : among)
            if (glm::length(p - q) < 1e-5) return true;
        return false;
    };
    for (const glm::dvec3& p : drawn) EXPECT_TRUE(near(expected, p)) << p.x << " " << p.y << " " << p.z;
    for (const glm::dvec3& p : expected) EXPECT_TRUE(near(drawn, p)) << p.x << " " << p.y << " " << p.z;
    // What the check relies on: keyframe 70 is away from the base mesh.
    EXPECT_FALSE(near(keyframePositions(0), expected[0]) && near(keyframePositions(0), expected[5]));

    // The depfile names the glTF and its .bin, once each.
    const std::string dep = readFile(out / "f.d");
    EXPECT_NE(dep.find("AnimatedMorphCube.bin"), std::string::npos) << dep;
    EXPECT_EQ(dep.find("AnimatedMorphCube.gltf"), dep.rfind("AnimatedMorphCube.gltf")) << dep;

    // The glTF with keyframe 70's weights as its default weights, drawn on its own.
    const std::vector<uint8_t> bin = readBytes(modelPath("gltf/AnimatedMorphCube/AnimatedMorphCube.bin"));
    const std::vector<float> w = floatsAt(bin, 3268 + 8 * 70, 2);
    std::string json = readFile(morphCube());
    const std::string defaults = "\"weights\": [\n        0.0,\n        0.0\n      ]";
    const size_t at = json.find(defaults);
    ASSERT_NE(at, std::string::npos);
    char weights[96];
    std::snprintf(weights, sizeof weights, "\"weights\": [%.17g, %.17g]", double(w[0]), double(w[1]));
    json.replace(at, defaults.size(), weights);
    ScratchDir single;
    writeFile(single / "morphed.gltf", json);
    std::filesystem::copy_file(modelPath("gltf/AnimatedMorphCube/AnimatedMorphCube.bin"),
                               single / "AnimatedMorphCube.bin");
    r = run(plus({limnRender(), (single / "morphed.gltf").string(), "-o", (single / "single.png").string()}, kCamera));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(single / "single.png"), readBytes(out / "f_0070.png"));
}

// A container made from the glTF takes its frames (limn-classify joins the cube's 12 triangles
// into 6 quads; the vertices stay, in their order); --fps resamples the animation (keyframes from 0 to 4.19999743 s at
// 5 fps: 21 frames, 0 to 20).
TEST(MorphFrames, AContainerMadeFromTheGltfAndFps) {
    ScratchDir out;
    const std::string gltf = morphCube().string(), limn = (out / "cube.limn").string();
    auto r = run({tool("limn-classify").string(), gltf, "-q", "-o", limn});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run({tool("limn-tables").string(), limn, "--depth", "1", "-q", "-o", limn});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run(plus({limnRender(), limn, "--frames", gltf, "--fps", "5", "--frame-range", "19-30", "-o",
                  (out / "f_%02d.png").string()},
                 kCamera));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(filesIn(out.path()), (std::vector<std::string>{"cube.limn", "f_19.png", "f_20.png"}));
}

TEST(MorphFrames, RefusedBeforeAnyFileIsWritten) {
    ScratchDir out;
    const std::string gltf = morphCube().string(), o = (out / "f_%04d.png").string();
    auto r = run({tool("limn-examples").string(), "-o", out.path().string(), "--only", "cube"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string cube = (out / "cube.obj").string(); // 8 vertices, but not the glTF's
    const std::string still = modelPath("gltf/features/cube.gltf").string(); // no animation
    const std::string rest = (out / "rest.gltf").string(); // the glTF with other default weights
    std::string json = readFile(morphCube());
    const std::string defaults = "\"weights\": [\n        0.0,\n        0.0\n      ]";
    ASSERT_NE(json.find(defaults), std::string::npos);
    json.replace(json.find(defaults), defaults.size(), "\"weights\": [1, 0]");
    writeFile(rest, json);
    std::filesystem::copy_file(modelPath("gltf/AnimatedMorphCube/AnimatedMorphCube.bin"), out / "AnimatedMorphCube.bin");
    const struct {
        std::vector<std::string> args;
        int exit;
        const char* words;
    } cases[] = {
        {{gltf, "--frames", gltf, "--fps", "0", "-o", o}, 2, "--fps"},
        {{gltf, "--frames", gltf, "--fps", "1001", "-o", o}, 2, "--fps"},
        {{gltf, "--fps", "10", "--turntable", "3", "-o", o}, 2, "--frames FILE.gltf"},
        {{gltf, "--frames", still, "-o", o}, 1, "no animation"},
        {{modelPath("gltf/Avocado/Avocado.gltf").string(), "--frames", gltf, "-o", o}, 1,
         "the glTF's base mesh has 8 vertices, the input has 363"},
        {{cube, "--frames", gltf, "-o", o}, 1, "is not where the glTF's base mesh"},
        {{rest, "--frames", gltf, "-o", o}, 1, "is not where the glTF's base mesh"},
    };
    for (const auto& c : cases) {
        r = run(plus(plus({limnRender()}, c.args), {"--size", "32x24"}));
        EXPECT_EQ(r.exitCode, c.exit) << r.err;
        EXPECT_NE(r.err.find(c.words), std::string::npos) << r.err;
        EXPECT_EQ(filesIn(out.path()), (std::vector<std::string>{"AnimatedMorphCube.bin", "cube.obj", "rest.gltf"})) << r.err;
    }
}
