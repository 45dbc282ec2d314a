#include "render/control_mesh_pass.h"

#include "base/error.h"
#include "render_shaders.h"

namespace limn::render {

namespace {

struct VertexPush {
    uint32_t firstVertex;
};

template <class T>
uint64_t bytes(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

} // namespace

struct ControlMeshPass::Gpu {
    Gpu(gpu::Context& ctx, const ControlMeshDraw& d, const FloatImage* colour, gpu::TargetFormat target,
        Shade shade)
        : vertices(ctx, {"vertices", bytes(d.controlPoints)}),
          faceOffsets(ctx, {"face offsets", bytes(d.faceOffsets)}),
          faceVertices(ctx, {"face vertices", bytes(d.faceVertices)}),
          faceNormals(ctx, {"face normals", (d.faceOffsets.size() - 1) * 16}),
          corners(ctx, {"corners", bytes(d.corners)}), uvs(ctx, {"uvs", bytes(d.uvs)}),
          triangles(ctx, {"triangle indices", bytes(d.triangles), gpu::kIndex}),
          edges(ctx, {"edge indices", bytes(d.edges), gpu::kIndex}),
          texture(gpu::uploadBufferNow(ctx, "colour texture", textureWords(colour))),
          faceNormalsPass(ctx, {"face normals", face_normals_comp_spv, 4, sizeof(VertexPush)}),
          // Lit shading: the fragment stage without the other modes' code (why in draw_common.glsl).
          meshPipeline(ctx, {"mesh", mesh_vert_spv,
                             shade == Shade::Lit ? std::span<const uint32_t>(mesh_lit_frag_spv)
                                                 : std::span<const uint32_t>(mesh_frag_spv),
                             5, sizeof(DrawPush)},
                       target),
          wirePipeline(ctx, {"wire", wire_vert_spv, wire_frag_spv, 1, sizeof(DrawPush),
                             gpu::Primitive::Lines, gpu::DepthTest::LessOrEqual, false},
                       target) {
        normalBindings = faceNormalsPass.bind({vertices, faceOffsets, faceVertices, faceNormals});
        meshBindings = meshPipeline.bind({vertices, faceNormals, corners, uvs, texture});
        wireBindings = wirePipeline.bind({vertices});
        // Topology is uploaded once; positions every frame.
        gpu::uploadArrayNow<uint32_t>(ctx, faceOffsets, d.faceOffsets);
        gpu::uploadArrayNow<uint32_t>(ctx, faceVertices, d.faceVertices);
        gpu::uploadArrayNow<GpuCorner>(ctx, corners, d.corners);
        gpu::uploadArrayNow<glm::vec2>(ctx, uvs, d.uvs);
        gpu::uploadArrayNow<uint32_t>(ctx, triangles, d.triangles);
        gpu::uploadArrayNow<uint32_t>(ctx, edges, d.edges);
    }

    gpu::Buffer vertices, faceOffsets, faceVertices, faceNormals, corners, uvs, triangles, edges, texture;
    gpu::ComputePipeline faceNormalsPass;
    gpu::GraphicsPipeline meshPipeline, wirePipeline;
    gpu::BindGroup normalBindings, meshBindings, wireBindings;
};

ControlMeshPass::ControlMeshPass(gpu::Context& ctx, ControlMeshDraw draw, const FloatImage* texture,
                                 Shade shade, gpu::TargetFormat target)
    : ctx_(ctx), draw_(std::move(draw)), shade_(shade),
      gpu_(std::make_unique<Gpu>(ctx, draw_, texture, target, shade)) {}

ControlMeshPass::~ControlMeshPass() = default;

const gpu::Buffer& ControlMeshPass::vertexBuffer() const { return gpu_->vertices; }

void ControlMeshPass::recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) {
    auto& g = *gpu_;
    timed.begin(cmd, "face normals", true);
    cmd.dispatch(g.faceNormalsPass, g.normalBindings,
                 static_cast<uint32_t>(draw_.faceOffsets.size() - 1), VertexPush{0});
    cmd.endTimed();
    cmd.barrier(gpu::Access::ComputeWrite, gpu::Access::VertexRead | gpu::Access::TransferRead);
}

void ControlMeshPass::recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) {
    auto& g = *gpu_;
    if (push.shade != static_cast<uint32_t>(shade_))
        throw Error(ErrorKind::BadInput, "internal: a control mesh draw shaded otherwise than its pass was built for");
    cmd.drawIndexed(g.meshPipeline, g.meshBindings, g.triangles,
                    static_cast<uint32_t>(draw_.triangles.size()), 1, gpu::CommandBuffer::asBytes(push));
    if (wire != Wire::None)
        cmd.drawIndexed(g.wirePipeline, g.wireBindings, g.edges,
                        static_cast<uint32_t>(draw_.edges.size()), 1, gpu::CommandBuffer::asBytes(push));
}

exporting::DrawnMesh ControlMeshPass::drawnMesh() {
    auto vertices = gpu::readbackArrayNow<glm::vec4>(ctx_, gpu_->vertices, draw_.controlPoints.size());
    auto normals = gpu::readbackArrayNow<glm::vec4>(ctx_, gpu_->faceNormals, draw_.faceOffsets.size() - 1);
    exporting::DrawnMesh out;
    out.vertices.reserve(draw_.corners.size());
    for (const GpuCorner& c : draw_.corners) {
        exporting::DrawnVertex v;
        const glm::vec4& p = vertices[c.vertex];
        const glm::vec4& n = normals[c.face];
        v.x = p.x, v.y = p.y, v.z = p.z;
        v.nx = n.x, v.ny = n.y, v.nz = n.z;
        v.ptex = static_cast<int32_t>(c.ptex);
        v.u = draw_.uvs[c.uv].x;
        v.v = draw_.uvs[c.uv].y;
        if (draw_.hasUVs) v.s = v.u, v.t = v.v; // one vertex per face corner: split at every seam
        out.vertices.push_back(v);
    }
    out.hasTexCoords = draw_.hasUVs;
    out.triangles = draw_.triangles;
    return out;
}

uint64_t ControlMeshPass::bufferBytes() const {
    auto& g = *gpu_;
    uint64_t sum = 0;
    for (const gpu::Buffer* b : {&g.vertices, &g.faceOffsets, &g.faceVertices, &g.faceNormals,
                                 &g.corners, &g.uvs, &g.triangles, &g.edges, &g.texture})
        sum += b->size();
    return sum;
}

} // namespace limn::render
