// Frame patterns, input frame discovery, turntable views and camera files (lib/render/sequence).
#include "render/sequence.h"

#include "base/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace limn;
using namespace limn::render;

namespace {

ErrorKind kindOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.kind();
    }
    ADD_FAILURE() << "no error thrown";
    return ErrorKind::BadInput;
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return std::string(e.what()) + " @ " + e.where();
    }
    return "";
}

void touch(const std::filesystem::path& p) { std::ofstream(p) << "x"; }

} // namespace

TEST(FramePattern, PaddedPlainAndLiteralPercent) {
    EXPECT_EQ(framePath(parseFramePattern("-o", "shot_%04d.png"), 7), "shot_0007.png");
    EXPECT_EQ(framePath(parseFramePattern("-o", "shot_%04d.png"), 123456), "shot_123456.png");
    EXPECT_EQ(framePath(parseFramePattern("-o", "f%d.png"), 0), "f0.png");
    EXPECT_EQ(framePath(parseFramePattern("-o", "100%%_%02d.png"), 3), "100%_03.png");
    EXPECT_TRUE(hasFrameNumber("a_%04d.png"));
    EXPECT_TRUE(hasFrameNumber("a_%d.png"));
    EXPECT_FALSE(hasFrameNumber("100%%d.png"));
    EXPECT_FALSE(hasFrameNumber("100%.png"));
    EXPECT_FALSE(hasFrameNumber("a_%4d.png"));
    EXPECT_FALSE(hasFrameNumber("plain.png"));
}

TEST(FramePattern, RefusesWhatPrintfWouldMisread) {
    for (const char* bad : {"plain.png", "a_%s.png", "a_%4d.png", "a_%00d.png", "a_%d_%d.png", "a_%", "a_%0",
                            "a_%05", "100%%.png"}) {
        EXPECT_EQ(kindOf([&] { parseFramePattern("-o", bad); }), ErrorKind::Usage) << bad;
        EXPECT_NE(messageOf([&] { parseFramePattern("-o", bad); }).find("-o:"), std::string::npos) << bad;
    }
}

TEST(FrameFiles, ExactNamesInNumberOrder) {
    test::ScratchDir dir;
    for (const char* name : {"walk_0010.obj", "walk_0002.obj", "walk_0001.obj", "walk_7.obj", "walk_00003.obj",
                             "walk_0004.obj.bak", "run_0005.obj", "walk_abcd.obj"})
        touch(dir / name);
    std::filesystem::create_directory(dir / "walk_0006.obj"); // a folder, not a frame
    const auto files = findFrameFiles(parseFramePattern("--frames", (dir / "walk_%04d.obj").string()));
    ASSERT_EQ(files.size(), 3u);
    EXPECT_EQ(files[0].number, 1u);
    EXPECT_EQ(files[1].number, 2u);
    EXPECT_EQ(files[2].number, 10u);
    EXPECT_EQ(files[2].path, (dir / "walk_0010.obj").string());
    // Unpadded: walk_7.obj, and not the zero-padded names.
    const auto plain = findFrameFiles(parseFramePattern("--frames", (dir / "walk_%d.obj").string()));
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_EQ(plain[0].number, 7u);
}

TEST(FrameFiles, NoneOrMissingFolderIsBadInput) {
    test::ScratchDir dir;
    EXPECT_EQ(kindOf([&] { findFrameFiles(parseFramePattern("--frames", (dir / "none_%04d.obj").string())); }),
              ErrorKind::BadInput);
    EXPECT_EQ(kindOf([&] { findFrameFiles(parseFramePattern("--frames", (dir / "no/such/x_%d.obj").string())); }),
              ErrorKind::BadInput);
    EXPECT_EQ(kindOf([&] { findFrameFiles(parseFramePattern("--frames", (dir / "f%d/x.obj").string())); }),
              ErrorKind::Usage);
}

