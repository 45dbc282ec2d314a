// The view-adaptive tessellation's options from the render settings: the rates' targets, which
// elements are culled, the per-frame buffers' budget.
#pragma once

#include "render/adaptive/adaptive_tess.h"
#include "render/renderer.h"

namespace limn::render {

// `draw` prepared with adaptive = true; the image drawn is drawWidth x drawHeight pixels
// (supersampled); `standardSampleLocations`: the device uses Vulkan's standard 4-sample pattern.
AdaptiveOptions adaptiveOptions(const RenderSettings& settings, const SubdivisionDraw& draw, uint32_t drawWidth,
                                uint32_t drawHeight, bool standardSampleLocations);

} // namespace limn::render
