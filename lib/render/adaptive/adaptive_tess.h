// View-adaptive tessellation on the GPU: instead of a fixed grid of 2^(N-l) segments
// per side of a level-l patch (paper 000, 4.3), every frame five compute passes decide from the
// camera how finely each edge piece (lib/tess/edge_pieces.h) is cut, and write the tessellation
// that the draw then reads through one drawIndexedIndirect:
//
//   adaptive_cull.comp    per element: outside the frustum, facing away, or between the
//                         image's samples? (hull of its Bezier points; it draws nothing then)
//   adaptive_rates.comp   per edge piece: the fewest segments within --max-error pixels of the
//                         surface, none longer than --edge-pixels, clamped to 1..--tess (from
//                         the piece owner's surface only)
//   adaptive_counts.comp  per element: interior rates (or flat: its boundary only, less the
//                         fan triangles that hold no sample), vertex and triangle counts
//   adaptive_scan.comp    one workgroup: deterministic prefix sums -> offsets, indirect args
//   adaptive_emit.comp    per element: its (element, s, t) vertices and its triangles
//
// Everything stays inside WebGPU: compute + vertex/fragment, storage buffers <= 128 MiB (the
// per-frame buffers are sized to a budget below that and the host is told when a frame did not
// fit), workgroups <= 256, no float64, one indirect draw. Topology is uploaded once; a moving
// camera re-runs only these passes.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "render/frame_pass.h"
#include "render/subdivision_draw.h"
#include "render/tessellation.h"
#include "tess/edge_pieces.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace limn::render {

struct GpuAdaptiveElement { // mirrors AdaptiveElement in shaders/adaptive_tess.glsl
    uint32_t sideFirst[4], sideCount[4]; // into the edge-pieces buffer (after its pieces and points)
    float uv[8];
    uint32_t level;
    uint32_t crease; // a single-crease patch's crease side (TBLS's crease bit: 1 t=0, 2 s=1, 4 t=1, 8 s=0), else 0
    uint32_t pad[2];
};
static_assert(sizeof(GpuAdaptiveElement) == 80);

struct AdaptiveView {
    glm::mat4 viewProj{1.0f};
    uint32_t width = 1, height = 1;
    glm::vec3 eye{0.0f};
    float facing = 0; // cull patches facing away: +1 / -1 (normals' orientation), 0 never
};

// The five passes' pipelines. They need no buffers, so the renderer builds them on a second
// thread while the CPU prepares the edge pieces: lavapipe compiles a shader when its pipeline is
// created, and these five took about 120 ms of catmark_car_level3's set-up on one core. They are
// compiled on two threads (about 90 and 70 ms of work on this machine's cores): a small mesh's
// set-up is otherwise mostly waiting for them.
struct AdaptivePipelines {
    explicit AdaptivePipelines(gpu::Context& ctx);
    std::unique_ptr<gpu::ComputePipeline> cull, rates, counts, scan, emit;
};

