// Displacement (paper 000, 4.5) of the view-adaptive tessellation: adaptive_displace.comp
// samples the map at each emitted vertex's UV from its owner's seam record (the seam fix: both
// sides of a UV seam read the same texels), adaptive_displaced_normals.comp takes the normal of
// the displaced surface by differences around the vertex in its element's domain. Both run over
// the scan's vertex count (indirect dispatch).
#pragma once

#include "render/tessellation.h"

#include <memory>

namespace limn::render {

class AdaptiveTess;

// `draw` must hold seam records (draw.seams; the smooth UVs' records when it has them).
std::unique_ptr<DisplacementPasses> makeAdaptiveDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                             const SurfaceBuffers& surface, const AdaptiveTess& tess,
                                                             const DisplacementInputs& in);

} // namespace limn::render
