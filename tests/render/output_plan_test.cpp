// What limn-render writes and which sequence it renders, decided from the options alone
// (lib/render/output_plan.h, sequence_plan.h): the rules of limn-render --help, without a device.
#include "render/output_plan.h"
#include "render/sequence_plan.h"

#include "base/error.h"

#include <gtest/gtest.h>

#include <functional>

using namespace limn;
using namespace limn::render;

namespace {

// The message of the Error(Usage) that `f` throws ("" when it throws none, or another kind).
std::string usageMessage(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        if (e.kind() == ErrorKind::Usage) return e.what();
        ADD_FAILURE() << "not a usage error: " << e.what();
    }
    return "";
}

} // namespace

TEST(OutputPlan, ImageGoesToStandardOutputByDefault) {
    const OutputPlan p = planOutputs({});
    EXPECT_TRUE(p.writeImage);
    EXPECT_EQ(p.image, "-");
    EXPECT_EQ(p.imageFormat, ImageFormat::Png);
    EXPECT_FALSE(p.meshFormat);
}

TEST(OutputPlan, FormatFollowsTheExtension) {
    EXPECT_EQ(planOutputs({.image = "still.EXR"}).imageFormat, ImageFormat::Exr);
    EXPECT_EQ(planOutputs({.image = "a.png"}).imageFormat, ImageFormat::Png);
    // A device is a stream like standard output: PNG whatever its name.
    EXPECT_EQ(planOutputs({.image = "/dev/null"}).imageFormat, ImageFormat::Png);
    EXPECT_NE(usageMessage([] { planOutputs({.image = "a.jpg"}); }).find("unknown image extension"),
              std::string::npos);
}

TEST(OutputPlan, MeshOutAloneWritesNoImage) {
    const OutputPlan p = planOutputs({.mesh = "drawn.glb"});
    EXPECT_FALSE(p.writeImage);
    EXPECT_EQ(p.meshFormat, exporting::ExportFormat::Glb);
    EXPECT_EQ(p.meshFileKind(), OutputFile::Kind::Binary);
    const OutputPlan both = planOutputs({.image = "a.png", .mesh = "drawn.obj"});
    EXPECT_TRUE(both.writeImage);
    EXPECT_EQ(both.meshFileKind(), OutputFile::Kind::Text);
    EXPECT_EQ(planOutputs({.mesh = "a.ply", .meshAscii = true}).meshFileKind(), OutputFile::Kind::Text);
    EXPECT_EQ(planOutputs({.mesh = "a.ply"}).meshFileKind(), OutputFile::Kind::Binary);
    EXPECT_EQ(planOutputs({.mesh = "a.gltf"}).meshFileKind(), OutputFile::Kind::Text);
}

TEST(OutputPlan, BenchWritesAnImageOnlyWithAFile) {
    EXPECT_FALSE(planOutputs({.bench = true}).writeImage);
    EXPECT_TRUE(planOutputs({.image = "b.png", .bench = true}).writeImage);
    EXPECT_EQ(usageMessage([] { planOutputs({.image = "-", .bench = true}); }),
              "--bench prints JSON on standard output; write the image with -o FILE");
}

TEST(OutputPlan, StandardOutputIsNotShared) {
    const std::string shared = "--mesh-out - and the image (or --bench JSON) cannot share standard output";
    EXPECT_EQ(usageMessage([] { planOutputs({.image = "-", .mesh = "-"}); }), shared);
    EXPECT_EQ(usageMessage([] { planOutputs({.mesh = "-", .bench = true}); }), shared);
    // The mesh alone on standard output is PLY.
    EXPECT_EQ(planOutputs({.mesh = "-"}).meshFormat, exporting::ExportFormat::Ply);
}

TEST(OutputPlan, MeshOptionsRefused) {
    EXPECT_NE(usageMessage([] { planOutputs({.mesh = "a.stl"}); }).find("--mesh-out: unknown extension"),
              std::string::npos);
    EXPECT_EQ(usageMessage([] { planOutputs({.mesh = "a.obj", .meshAscii = true}); }),
              "--mesh-ascii applies to a .ply --mesh-out, not a.obj");
    EXPECT_EQ(usageMessage([] { planOutputs({.meshAscii = true}); }),
              "--mesh-ascii applies to a .ply --mesh-out; give --mesh-out FILE.ply");
}

TEST(OutputPlan, BitDepthNeedsAPng) {
    EXPECT_EQ(usageMessage([] { planOutputs({.image = "a.exr", .bitDepthGiven = true}); }),
              "--bit-depth sets PNG samples; an .exr is always 32-bit float");
    EXPECT_EQ(usageMessage([] { planOutputs({.mesh = "a.ply", .bitDepthGiven = true}); }),
              "--bit-depth applies to the image, and none is written");
    EXPECT_TRUE(planOutputs({.image = "a.png", .bitDepthGiven = true}).writeImage);
}

TEST(OutputPlan, SequenceNamesEveryFrame) {
    const OutputPlan p = planOutputs({.image = "out/shot_%04d.png", .mesh = "m_%d.obj", .sequence = true});
    EXPECT_EQ(p.framePaths({0, 12}),
              (std::vector<std::string>{"out/shot_0000.png", "m_0.obj", "out/shot_0012.png", "m_12.obj"}));
    EXPECT_EQ(planOutputs({.image = "v%02d.png", .sequence = true}).framePaths({3}),
              std::vector<std::string>{"v03.png"});
    const std::string needsPattern = "a sequence writes one image per frame: give -o NAME_%04d.png";
    EXPECT_EQ(usageMessage([] { planOutputs({.sequence = true}); }), needsPattern);
    EXPECT_EQ(usageMessage([] { planOutputs({.image = "-", .sequence = true}); }), needsPattern);
    EXPECT_NE(usageMessage([] { planOutputs({.image = "shot.png", .sequence = true}); }).find("-o: "),
              std::string::npos);
    EXPECT_NE(usageMessage([] { planOutputs({.image = "s%d.png", .mesh = "m.obj", .sequence = true}); })
                  .find("--mesh-out: "),
              std::string::npos);
}