struct AdaptiveOptions {
    // Rates from the screen-space error (adaptive_rates.comp): each edge piece gets the fewest
    // segments whose chords stay within maxError pixels of the surface, and none longer than
    // edgePixels. maxError 0: segments of about edgePixels (with a chord tolerance of
    // edgePixels / 40), the rule before the error estimate.
    float edgePixels = 4;
    float maxError = 0;
    uint32_t tess = 64;     // most segments per edge piece and per element interior
    bool cull = true;       // skip drawing elements outside the frustum
    bool backFaceCull = true; // ... and those facing away (closed surfaces seen from outside)
    // ... and those whose projected hull holds none of the image's sample positions, which
    // rasterize to nothing: the positions within a pixel of the drawn image (1 sample: the
    // centre; 4: Vulkan's standard pattern, which is WebGPU's). Empty: off (--wire-triangles,
    // whose lines light pixels that no triangle covers).
    std::vector<glm::vec2> samplePositions;
    float texelsPerUV = 0;  // displacement map size: its texels bound the rates too (0: none)
    // Budget of the per-frame buffers; the capacity is the smaller of this and what the largest
    // rates could ever need.
    uint64_t maxVertices = 0, maxTriangles = 0; // 0: as many as 128 MiB buffers hold
    // Whether a compute pass evaluates the tessellation vertices (surface_eval.comp over the
    // whole capacity, so unwritten slots must hold valid records); otherwise only what the
    // frame wrote is ever read, and the buffers are left as allocated.
    bool evaluated = false;
    // Smooth face-varying UVs (FaceVaryingSurface::gpu, shaders/fvar_eval.glsl): per
    // element (patches, then irregular faces) its ptex face (uint bits) and (u0, v0, size), the
    // quadtree and records, and fvar_eval.glsl's nudge (2^-21). Empty: bilinear corner UVs.
    // The emit pass reads them from the edge-piece buffer, after the points.
    std::vector<glm::vec4> elementDomains, fvarRecords;
    std::vector<uint32_t> fvarNodes;
    float fvarCell = 0;
    // Per element (patches, then irregular faces): a single-crease patch's crease side (the
    // crease bit of GpuPatch::levelBoundary), 0 otherwise; the emit pass grades the segments
    // across a crease towards it. Missing entries are 0.
    std::vector<uint8_t> elementCrease;
    // Whether vertices may be shared between elements at points (corners and piece ends) and
    // along edge pieces: the draw reads no own-chart UV (no --texture, no --shade uv), and
    // nothing reads the whole surface or each element's own vertices (no --mesh-out, --wire,
    // displacement). With `evaluated`, the compute pass then evaluates each point once.
    bool sharePoints = false;
    // Per-pixel normals: each element writes its own vertices (no shared points) and each
    // carries, in place of its UV, the element and its own (s, t) (adaptive_emit.comp), which
    // the lit fragment stage evaluates the limit normal at (surface_lit_pixel.frag).
    bool pixelNormals = false;
    // The error allowed, in pixels, for a piece whose every sample faces the eye (normal within
    // 70 degrees of the view ray, adaptive_rates.comp): there the chords' error moves no outline,
    // only where the shading lands. 0: maxError everywhere.
    float interiorError = 0;
    // Built ahead (see AdaptivePipelines); null: AdaptiveTess builds them itself.
    std::shared_ptr<AdaptivePipelines> pipelines;
};

// What the scan wrote for the last frame (read back from the GPU).
struct AdaptiveTotals {
    uint32_t vertices = 0;          // emitted (and evaluated)
    uint32_t visibleTriangles = 0;  // facing the view and in it (needed; more than drawn on overflow)
    uint32_t drawnTriangles = 0;    // what the indirect draw draws: visible, within capacity
    uint32_t culledTriangles = 0;   // emitted for --mesh-out only
    bool overflow = false;          // the frame needed more than the buffers hold
    uint32_t writtenTriangles = 0;  // visible + culled, within capacity
    uint32_t writtenVertices = 0;
    bool overBudget = false;        // an element over adaptive_counts.comp's loop budget
    // An element's emit stopped before its last triangle (adaptive_emit.comp checks; lavapipe
    // ends a shader's loops after 65,535 iterations, which the budget estimates).
    bool cutShort = false;
    // "N vertices and M triangles" for messages; the GPU's sums saturate at 2^31 - 1
    // (adaptive_scan.comp), which reads "over 2147483646".
    std::string need() const;
};

// The view-adaptive tessellation behind SubdivisionPass's seam (render/tessellation.h): the
// five passes above each frame, the evaluation and the draws sized by the scan's indirect
// arguments, and its own displacement passes (adaptive_displacement.h). Its options come from
// the render settings (adaptive_options.h).
class AdaptiveTess : public Tessellation {
  public:
    // `draw` prepared with adaptive = true; the surface buffers must outlive this. `evaluated`:
    // a compute pass evaluates every tessellation vertex (AdaptiveOptions::evaluated).
    AdaptiveTess(gpu::Context& ctx, const SubdivisionDraw& draw, const SurfaceBuffers& surface,
                 AdaptiveOptions options, bool evaluated);
    ~AdaptiveTess() override;

