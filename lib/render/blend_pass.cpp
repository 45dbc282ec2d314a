#include "render/blend_pass.h"

#include "base/error.h"
#include "render_shaders.h"

#include <cstring>

namespace limn::render {

namespace {

// The blending surface's fragment stage: each covered sample shaded (and trimmed) on its own with
// --sample-shading (blend_per_sample.frag; why in draw_common.glsl's LIMN_SMOOTH_IN), and for the
// lit shading the variant without the other modes' code (why in draw_common.glsl).
std::span<const uint32_t> blendFragment(const gpu::TargetFormat& target, Shade shade) {
    using Code = std::span<const uint32_t>;
    if (shade == Shade::Lit)
        return target.sampleShading ? Code(blend_lit_per_sample_frag_spv) : Code(blend_lit_frag_spv);
    return target.sampleShading ? Code(blend_per_sample_frag_spv) : Code(blend_frag_spv);
}

struct EvalPush { // blend_eval.comp
    uint32_t grid, weights;
};

using gpu::uploadBufferNow;

// The DrawData buffer: its header, then the trim atlas packed four texels to a word.
std::vector<uint32_t> drawData(const BlendDraw& d, const std::optional<blend::TrimMask>& trim) {
    BlendDrawData h{d.grid, static_cast<uint32_t>(d.weights), 0, 0, 0, d.hasUVs ? 1u : 0u, {0, 0}};
    std::vector<uint32_t> words(sizeof h / 4 + 1, 0);
    if (trim) {
        h.trimTile = trim->layout.tile;
        h.trimTilesX = trim->layout.tilesX;
        h.trimWidth = trim->layout.width();
        words.resize(sizeof h / 4 + (trim->texels.size() + 3) / 4, 0);
        for (size_t i = 0; i < trim->texels.size(); ++i)
            words[sizeof h / 4 + i / 4] |= uint32_t(trim->texels[i]) << (8 * (i % 4));
    }
    std::memcpy(words.data(), &h, sizeof h);
    return words;
}

} // namespace

struct BlendPass::Gpu {
    Gpu(gpu::Context& ctx, const BlendDraw& d, bool evaluate,
        const std::optional<blend::TrimMask>& trim, gpu::TargetFormat target, Shade shade)
        : controlPoints(ctx, {"control points (unused by the blend draw)",
                              std::max<uint64_t>(d.vertices.size(), 1) * 16}),
          vertices(uploadBufferNow(ctx, "blend vertices", d.vertices)),
          faces(uploadBufferNow(ctx, "blend faces", d.faces)), points(uploadBufferNow(ctx, "blend points", d.points)),
          drawVertices(uploadBufferNow(ctx, "blend grid vertices", d.drawVertices)),
          triangles(uploadBufferNow(ctx, "triangle indices", d.triangles, gpu::kIndex)),
          wireLines(uploadBufferNow(ctx, "wire lines", d.wireLines, gpu::kIndex)),
          faceUVs(uploadBufferNow(ctx, "face uvs", d.faceUVs)),
          data(uploadBufferNow(ctx, "blend draw data and trim atlas", drawData(d, trim))),
          positions(ctx, {"evaluated positions",
                          evaluate ? std::max<uint64_t>(d.points.size(), 1) * 16 : 16}),
          normals(ctx, {"evaluated normals",
                        evaluate ? std::max<uint64_t>(d.points.size(), 1) * 16 : 16}),
          evalPass(ctx, {"evaluate blend surface", blend_eval_comp_spv, 5, sizeof(EvalPush)}),
          drawEval(ctx, {"blend surface", blend_vert_spv, blendFragment(target, shade), 7, sizeof(DrawPush)}, target),
          drawFetch(ctx, {"blend surface (evaluated)", blend_fetch_vert_spv, blendFragment(target, shade), 7,
                          sizeof(DrawPush)},
                    target),
          wire(ctx, {"wire", wire_vert_spv, wire_frag_spv, 1, sizeof(DrawPush),
                     gpu::Primitive::Lines, gpu::DepthTest::LessOrEqual, false},
               target) {
        evalBindings = evalPass.bind({vertices, faces, points, positions, normals});
        // Both draws have one layout, so one fragment shader serves them.
        drawBindings =
            drawEval.bind({vertices, faces, drawVertices, positions, normals, data, faceUVs});
        fetchBindings =
            drawFetch.bind({vertices, faces, drawVertices, positions, normals, data, faceUVs});
        wireBindings = wire.bind({positions});
    }

