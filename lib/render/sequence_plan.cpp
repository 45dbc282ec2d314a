#include "render/sequence_plan.h"

#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "mesh/import.h"

namespace limn::render {

bool planSequence(const SequenceRequest& request) {
    const int sequenceOptions = (request.turntable > 0) + request.cameras + request.frames;
    const bool sequence = sequenceOptions > 0;
    if (sequenceOptions > 1) throwUsage("--turntable, --cameras and --frames exclude each other");
    if (request.turntable && request.eye)
        throwUsage("--turntable turns the --view camera around the up axis; leave out --eye");
    if (request.cameras && (request.eye || request.view))
        throwUsage("--cameras gives every frame's camera; leave out --view and --eye");
    if (sequence && request.bench) throwUsage("--bench measures one frame; leave out --turntable, --cameras and --frames");
    if (request.fps && !request.animation)
        throwUsage("--fps samples a glTF's morph-target animation; give --frames FILE.gltf (or .glb)");
    if (request.part && !sequence)
        throwUsage("--shard and --frame-range render part of a sequence; give --turntable, --cameras or --frames");
    return sequence;
}

bool isAnimationFile(const std::string& frames) {
    if (hasFrameNumber(frames)) return false;
    const MeshFormat format = formatFromExtension(extensionOf(frames));
    return format == MeshFormat::Gltf || format == MeshFormat::Glb;
}

double parseFps(const std::string& option, const std::string& text) {
    const std::vector<double> v = cli::parseNumberList(option, text, 1);
    if (!(v[0] > 0 && v[0] <= kMaxFps))
        throwUsage(option + ": '" + text + "' is not a number of frames per second above 0 and at most " +
              std::to_string(int(kMaxFps)));
    return v[0];
}

std::vector<uint64_t> sequenceFrameNumbers(const std::vector<ViewSpec>& views,
                                           const std::vector<FrameFile>& frameFiles, size_t animationFrames) {
    std::vector<uint64_t> numbers;
    for (size_t k = 0; k < views.size(); ++k) numbers.push_back(k);
    for (size_t k = 0; k < animationFrames; ++k) numbers.push_back(k);
    for (const auto& f : frameFiles) numbers.push_back(f.number);
    return numbers;
}

} // namespace limn::render