TEST(OutputPlan, OneImageHasNoFrameNumber) {
    EXPECT_NE(usageMessage([] { planOutputs({.image = "shot_%04d.png"}); }).find("numbers frames"),
              std::string::npos);
    EXPECT_NE(usageMessage([] { planOutputs({.image = "a.png", .mesh = "m%d.ply"}); }).find("numbers frames"),
              std::string::npos);
    // %% is a literal %.
    EXPECT_TRUE(planOutputs({.image = "100%%.png"}).writeImage);
}

TEST(SequencePlan, OneKindAtMost) {
    EXPECT_FALSE(planSequence({}));
    EXPECT_TRUE(planSequence({.turntable = 8}));
    EXPECT_TRUE(planSequence({.cameras = true}));
    EXPECT_TRUE(planSequence({.frames = true, .eye = true, .view = true}));
    EXPECT_EQ(usageMessage([] { planSequence({.turntable = 8, .frames = true}); }),
              "--turntable, --cameras and --frames exclude each other");
    EXPECT_EQ(usageMessage([] { planSequence({.cameras = true, .frames = true}); }),
              "--turntable, --cameras and --frames exclude each other");
}

TEST(SequencePlan, CamerasComeFromOnePlace) {
    EXPECT_NE(usageMessage([] { planSequence({.turntable = 4, .eye = true}); }).find("leave out --eye"),
              std::string::npos);
    EXPECT_TRUE(planSequence({.turntable = 4, .view = true})); // turns the --view camera
    EXPECT_NE(usageMessage([] { planSequence({.cameras = true, .view = true}); }).find("leave out --view"),
              std::string::npos);
    EXPECT_NE(usageMessage([] { planSequence({.cameras = true, .eye = true}); }).find("leave out --view"),
              std::string::npos);
    EXPECT_NE(usageMessage([] { planSequence({.turntable = 2, .bench = true}); }).find("--bench measures one frame"),
              std::string::npos);
    EXPECT_FALSE(planSequence({.bench = true}));
}

TEST(SequencePlan, FrameNumbers) {
    EXPECT_EQ(sequenceFrameNumbers(std::vector<ViewSpec>(3), {}), (std::vector<uint64_t>{0, 1, 2}));
    EXPECT_EQ(sequenceFrameNumbers({}, {{7, "w_0007.obj"}, {9, "w_0009.obj"}}), (std::vector<uint64_t>{7, 9}));
    EXPECT_TRUE(sequenceFrameNumbers({}, {}).empty());
}

// A sequence's size before any work: images uncompressed (RGB or RGBA, 1 or 2 bytes a sample; EXR
// five 32-bit floats a pixel), meshes at 24 bytes a control-mesh triangle.
TEST(OutputPlan, FrameBytesAreEstimatedFromTheImageAndTheMesh) {
    const OutputPlan png = planOutputs({.image = "f_%d.png", .sequence = true});
    EXPECT_EQ(estimateFrameBytes(png, {.width = 320, .height = 240}), 320u * 240 * 3);
    EXPECT_EQ(estimateFrameBytes(png, {.width = 320, .height = 240, .alpha = true, .bitDepth = 16}),
              320u * 240 * 4 * 2);
    const OutputPlan exr = planOutputs({.image = "f_%d.exr", .sequence = true});
    EXPECT_EQ(estimateFrameBytes(exr, {.width = 10, .height = 10}), 10u * 10 * 5 * 4);
    EXPECT_EQ(estimateFrameBytes(png, {.width = 1, .height = 1, .meshTriangles = 100}), 3u); // no --mesh-out
    const OutputPlan meshes = planOutputs({.image = "f_%d.png", .mesh = "m_%d.ply", .sequence = true});
    EXPECT_EQ(estimateFrameBytes(meshes, {.width = 1, .height = 1, .meshTriangles = 100}), 3u + 100 * 24);
}

TEST(SequencePlan, GltfAnimationAndFps) {
    EXPECT_TRUE(isAnimationFile("cube.gltf"));
    EXPECT_TRUE(isAnimationFile("dir/Cube.GLB"));
    EXPECT_FALSE(isAnimationFile("walk_%04d.gltf")); // a pattern of mesh files
    EXPECT_FALSE(isAnimationFile("cube.obj"));
    EXPECT_EQ(parseFps("--fps", "24"), 24.0);
    EXPECT_EQ(parseFps("--fps", "1000"), 1000.0);
    for (const char* bad : {"0", "-1", "1000.5", "nan", "x"})
        EXPECT_NE(usageMessage([&] { parseFps("--fps", bad); }).find("--fps"), std::string::npos) << bad;
    EXPECT_TRUE(planSequence({.frames = true, .animation = true, .fps = true}));
    EXPECT_NE(usageMessage([] { planSequence({.frames = true, .fps = true}); }).find("--frames FILE.gltf"),
              std::string::npos);
    EXPECT_EQ(sequenceFrameNumbers({}, {}, 3), (std::vector<uint64_t>{0, 1, 2}));
}