    // The five passes, each timed, after a barrier on the limit points; ends with the barrier
    // that the evaluation pass and the draw need.
    void record(gpu::CommandBuffer& cmd, TimedPasses& timed, const AdaptiveView& view) override;

    const gpu::Buffer& tessVertices() const override { return *tessVertices_; }
    const gpu::Buffer& elementsBuffer() const { return *elements_; }
    const gpu::Buffer& triangles() const override { return *triangles_; }
    const gpu::Buffer& triangleLevels() const override { return *triangleLevels_; }
    const gpu::Buffer& totalsBuffer() const { return *totals_; }
    // Offsets into totalsBuffer(): indexed draw, non-indexed draw, evaluation dispatch, the
    // non-indexed draw of the triangles' edges (--wire).
    static constexpr uint64_t kIndexedDrawArgs = 0, kDrawArgs = 20, kDispatchArgs = 36, kWireDrawArgs = 72;
    static constexpr uint32_t kRowGroups = 65535;
    uint64_t vertexCapacity() const override { return capV_; }
    uint32_t triangleCapacity() const { return capT_; }
    AdaptiveTotals readTotals(gpu::Context& ctx) const;
    uint32_t pieceCount() const { return pieceCount_; }

    // Sized by the scan (indirect arguments in totalsBuffer()).
    void dispatchPerVertex(gpu::CommandBuffer& cmd, const gpu::ComputePipeline& pipeline,
                           const gpu::BindGroup& bindings, std::span<const uint8_t> push) const override;
    void drawTriangles(gpu::CommandBuffer& cmd, const gpu::GraphicsPipeline& pipeline, const gpu::BindGroup& bindings,
                       std::span<const uint8_t> push, bool pullIndices) const override;
    // Triangle edges only: outlines exist for the fixed grids (the renderer picks them for
    // Wire::Outlines).
    void drawWire(gpu::CommandBuffer& cmd, Wire wire, const WirePipelines& pipelines,
                  std::span<const uint8_t> push) const override;
    std::unique_ptr<DisplacementPasses> makeDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                         const SurfaceBuffers& surface,
                                                         const DisplacementInputs& in) const override;

    const AdaptiveTotals* lastTotals(gpu::Context& ctx) const override;
    std::string shortfall(gpu::Context& ctx) const override;
    size_t drawnVertexCount(gpu::Context& ctx) const override;
    void finishDrawnMesh(gpu::Context& ctx, exporting::DrawnMesh& out) const override;
    uint64_t triangleCount(gpu::Context& ctx) const override;
    uint64_t verticesEvaluated(gpu::Context& ctx) const override;
    uint64_t bufferBytes() const override;

  private:
    AdaptiveTess(gpu::Context& ctx, const EdgePieces& pieces, uint32_t patchCount, const SurfaceBuffers& surface,
                 const AdaptiveOptions& options);
    void recordPasses(gpu::CommandBuffer& cmd, TimedPasses& timed);

    AdaptiveOptions options_;
    AdaptiveView view_;
    const SubdivisionDraw* draw_ = nullptr; // the pass's draw data, which outlives this
    uint32_t elementCount_, pieceCount_, pointBase_, patchCount_, capV_ = 0, capT_ = 0;
    uint32_t sharedPoints_ = 0; // points with shared vertex slots (the first ones), or 0
    uint32_t domainBase_ = 0, nodeBase_ = 0, recordBase_ = 0; // smooth UVs, in pieces_
    std::unique_ptr<gpu::Buffer> elements_, pieces_, cull_, rates_, pieceEnds_, info_, totals_,
        tessVertices_, triangles_, triangleLevels_;
    std::shared_ptr<AdaptivePipelines> passes_;
    gpu::BindGroup cullBind_, rateBind_, countBind_, scanBind_, emitBind_;
    // The last frame's totals, read back on first use after record().
    mutable AdaptiveTotals lastTotals_;
    mutable bool totalsRead_ = false;
};

} // namespace limn::render
