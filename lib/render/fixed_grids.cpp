#include "render/fixed_grids.h"

#include "base/error.h"
#include "render_shaders.h"

#include <algorithm>

namespace limn::render {

namespace {

using gpu::uploadBufferNow; // absent tables get one zero element

// The draw data's displacement plan: one sample range per tessellation vertex.
const SubdivisionDraw& checkedPlan(const SubdivisionDraw& d) {
    if (d.sideRanges.size() != d.tessVertices.size())
        throw Error(ErrorKind::BadInput, "internal: draw data prepared without a displacement plan");
    return d;
}

struct DisplacePush { // displace.comp
    float scale, mid;
};

// Paper 000, 4.5 on the fixed grids: displace.comp samples the map at each vertex's UVs (the
// plan's sample ranges: one UV, or the seam fix's several averaged), displaced_normals.comp
// averages the displaced triangles' normals around each vertex (the incident triangles).
class FixedGridDisplacement : public DisplacementPasses {
  public:
    FixedGridDisplacement(gpu::Context& ctx, const SubdivisionDraw& d, const gpu::Buffer& triangles,
                          const DisplacementInputs& in)
        : scale_(in.scale), mid_(in.mid), count_(static_cast<uint32_t>(d.tessVertices.size())),
          sideRanges_(uploadBufferNow(ctx, "displacement sample ranges", checkedPlan(d).sideRanges)),
          sideUVs_(uploadBufferNow(ctx, "displacement sample UVs", d.sideUVs)),
          map_(uploadBufferNow(ctx, "displacement map", displacementMapWords(in.map))),
          displaced_(ctx, gpu::BufferDesc{"displaced positions", in.vertexCapacity * 16}),
          incidentRanges_(uploadBufferNow(ctx, "incident ranges", d.incidentRanges)),
          incident_(uploadBufferNow(ctx, "incident triangles", d.incidentTriangles)),
          displacedNormals_(ctx, gpu::BufferDesc{"displaced normals", in.vertexCapacity * 16}),
          displacePass_(ctx, gpu::ComputePipelineDesc{"displace", displace_comp_spv, 6, sizeof(DisplacePush)}),
          normalsPass_(ctx, gpu::ComputePipelineDesc{"displaced normals", displaced_normals_comp_spv, 5, 0}) {
        displaceBindings_ = displacePass_.bind(
            {in.evaluatedPositions, in.evaluatedNormals, sideRanges_, sideUVs_, map_, displaced_});
        normalsBindings_ = normalsPass_.bind({displaced_, triangles, incidentRanges_, incident_, displacedNormals_});
    }

    void record(gpu::CommandBuffer& cmd, TimedPasses& timed) override {
        const auto compute = gpu::Access::ComputeWrite, read = gpu::Access::ComputeRead;
        cmd.barrier(compute, read);
        timed.begin(cmd, "displace", true);
        cmd.dispatch(displacePass_, displaceBindings_, count_, DisplacePush{scale_, mid_});
        cmd.endTimed();
        cmd.barrier(compute, read);
        timed.begin(cmd, "displaced normals", true);
        cmd.dispatch(normalsPass_, normalsBindings_, count_);
        cmd.endTimed();
    }
    const gpu::Buffer& positions() const override { return displaced_; }
    const gpu::Buffer& normals() const override { return displacedNormals_; }
    uint64_t bufferBytes() const override {
        return sideRanges_.size() + sideUVs_.size() + map_.size() + displaced_.size() + incidentRanges_.size() +
               incident_.size() + displacedNormals_.size();
    }

  private:
    float scale_, mid_;
    uint32_t count_;
    gpu::Buffer sideRanges_, sideUVs_, map_, displaced_, incidentRanges_, incident_, displacedNormals_;
    gpu::ComputePipeline displacePass_, normalsPass_;
    gpu::BindGroup displaceBindings_, normalsBindings_;
};

} // namespace

FixedGrids::FixedGrids(gpu::Context& ctx, const SubdivisionDraw& d)
    : draw_(d), tessVertices_(uploadBufferNow(ctx, "tessellation vertices", d.tessVertices)),
      // Indices are also read by the vertex stage for --shade levels.
      triangles_(uploadBufferNow(ctx, "triangle indices", d.triangles, gpu::kIndex | gpu::kStorage)),
      triangleLevels_(uploadBufferNow(ctx, "triangle levels", d.triangleLevels)),
      wireLines_(uploadBufferNow(ctx, "wire lines", d.wireLines, gpu::kIndex)) {}

uint64_t FixedGrids::vertexCapacity() const { return std::max<uint64_t>(draw_.tessVertices.size(), 1); }

void FixedGrids::dispatchPerVertex(gpu::CommandBuffer& cmd, const gpu::ComputePipeline& pipeline,
                                   const gpu::BindGroup& bindings, std::span<const uint8_t> push) const {
    cmd.dispatch(pipeline, bindings, static_cast<uint32_t>(draw_.tessVertices.size()), push);
}

void FixedGrids::drawTriangles(gpu::CommandBuffer& cmd, const gpu::GraphicsPipeline& pipeline,
                               const gpu::BindGroup& bindings, std::span<const uint8_t> push,
                               bool pullIndices) const {
    const auto indexCount = static_cast<uint32_t>(draw_.triangles.size());
    if (pullIndices)
        cmd.draw(pipeline, bindings, indexCount, 1, push);
    else
        cmd.drawIndexed(pipeline, bindings, triangles_, indexCount, 1, push);
}

void FixedGrids::drawWire(gpu::CommandBuffer& cmd, Wire wire, const WirePipelines& p,
                          std::span<const uint8_t> push) const {
    if (wire == Wire::Outlines)
        cmd.drawIndexed(p.outlines, p.outlineBindings, wireLines_, static_cast<uint32_t>(draw_.wireLines.size()), 1,
                        push);
    if (wire == Wire::Triangles) // two vertices per triangle corner: its three edges
        cmd.draw(p.triangleEdges, p.triangleEdgeBindings, static_cast<uint32_t>(2 * draw_.triangles.size()), 1, push);
}

std::unique_ptr<DisplacementPasses> FixedGrids::makeDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                                 const SurfaceBuffers&,
                                                                 const DisplacementInputs& in) const {
    return std::make_unique<FixedGridDisplacement>(ctx, draw, triangles_, in);
}

void FixedGrids::finishDrawnMesh(gpu::Context&, exporting::DrawnMesh& out) const {
    for (size_t i = 0; i < out.vertices.size(); ++i) {
        const GpuTessVertex& t = draw_.tessVertices[i];
        if (draw_.hasUVs) // the grids split their vertices at UV seams
            out.vertices[i].s = t.u, out.vertices[i].t = t.v;
        out.vertices[i].approximate = drawnPointIsApproximate(draw_, t.element, t.st);
    }
    out.triangles = draw_.triangles;
}

uint64_t FixedGrids::bufferBytes() const {
    return tessVertices_.size() + triangles_.size() + triangleLevels_.size() + wireLines_.size();
}

} // namespace limn::render
