// The seam between the subdivision surface's passes and its tessellation: which (element, s, t)
// vertices and triangles the draw reads, the passes that write them each frame, the passes that
// displace them (paper 000, 4.5), and how the evaluation and the draws are sized (by the host
// for the fixed grids, by a compute pass through indirect arguments for the view-adaptive
// tessellation). Two implementations:
//
//   FixedGrids    (fixed_grids.h)            2^(N-l) segments per side of a level-l patch
//                                            (paper 000, 4.3), uploaded once
//   AdaptiveTess  (adaptive/adaptive_tess.h) segments chosen from the camera every frame
//
// SubdivisionPass (subdivision_pass.h) computes the table vertices and limit points, evaluates
// and draws; it asks this interface everything that depends on which tessellation it draws.
#pragma once

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "export/ply.h"
#include "image/image_file.h"
#include "render/frame_pass.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace limn::render {

struct SubdivisionDraw;
struct AdaptiveView;
struct AdaptiveTotals;

// The surface's buffers that SubdivisionPass owns and the tessellations' passes read (table
// vertices, patches, irregular faces, limit points); they outlive the tessellation.
struct SurfaceBuffers {
    const gpu::Buffer &vertices, &patches, &irregular, &limits;
};

// Displacement along the limit normal (paper 000, 4.5): every drawn vertex moves by
// scale * (sample - mid); the draw then reads positions() and normals().
class DisplacementPasses {
  public:
    virtual ~DisplacementPasses() = default;
    // "displace" then "displaced normals", each timed, after a barrier on the evaluation.
    virtual void record(gpu::CommandBuffer& cmd, TimedPasses& timed) = 0;
    virtual const gpu::Buffer& positions() const = 0;
    virtual const gpu::Buffer& normals() const = 0;
    virtual uint64_t bufferBytes() const = 0;
};

// What a displacement pass needs from the pass: the map and the evaluated surface.
struct DisplacementInputs {
    const FloatImage& map; // channel 0 is the height
    float scale, mid;
    const gpu::Buffer &evaluatedPositions, &evaluatedNormals;
    uint64_t vertexCapacity; // slots of the evaluated buffers
};

// The displacement map for displace.comp and adaptive_displace.comp: width, height, then
// channel 0 of each texel.
std::vector<uint32_t> displacementMapWords(const FloatImage& img);

class Tessellation {
  public:
    virtual ~Tessellation() = default;

    // The draw's inputs: (element, s, t) vertices, triangle indices, each triangle's level.
    virtual const gpu::Buffer& tessVertices() const = 0;
    virtual const gpu::Buffer& triangles() const = 0;
    virtual const gpu::Buffer& triangleLevels() const = 0;
    // Slots of the tessellation vertices: the size of the evaluated (and displaced) buffers.
    virtual uint64_t vertexCapacity() const = 0;

    // The frame's tessellation passes, after the limit points (none for fixed grids).
    virtual void record(gpu::CommandBuffer& cmd, TimedPasses& timed, const AdaptiveView& view) = 0;
    // Runs `pipeline` once per tessellation vertex (surface_eval.comp).
    virtual void dispatchPerVertex(gpu::CommandBuffer& cmd, const gpu::ComputePipeline& pipeline,
                                   const gpu::BindGroup& bindings, std::span<const uint8_t> push) const = 0;
    // Draws the triangles; `pullIndices`: non-indexed, the vertex stage reads the indices itself
    // (--shade levels, which needs the triangle's number).
    virtual void drawTriangles(gpu::CommandBuffer& cmd, const gpu::GraphicsPipeline& pipeline,
                               const gpu::BindGroup& bindings, std::span<const uint8_t> push,
                               bool pullIndices) const = 0;
    // Draws the lines of `wire` (Outlines: the fixed grids' patch and face outlines through the
    // `outlines` pipeline; Triangles: every triangle's edges through `triangleEdges`).
    struct WirePipelines {
        const gpu::GraphicsPipeline& outlines;
        const gpu::BindGroup& outlineBindings;
        const gpu::GraphicsPipeline& triangleEdges;
        const gpu::BindGroup& triangleEdgeBindings;
    };
    virtual void drawWire(gpu::CommandBuffer& cmd, Wire wire, const WirePipelines& pipelines,
                          std::span<const uint8_t> push) const = 0;

    // The displacement passes of this tessellation.
    virtual std::unique_ptr<DisplacementPasses> makeDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                                 const SurfaceBuffers& surface,
                                                                 const DisplacementInputs& in) const = 0;

    // The last frame's totals (null for the fixed grids; read back once per frame).
    virtual const AdaptiveTotals* lastTotals(gpu::Context& ctx) const = 0;
    // Why the last frame left parts of the surface out, with what to do; empty when it did not.
    virtual std::string shortfall(gpu::Context& ctx) const = 0;
    // Vertices the drawn mesh holds (--mesh-out); throws on a shortfall.
    virtual size_t drawnVertexCount(gpu::Context& ctx) const = 0;
    // Fills in the drawn mesh's texture UVs (when the surface has them) and its triangles.
    virtual void finishDrawnMesh(gpu::Context& ctx, exporting::DrawnMesh& out) const = 0;
    // Triangles drawn in the last frame (view-adaptive: after culling).
    virtual uint64_t triangleCount(gpu::Context& ctx) const = 0;
    // Tessellation vertices evaluated, plus any points that decided the rates.
    virtual uint64_t verticesEvaluated(gpu::Context& ctx) const = 0;
    virtual uint64_t bufferBytes() const = 0;
};

} // namespace limn::render