TEST(Turntable, EvenAzimuthsSameElevation) {
    ViewSpec base;
    base.azimuthDeg = 30, base.elevationDeg = 20;
    const auto views = turntableViews(base, 36);
    ASSERT_EQ(views.size(), 36u);
    for (size_t k = 0; k < views.size(); ++k) {
        EXPECT_DOUBLE_EQ(views[k].azimuthDeg, std::fmod(30.0 + 10.0 * double(k), 360.0));
        EXPECT_EQ(views[k].elevationDeg, 20);
        EXPECT_FALSE(views[k].eye);
    }
    EXPECT_EQ(turntableViews(base, 1).size(), 1u);
}

TEST(CameraFile, ViewsCommentsAndSeparators) {
    const auto views = parseCameraFile("# eye target up fov\n"
                                       "0 0 5  0 0 0  0 1 0\n"
                                       "\n"
                                       "1,2,3, 0,0,0, 0,0,1, 50 # a wide one\r\n"
                                       "\t-4\t0\t0\t0 0 0 0 1 0\n",
                                       35);
    ASSERT_EQ(views.size(), 3u);
    EXPECT_EQ(*views[0].eye, glm::dvec3(0, 0, 5));
    EXPECT_EQ(views[0].fovDeg, 35);
    EXPECT_EQ(*views[1].up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(views[1].fovDeg, 50);
    EXPECT_EQ(*views[2].eye, glm::dvec3(-4, 0, 0));
}

TEST(CameraFile, BadLinesNamed) {
    const std::pair<const char*, const char*> cases[] = {
        {"0 0 5 0 0 0 0 1\n", "9 or 10 numbers"},
        {"0 0 5 0 0 0 0 1 0 35 1\n", "9 or 10 numbers"},
        {"0 0 5 0 0 0 0 1 0 x\n", "not a finite number"},
        {"0 0 5 0 0 0 0 1 0 nan\n", "not a finite number"},
        {"0 0 5 0 0 0 0 1 0 1e999\n", "not a finite number"},
        {"1 1 1 1 1 1 0 1 0\n", "same point"},
        {"0 0 5 0 0 0 0 0 0\n", "up vector is zero"},
        {"0 5 0 0 0 0 0 1 0\n", "parallel"},
        {"0 0 1e39 0 0 0 0 1 0\n", "beyond the 1e18"},
        {"0 0 5 0 0 0 1e300 1e300 0\n", "beyond the 1e18"},
        {"0 0 5 0 0 0 0 1 0 0.5\n", "field of view"},
        {"0 0 5 0 0 0 0 1 0 171\n", "field of view"},
        {"# only comments\n\n", "no camera"},
    };
    for (const auto& [text, words] : cases) {
        EXPECT_EQ(kindOf([&] { parseCameraFile(text, 35); }), ErrorKind::BadInput) << text;
        const std::string m = messageOf([&] { parseCameraFile(text, 35); });
        EXPECT_NE(m.find(words), std::string::npos) << text << " -> " << m;
    }
    EXPECT_NE(messageOf([&] { parseCameraFile("0 0 5 0 0 0 0 1 0\n\n0 0 5 0 0 0 0 1\n", 35); }).find("line 3"),
              std::string::npos);
}

// --shard and --frame-range: a part of a sequence as the same frames the whole run renders.
TEST(Shard, BadShardsAreUsageErrors) {
    for (const char* bad : {"0/0", "5/4", "4/4", "-1/2", "1/-2", "+1/2", "a/4", "1/b", "1", "1/", "/4", "1/2/3",
                            " 1/2", "1/2 ", "1.0/2", "0x1/2", "", "0/100001", "99999999999999999999/2"}) {
        EXPECT_EQ(kindOf([&] { parseShard("--shard", bad); }), ErrorKind::Usage) << bad;
        EXPECT_NE(messageOf([&] { parseShard("--shard", bad); }).find("--shard:"), std::string::npos) << bad;
    }
    const Shard s = parseShard("--shard", "3/4");
    EXPECT_EQ(s.index, 3u);
    EXPECT_EQ(s.count, 4u);
    EXPECT_EQ(parseShard("--shard", "0/1").count, 1u);
    EXPECT_EQ(parseShard("--shard", "007/100000").index, 7u);
}

TEST(Shard, BadRangesAreUsageErrors) {
    for (const char* bad : {"5-4", "-1-2", "1", "1-", "-3", "a-b", "1-2-3", "1 - 2", "1.5-2", ""})
        EXPECT_EQ(kindOf([&] { parseFrameRange("--frame-range", bad); }), ErrorKind::Usage) << bad;
    const FrameRange r = parseFrameRange("--frame-range", "12-12");
    EXPECT_EQ(r.first, 12u);
    EXPECT_EQ(r.last, 12u);
}

// Every split of every length: the parts are contiguous, in order, disjoint, cover the frames,
// and differ in size by at most one frame.
TEST(Shard, PartsPartitionTheFrames) {
    for (uint64_t n = 1; n <= 40; ++n) {
        std::vector<uint64_t> numbers;
        for (uint64_t k = 0; k < n; ++k) numbers.push_back(100 + 3 * k); // --frames: any numbers
        for (uint32_t parts = 1; parts <= n; ++parts) {
            std::vector<size_t> all;
            size_t smallest = n, largest = 0;
            for (uint32_t i = 0; i < parts; ++i) {
                const auto part = framesOfPart(numbers, FrameRange{}, Shard{i, parts});
                ASSERT_FALSE(part.empty()) << i << "/" << parts << " of " << n;
                for (size_t j = 1; j < part.size(); ++j) EXPECT_EQ(part[j], part[j - 1] + 1);
                all.insert(all.end(), part.begin(), part.end());
                smallest = std::min(smallest, part.size());
                largest = std::max(largest, part.size());
            }
            ASSERT_EQ(all.size(), n) << parts << " parts of " << n;
            for (size_t k = 0; k < n; ++k) EXPECT_EQ(all[k], k) << parts << " parts of " << n;
            EXPECT_LE(largest - smallest, 1u) << parts << " parts of " << n;
        }
    }
    // 10 frames in 4 parts: 2, 3, 2, 3 (floor(10 i / 4)).
    const std::vector<uint64_t> ten = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    EXPECT_EQ(framesOfPart(ten, {}, {0, 4}), (std::vector<size_t>{0, 1}));
    EXPECT_EQ(framesOfPart(ten, {}, {1, 4}), (std::vector<size_t>{2, 3, 4}));
    EXPECT_EQ(framesOfPart(ten, {}, {3, 4}), (std::vector<size_t>{7, 8, 9}));
}

TEST(Shard, RangeSelectsByFrameNumberThenShardsSplitIt) {
    const std::vector<uint64_t> numbers = {3, 5, 8, 13, 21, 34}; // a --frames sequence's file numbers
    EXPECT_EQ(framesOfPart(numbers, {5, 21}, {}), (std::vector<size_t>{1, 2, 3, 4}));
    EXPECT_EQ(framesOfPart(numbers, {6, 8}, {}), (std::vector<size_t>{2}));
    EXPECT_EQ(framesOfPart(numbers, {0, 1000}, {}), (std::vector<size_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(framesOfPart(numbers, {5, 21}, {1, 2}), (std::vector<size_t>{3, 4}));
    // Nothing to render is a usage error naming the option: a range between numbers, more parts
    // than frames.
    EXPECT_EQ(kindOf([&] { framesOfPart(numbers, {9, 12}, {}); }), ErrorKind::Usage);
    EXPECT_NE(messageOf([&] { framesOfPart(numbers, {9, 12}, {}); }).find("--frame-range"), std::string::npos);
    EXPECT_EQ(kindOf([&] { framesOfPart(numbers, {}, {6, 7}); }), ErrorKind::Usage);
    EXPECT_NE(messageOf([&] { framesOfPart(numbers, {}, {6, 7}); }).find("--shard"), std::string::npos);
    EXPECT_EQ(kindOf([&] { framesOfPart(numbers, {5, 8}, {0, 3}); }), ErrorKind::Usage);
}
