// The control mesh's GPU frame: a face-normal compute pass, then fan triangles drawn flat (with
// wire edges), lit or textured. Used for containers without subdivision tables.
#pragma once

#include "gpu/context.h"
#include "render/control_mesh.h"
#include "render/frame_pass.h"

#include <memory>

namespace limn::render {

class ControlMeshPass : public FramePass {
public:
    // `texture` (optional): the colour texture drawn with Shade::Texture. `shade`: the shading
    // every draw will ask for (its fragment stage is picked for it).
    ControlMeshPass(gpu::Context& ctx, ControlMeshDraw draw, const FloatImage* texture, Shade shade,
                    gpu::TargetFormat target = {});
    ~ControlMeshPass() override;

    const gpu::Buffer& vertexBuffer() const override;
    void recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) override;
    void recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) override;
    exporting::DrawnMesh drawnMesh() override;
    uint64_t triangleCount() const override { return draw_.triangles.size() / 3; }
    uint64_t verticesEvaluated() const override { return draw_.controlPoints.size(); }
    uint64_t bufferBytes() const override;

private:
    gpu::Context& ctx_;
    ControlMeshDraw draw_;
    Shade shade_;
    struct Gpu;
    std::unique_ptr<Gpu> gpu_;
};

} // namespace limn::render
