// Which sequence a limn-render run renders (--turntable N, --cameras FILE, --frames PATTERN: one
// at most) and the numbers of its frames, which name its output files. Checked before any work;
// every refusal is an Error(Usage) with the message the tool prints.
#pragma once

#include "render/camera.h"
#include "render/sequence.h"

#include <cstdint>
#include <vector>

namespace limn::render {

struct SequenceRequest {
    uint32_t turntable = 0; // --turntable N (0: none)
    bool cameras = false;   // --cameras FILE
    bool frames = false;    // --frames PATTERN (or FILE.gltf|.glb)
    bool animation = false; // --frames names a glTF's morph-target animation
    bool fps = false;       // --fps N
    bool eye = false;       // --eye (an explicit camera)
    bool view = false;      // --view
    bool bench = false;     // --bench
    bool part = false;      // --shard or --frame-range
};

// Whether the run is a sequence. Throws Error(Usage) when more than one kind is asked for, for
// --turntable with --eye (it turns the --view camera), --cameras with --view or --eye (the file
// gives every camera), a sequence with --bench (which measures one frame), and --shard or
// --frame-range without a sequence, and --fps without a glTF animation to sample.
bool planSequence(const SequenceRequest& request);

// Whether --frames names one glTF file (its morph-target animation: .gltf or .glb, no frame
// number) rather than a pattern of mesh files.
bool isAnimationFile(const std::string& frames);
// --fps N: frames per second, 0 < N <= kMaxFps; throws Error(Usage) naming `option` otherwise.
inline constexpr double kMaxFps = 1000;
double parseFps(const std::string& option, const std::string& text);

// The frame numbers: 0 .. n-1 for n views (a turntable or a camera file) or n frames of a glTF
// animation (`animationFrames`), else the numbers of the --frames files, in their order.
std::vector<uint64_t> sequenceFrameNumbers(const std::vector<ViewSpec>& views,
                                           const std::vector<FrameFile>& frameFiles, size_t animationFrames = 0);

} // namespace limn::render
