// The fixed tessellation (paper 000, 4.3): a grid of 2^(N-l) segments per side of a level-l
// patch, stitched to its neighbours' so the surface stays watertight; prepared on the CPU
// (subdivision_draw.h), uploaded once, drawn with host-known counts. Displaced with
// displace.comp and displaced_normals.comp (paper 000, 4.5).
#pragma once

#include "render/subdivision_draw.h"
#include "render/tessellation.h"

namespace limn::render {

class FixedGrids : public Tessellation {
  public:
    // `draw` holds the grids (prepared with adaptive = false) and must outlive this.
    FixedGrids(gpu::Context& ctx, const SubdivisionDraw& draw);

    const gpu::Buffer& tessVertices() const override { return tessVertices_; }
    const gpu::Buffer& triangles() const override { return triangles_; }
    const gpu::Buffer& triangleLevels() const override { return triangleLevels_; }
    uint64_t vertexCapacity() const override;

    void record(gpu::CommandBuffer&, TimedPasses&, const AdaptiveView&) override {}
    void dispatchPerVertex(gpu::CommandBuffer& cmd, const gpu::ComputePipeline& pipeline,
                           const gpu::BindGroup& bindings, std::span<const uint8_t> push) const override;
    void drawTriangles(gpu::CommandBuffer& cmd, const gpu::GraphicsPipeline& pipeline, const gpu::BindGroup& bindings,
                       std::span<const uint8_t> push, bool pullIndices) const override;
    void drawWire(gpu::CommandBuffer& cmd, Wire wire, const WirePipelines& pipelines,
                  std::span<const uint8_t> push) const override;
    std::unique_ptr<DisplacementPasses> makeDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                         const SurfaceBuffers& surface,
                                                         const DisplacementInputs& in) const override;

    const AdaptiveTotals* lastTotals(gpu::Context&) const override { return nullptr; }
    std::string shortfall(gpu::Context&) const override { return {}; }
    size_t drawnVertexCount(gpu::Context&) const override { return draw_.tessVertices.size(); }
    void finishDrawnMesh(gpu::Context& ctx, exporting::DrawnMesh& out) const override;
    uint64_t triangleCount(gpu::Context&) const override { return draw_.triangles.size() / 3; }
    uint64_t verticesEvaluated(gpu::Context&) const override { return draw_.tessVertices.size(); }
    uint64_t bufferBytes() const override;

  private:
    const SubdivisionDraw& draw_;
    gpu::Buffer tessVertices_, triangles_, triangleLevels_, wireLines_;
};

} // namespace limn::render