    gpu::Buffer controlPoints, vertices, faces, points, drawVertices, triangles, wireLines, faceUVs,
        data, positions, normals;
    gpu::ComputePipeline evalPass;
    gpu::GraphicsPipeline drawEval, drawFetch, wire;
    gpu::BindGroup evalBindings, drawBindings, fetchBindings, wireBindings;
};

BlendPass::BlendPass(gpu::Context& ctx, BlendDraw draw, Eval eval, bool keepEvaluated,
                     const std::optional<blend::TrimMask>& trim, Shade shade, gpu::TargetFormat target)
    : ctx_(ctx), draw_(std::move(draw)), eval_(eval),
      evaluate_(keepEvaluated || eval == Eval::Compute), shade_(shade),
      gpu_(std::make_unique<Gpu>(ctx, draw_, evaluate_, trim, target, shade)) {}

BlendPass::~BlendPass() = default;

const gpu::Buffer& BlendPass::vertexBuffer() const {
    return gpu_->controlPoints;
}

void BlendPass::recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) {
    auto& g = *gpu_;
    if (evaluate_) {
        timed.begin(cmd, "evaluate blend surface", true);
        cmd.dispatch(g.evalPass, g.evalBindings, static_cast<uint32_t>(draw_.points.size()),
                     EvalPush{draw_.grid, static_cast<uint32_t>(draw_.weights)});
        cmd.endTimed();
    }
    cmd.barrier(gpu::Access::ComputeWrite, gpu::Access::VertexRead | gpu::Access::TransferRead);
}

void BlendPass::recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) {
    auto& g = *gpu_;
    if (push.shade != static_cast<uint32_t>(shade_))
        throw Error(ErrorKind::BadInput, "internal: a blend draw shaded otherwise than its pass was built for");
    push.flags = 0;
    const bool fetch = eval_ == Eval::Compute;
    cmd.drawIndexed(fetch ? g.drawFetch : g.drawEval, fetch ? g.fetchBindings : g.drawBindings,
                    g.triangles, static_cast<uint32_t>(draw_.triangles.size()), 1,
                    gpu::CommandBuffer::asBytes(push));
    if (wire != Wire::None && evaluate_)
        cmd.drawIndexed(g.wire, g.wireBindings, g.wireLines,
                        static_cast<uint32_t>(draw_.wireLines.size()), 1,
                        gpu::CommandBuffer::asBytes(push));
}

exporting::DrawnMesh BlendPass::drawnMesh() {
    const size_t n = draw_.points.size();
    exporting::DrawnMesh out = readDrawnVertices(ctx_, evaluate_ ? &gpu_->positions : nullptr, &gpu_->normals, n);
    for (size_t i = 0; i < n; ++i) {
        exporting::DrawnVertex& v = out.vertices[i];
        v.ptex = static_cast<int32_t>(draw_.points[i].face); // a quad mesh: one Ptex face per face
        v.u = blendGridParam(draw_.points[i].ij & 0xFFFFu, draw_.grid);
        v.v = blendGridParam(draw_.points[i].ij >> 16, draw_.grid);
    }
    out.triangles.reserve(draw_.triangles.size());
    for (uint32_t t : draw_.triangles) out.triangles.push_back(draw_.drawVertices[t].point);
    return out;
}

uint64_t BlendPass::verticesEvaluated() const {
    // The compute pass evaluates each point once; the vertex stage each grid vertex of every
    // drawn face at least once (shared points once per face that draws them).
    uint64_t n = evaluate_ ? draw_.points.size() : 0;
    if (eval_ == Eval::Vertex) n += draw_.drawVertices.size();
    return n;
}

uint64_t BlendPass::bufferBytes() const {
    auto& g = *gpu_;
    uint64_t sum = 0;
    for (const gpu::Buffer* b :
         {&g.controlPoints, &g.vertices, &g.faces, &g.points, &g.drawVertices, &g.triangles,
          &g.wireLines, &g.faceUVs, &g.data, &g.positions, &g.normals})
        sum += b->size();
    return sum;
}

} // namespace limn::render
