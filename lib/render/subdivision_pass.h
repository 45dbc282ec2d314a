// The subdivision surface's GPU frame (paper 000, 4.2-4.4): per level a face-point, an
// edge-point and a vertex-point compute pass over the tables, a limit-point pass, then the draw
// of the watertight tessellation whose vertices the vertex stage evaluates. Which tessellation
// (fixed grids or view-adaptive) is behind render/tessellation.h: this pass never asks which.
#pragma once

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "render/adaptive/adaptive_tess.h"
#include "render/frame_pass.h"
#include "render/subdivision_draw.h"
#include "render/tessellation.h"
#include "image/texture_image.h"

#include <future>
#include <memory>

namespace limn::render {

class SubdivisionPass : public FramePass {
public:
    // Where the tessellation vertices are evaluated: in the vertex stage as the draw needs them
    // (paper 000, 4.3), or once each by a compute pass that the draw then reads.
    enum class Eval { Vertex, Compute };
    // `adaptive`: view-adaptive tessellation (adaptive/adaptive_tess.h, options from
    // adaptive/adaptive_options.h) instead of the fixed grids of the draw data (fixed_grids.h;
    // the draw data must be prepared for the one chosen).
    // `keepEvaluated`: with Eval::Vertex, also evaluate every vertex into buffers (for --wire,
    // which draws lines through them, and --mesh-out).
    // `shade`: the one shading every recordDraw pushes (its fragment stage is compiled for it).
    // Displacement (paper 000, 4.5): every drawn vertex moves along its limit normal by
    // scale * (sample - mid); needs Eval::Compute and draw data prepared with a plan.
    struct Displacement {
        const FloatImage* map = nullptr; // channel 0 is the height
        float scale = 1, mid = 0;
    };
    SubdivisionPass(gpu::Context& ctx, SubdivisionDraw draw, Eval eval, bool keepEvaluated, Shade shade,
                    const Displacement* displacement = nullptr, const FloatImage* texture = nullptr,
                    const AdaptiveOptions* adaptive = nullptr, gpu::TargetFormat target = {});
    ~SubdivisionPass() override;

    const gpu::Buffer& vertexBuffer() const override;
    void recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) override;
    void recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) override;
    exporting::DrawnMesh drawnMesh() override;
    void setView(const glm::mat4& viewProj, const glm::dvec3& eye, uint32_t width, uint32_t height) override;
    void setControlPoints(const Bounds& bounds, float orientation) override;
    // Drawn triangles of the last frame (view-adaptive: read back from the GPU, after culling).
    uint64_t triangleCount() const override;
    // The last frame's view-adaptive totals (null for the fixed tessellation).
    const AdaptiveTotals* lastTotals() const;
    // Why the last frame's view-adaptive tessellation left parts of the surface out (its buffers
    // overflowed, or a patch's loops were cut short), with what to do; empty when it did not.
    std::string tessellationShortfall() const;
    uint64_t verticesEvaluated() const override;
    uint64_t bufferBytes() const override;

private:
    const gpu::GraphicsPipeline& culledPipeline(float facing);

    gpu::Context& ctx_;
    SubdivisionDraw draw_;
    Eval eval_;
    bool evaluate_, levels_;
    bool pixelNormals_; // lit, per-pixel limit normals (AdaptiveOptions::pixelNormals)
    Shade shade_;
    AdaptiveView view_;
    float orientation_ = 0; // sign of the control mesh's volume where back faces may be culled
    bool mayCullBackFaces_ = false; // closed, and culling asked for
    gpu::TargetFormat target_; // what every draw pipeline, the lazily made culled ones too, targets
    struct Gpu;
    std::unique_ptr<Gpu> gpu_;
    // The culled draw the usual view needs, compiled on another thread during the set-up and
    // the first frame's compute recording (culledPipeline waits for it). Declared after gpu_,
    // so it is joined before the pipeline it compiles goes.
    std::future<void> culledCompile_;
};

} // namespace limn::render
