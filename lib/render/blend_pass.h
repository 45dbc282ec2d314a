// The blending surface's GPU frame (paper 001, section 4): the local surfaces and charts are
// uploaded once (4.1; BLND already holds them), then either a compute pass evaluates every surface
// point once and the draw fetches them (--eval compute), or the vertex stage evaluates the grid
// as it draws it, the paper's vertex program (4.2, --eval vertex). The fragment stage shades and
// trims (4.3).
#pragma once

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "render/blend_draw.h"
#include "render/frame_pass.h"
#include "blend/trim.h"

#include <memory>
#include <optional>

namespace limn::render {

// Mirrors the header of DrawData in shaders/blend_draw.glsl.
struct BlendDrawData {
    uint32_t grid, weights;
    uint32_t trimTile, trimTilesX, trimWidth; // trimTile 0: no trimming
    uint32_t hasUVs;
    uint32_t reserved[2];
};
static_assert(sizeof(BlendDrawData) == 32);

class BlendPass : public FramePass {
  public:
    enum class Eval { Vertex, Compute };
    // `keepEvaluated`: with Eval::Vertex, also evaluate every point into buffers (--wire draws
    // lines through them, --mesh-out reads them). `trim`: the atlas for the mesh's faces. `shade`:
    // the shading every draw will ask for (its fragment stage is picked for it).
    BlendPass(gpu::Context& ctx, BlendDraw draw, Eval eval, bool keepEvaluated,
              const std::optional<blend::TrimMask>& trim, Shade shade, gpu::TargetFormat target = {});
    ~BlendPass() override;

    // The control points are copied here every frame like for every surface; the blending
    // surface does not read them (its local surfaces were fitted by limn-blend, math.md A.9).
    const gpu::Buffer& vertexBuffer() const override;
    void recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) override;
    void recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) override;
    // The surface points (ptex = face, (u, v) its owner's parameters) and the triangles of every
    // drawn face through them.
    exporting::DrawnMesh drawnMesh() override;
    uint64_t triangleCount() const override { return draw_.triangles.size() / 3; }
    uint64_t verticesEvaluated() const override;
    uint64_t bufferBytes() const override;

  private:
    gpu::Context& ctx_;
    BlendDraw draw_;
    Eval eval_;
    bool evaluate_;
    Shade shade_;
    struct Gpu;
    std::unique_ptr<Gpu> gpu_;
};

} // namespace limn::render
