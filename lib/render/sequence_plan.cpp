#include "render/sequence_plan.h"

#include "base/error.h"

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
    if (request.part && !sequence)
        throwUsage("--shard and --frame-range render part of a sequence; give --turntable, --cameras or --frames");
    return sequence;
}

std::vector<uint64_t> sequenceFrameNumbers(const std::vector<ViewSpec>& views,
                                           const std::vector<FrameFile>& frameFiles) {
    std::vector<uint64_t> numbers;
    for (size_t k = 0; k < views.size(); ++k) numbers.push_back(k);
    for (const auto& f : frameFiles) numbers.push_back(f.number);
    return numbers;
}

} // namespace limn::render
