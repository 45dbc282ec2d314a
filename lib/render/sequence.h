// Sequences in one run: frame-numbered paths (-o shot_%04d.png, --frames
// walk_%04d.obj), the views of a turntable (--turntable N) and of a camera file (--cameras FILE).
// The renderer draws them one after another with the same tables and buffers; only the camera or
// the control points change between frames (paper 000: animation re-runs only the GPU passes).
#pragma once

#include "render/camera.h"

#include <cstdint>
#include <string>
#include <vector>

namespace limn::render {

// A path with one printf-style frame number in it: %d, or %0Nd (N = 1..9) for zero-padded
// numbers; %% is a literal %. Nothing else may follow a %.
struct FramePattern {
    std::string prefix, suffix; // around the number, %% already turned into %
    int width = 0;              // zero-padded to at least this many digits (0: no padding)
};

// Whether `text` holds a frame number conversion, %d or %0Nd (not written as %%d). A path
// without one is used literally, so a single image may still be called "100%.png".
bool hasFrameNumber(const std::string& text);
// Throws Error(Usage) naming `option` unless `text` has exactly one conversion.
FramePattern parseFramePattern(const std::string& option, const std::string& text);
std::string framePath(const FramePattern& pattern, uint64_t frame);

// The existing files a pattern names, by increasing frame number: those in the pattern's folder
// whose name is exactly framePath(pattern, n) for some n (so walk_%04d.obj takes walk_0007.obj,
// not walk_7.obj or walk_00007.obj). Throws Error(BadInput) when there is none, or more than
// kMaxFrames.
struct FrameFile {
    uint64_t number;
    std::string path;
};
inline constexpr size_t kMaxFrames = 100000;
std::vector<FrameFile> findFrameFiles(const FramePattern& pattern);

// n views around the up axis: base's azimuth + 360 k / n degrees, k = 0 .. n-1, base's elevation
// and field of view. Framing fits the bounding sphere, which every azimuth sees the same size,
// so the object does not change size from frame to frame.
std::vector<ViewSpec> turntableViews(const ViewSpec& base, uint32_t n);

// A camera file: one view per line, "EX EY EZ  TX TY TZ  UX UY UZ [FOV]" (eye, target, up, and
// the vertical field of view in degrees, default `defaultFovDeg`), numbers separated by spaces,
// tabs or commas; '#' starts a comment, blank lines are skipped. Throws Error(BadInput) naming
// the line for anything else: a wrong count, a non-finite number, eye = target, a zero or
// parallel up vector, a field of view outside 1..170, no view at all, more than kMaxFrames.
std::vector<ViewSpec> parseCameraFile(const std::string& text, double defaultFovDeg);

// Part of a sequence, for running one sequence as several processes (a Slurm job array, make -j,
// GNU parallel): every part frames, lights and views its frames exactly as the whole sequence
// does, so the parts' frames together are the one-process result, byte for byte.
//
// --shard I/N: part I of N, counted from 0 (Slurm: $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT
// of --array=0-(N-1)). Part I takes a contiguous block of the sequence's frames, positions
// floor(I*n/N) to floor((I+1)*n/N) - 1 of n: the parts differ by at most one frame, and a
// frame's neighbours (similar cost, the same files) stay together.
struct Shard {
    uint32_t index = 0, count = 1;
};
// Throws Error(Usage) naming `option` unless `text` is I/N in decimal digits with 0 <= I < N <=
// kMaxFrames (so 0/0, 5/4, -1/2, 1/2/3, " 1/2" and x/4 are refused).
Shard parseShard(const std::string& option, const std::string& text);

// --frame-range A-B: the frames numbered A to B, both included (frame numbers as in the output
// names: a turntable's view k is frame k, a --frames file keeps its number).
struct FrameRange {
    uint64_t first = 0, last = UINT64_MAX;
};
// Throws Error(Usage) naming `option` unless `text` is A-B in decimal digits with A <= B.
FrameRange parseFrameRange(const std::string& option, const std::string& text);

// The positions in `numbers` (a sequence's frame numbers, in order) that a run renders: those
// within `range`, then of those the shard's block. Throws Error(Usage) when that leaves no frame
// (more parts than frames, or a range that names none): a part with nothing to do is a mistake
// in the split, and it would have nothing to name in a depfile.
std::vector<size_t> framesOfPart(const std::vector<uint64_t>& numbers, const FrameRange& range, const Shard& shard);

} // namespace limn::render
