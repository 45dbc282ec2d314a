#include "render/adaptive/adaptive_displacement.h"

#include "base/error.h"
#include "render/adaptive/adaptive_tess.h"
#include "render_shaders.h"

namespace limn::render {

namespace {

struct AdaptiveDisplacePush { // adaptive_displace.comp
    float scale, mid;
    uint32_t seamFix, smoothUV;
};
struct AdaptiveNormalsPush { // adaptive_displaced_normals.comp
    uint32_t patchCount;
    float scale, mid;
};

// Smooth UVs: the records of the smooth UVs instead of SEAM's linear ones.
const Seams& seamRecords(const SubdivisionDraw& d) {
    if (!d.seams) throw Error(ErrorKind::BadInput, "internal: displacement without seam data");
    return d.smoothSeams.elements.empty() ? *d.seams : d.smoothSeams;
}

class AdaptiveDisplacement : public DisplacementPasses {
  public:
    AdaptiveDisplacement(gpu::Context& ctx, const SubdivisionDraw& d, const SurfaceBuffers& surface,
                         const AdaptiveTess& tess, const DisplacementInputs& in)
        : tess_(tess),
          displacePush_{in.scale, in.mid, d.seamFix ? 1u : 0u, d.smoothSeams.elements.empty() ? 0u : 1u},
          normalsPush_{static_cast<uint32_t>(d.patches.size()), in.scale, in.mid},
          seamElements_(gpu::uploadBufferNow(ctx, "seam elements", seamRecords(d).elements)),
          seamUVs_(gpu::uploadBufferNow(ctx, "seam UVs", seamRecords(d).uvs)),
          map_(gpu::uploadBufferNow(ctx, "displacement map", displacementMapWords(in.map))),
          displaced_(ctx, gpu::BufferDesc{"displaced positions", in.vertexCapacity * 16}),
          displacedNormals_(ctx, gpu::BufferDesc{"displaced normals", in.vertexCapacity * 16}),
          displacePass_(ctx, gpu::ComputePipelineDesc{"displace (adaptive)", adaptive_displace_comp_spv, 7,
                                                      sizeof(AdaptiveDisplacePush)}),
          normalsPass_(ctx, gpu::ComputePipelineDesc{"displaced normals (adaptive)",
                                                     adaptive_displaced_normals_comp_spv, 8,
                                                     sizeof(AdaptiveNormalsPush)}) {
        const gpu::Buffer& tv = tess.tessVertices();
        displaceBindings_ = displacePass_.bind(
            {in.evaluatedPositions, in.evaluatedNormals, tv, seamElements_, seamUVs_, map_, displaced_});
        normalsBindings_ = normalsPass_.bind({surface.vertices, surface.patches, surface.irregular, surface.limits,
                                              tv, tess.elementsBuffer(), map_, displacedNormals_});
    }

    void record(gpu::CommandBuffer& cmd, TimedPasses& timed) override {
        const auto compute = gpu::Access::ComputeWrite, read = gpu::Access::ComputeRead;
        const auto& args = tess_.totalsBuffer();
        const auto cap = static_cast<uint32_t>(tess_.vertexCapacity());
        cmd.barrier(compute, read);
        timed.begin(cmd, "displace", true);
        cmd.dispatchIndirect(displacePass_, displaceBindings_, args, AdaptiveTess::kDispatchArgs, cap,
                             AdaptiveTess::kRowGroups, displacePush_);
        cmd.endTimed();
        cmd.barrier(compute, read);
        timed.begin(cmd, "displaced normals", true);
        cmd.dispatchIndirect(normalsPass_, normalsBindings_, args, AdaptiveTess::kDispatchArgs, cap,
                             AdaptiveTess::kRowGroups, normalsPush_);
        cmd.endTimed();
    }
    const gpu::Buffer& positions() const override { return displaced_; }
    const gpu::Buffer& normals() const override { return displacedNormals_; }
    uint64_t bufferBytes() const override {
        return seamElements_.size() + seamUVs_.size() + map_.size() + displaced_.size() + displacedNormals_.size();
    }

  private:
    const AdaptiveTess& tess_;
    AdaptiveDisplacePush displacePush_;
    AdaptiveNormalsPush normalsPush_;
    gpu::Buffer seamElements_, seamUVs_, map_, displaced_, displacedNormals_;
    gpu::ComputePipeline displacePass_, normalsPass_;
    gpu::BindGroup displaceBindings_, normalsBindings_;
};

} // namespace

std::unique_ptr<DisplacementPasses> makeAdaptiveDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                             const SurfaceBuffers& surface, const AdaptiveTess& tess,
                                                             const DisplacementInputs& in) {
    return std::make_unique<AdaptiveDisplacement>(ctx, draw, surface, tess, in);
}

} // namespace limn::render
