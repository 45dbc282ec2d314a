#include "render/adaptive/adaptive_options.h"

#include <algorithm>

namespace limn::render {

AdaptiveOptions adaptiveOptions(const RenderSettings& settings, const SubdivisionDraw& draw, uint32_t drawWidth,
                                uint32_t drawHeight, bool standardSampleLocations) {
    AdaptiveOptions adaptive;
    adaptive.edgePixels = static_cast<float>(settings.edgePixels);
    adaptive.maxError = static_cast<float>(settings.maxError);
    adaptive.tess = settings.tessCap;
    // Displacement moves the surface off its control points' hull: no culling then (it
    // would have to widen every test by the largest displacement).
    adaptive.cull = settings.cull && !settings.displacementMap;
    adaptive.backFaceCull = adaptive.cull && !settings.backFaceColor;
    if (adaptive.cull && settings.sampleCull && settings.wire == Wire::None) {
        // Positions within a pixel counted from the image's bottom left (the cull measures
        // NDC upwards; gpu::CommandBuffer draws with a y-flipped viewport): Vulkan's standard
        // 4-sample pattern (x, y), counted from the top left, is at (x, 1 - y) here.
        if (settings.samples == 1)
            adaptive.samplePositions = {{0.5f, 0.5f}};
        else if (settings.samples == 4 && standardSampleLocations)
            adaptive.samplePositions = {{0.375f, 0.875f}, {0.875f, 0.625f}, {0.125f, 0.375f}, {0.625f, 0.125f}};
    }
    adaptive.sharePoints = settings.sharePoints && settings.shade != Shade::Uv && settings.shade != Shade::Texture &&
                           !settings.evaluateVertices && settings.wire == Wire::None && !settings.displacementMap;
    // Per-pixel normals: the lit shading from the vertex stage's draw only (the evaluated
    // pipeline binds the evaluated vertices instead of the surface), each element's own vertices.
    adaptive.pixelNormals = settings.pixelNormals && settings.shade == Shade::Lit && !settings.evalInCompute &&
                            !settings.evaluateVertices && settings.wire == Wire::None && !settings.displacementMap;
    if (adaptive.pixelNormals) adaptive.sharePoints = false;
    adaptive.interiorError = static_cast<float>(settings.interiorError);
    if (settings.displacementMap) // at least a segment per texel, up to one per 2 pixels
        adaptive.texelsPerUV = float(std::max(settings.displacementMap->width, settings.displacementMap->height));
    // Per-frame buffers: every element at its smallest (whole-surface --mesh-out), plus
    // a budget for the view: about 2 triangles per P x P pixels seen, with room for back
    // faces, off-screen parts and rounding (x32), at least 2^20. With the error
    // estimate, P is at most 4 (segments within 0.25 px of a curve are shorter only
    // where its radius is under 8 px).
    uint64_t minimum = 0;
    for (const auto& e : draw.pieces.elements)
        for (int k = 0; k < 4; ++k) minimum += e.sideCount[k];
    const double p = std::max(settings.maxError > 0 ? std::min(settings.edgePixels, 4.0) : settings.edgePixels, 0.25);
    const uint64_t view =
        std::max<uint64_t>(uint64_t(32.0 * drawWidth * drawHeight / (p * p)), uint64_t(1) << 20);
    adaptive.maxVertices = minimum + draw.pieces.elements.size() + view;
    adaptive.maxTriangles = minimum + 2 * view;
    return adaptive;
}

} // namespace limn::render
