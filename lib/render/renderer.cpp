#include "render/renderer.h"

#include "base/error.h"
#include "render_shaders.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <cstring>

namespace limn::render {

namespace {

// Mirrors DrawPush in draw_common.glsl (std430 push-constant layout).
struct DrawPush {
    float viewProj[16];
    float eye[4];
    float light[4];
    float wireColor[4];
    uint32_t shade;
    float wirePull;
    uint32_t pad0 = 0, pad1 = 0;
};
static_assert(sizeof(DrawPush) == 128);

struct VertexPush {
    uint32_t firstVertex;
};

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

constexpr float kWirePull = 2e-3f; // fraction of the distance to the eye

} // namespace

struct Renderer::Gpu {
    Gpu(gpu::Context& ctx, const ControlMeshDraw& d, uint32_t width, uint32_t height)
        : staging(ctx,
                  {"control point staging", bytes(d.controlPoints), 0, gpu::MemoryKind::Upload}),
          controlPoints(ctx, {"control points", bytes(d.controlPoints)}),
          vertices(ctx, {"vertices", bytes(d.controlPoints)}),
          faceOffsets(ctx, {"face offsets", bytes(d.faceOffsets)}),
          faceVertices(ctx, {"face vertices", bytes(d.faceVertices)}),
          faceNormals(ctx, {"face normals", (d.faceOffsets.size() - 1) * 16}),
          corners(ctx, {"corners", bytes(d.corners)}), uvs(ctx, {"uvs", bytes(d.uvs)}),
          triangles(ctx, {"triangle indices", bytes(d.triangles), gpu::kIndex}),
          edges(ctx, {"edge indices", bytes(d.edges), gpu::kIndex}),
          copyPoints(ctx, {"copy control points", copy_points_comp_spv, 2, sizeof(VertexPush)}),
          faceNormalsPass(ctx, {"face normals", face_normals_comp_spv, 4, sizeof(VertexPush)}),
          meshPipeline(ctx, {"mesh", mesh_vert_spv, mesh_frag_spv, 4, sizeof(DrawPush)}),
          wirePipeline(ctx, {"wire", wire_vert_spv, wire_frag_spv, 1, sizeof(DrawPush),
                             gpu::Primitive::Lines, gpu::DepthTest::LessOrEqual, false}),
          target(ctx, width, height), cmd(ctx) {
        copyBindings = copyPoints.bind({controlPoints, vertices});
        normalBindings = faceNormalsPass.bind({vertices, faceOffsets, faceVertices, faceNormals});
        meshBindings = meshPipeline.bind({vertices, faceNormals, corners, uvs});
        wireBindings = wirePipeline.bind({vertices});
        // Topology is uploaded once; positions every frame.
        gpu::uploadArrayNow<uint32_t>(ctx, faceOffsets, d.faceOffsets);
        gpu::uploadArrayNow<uint32_t>(ctx, faceVertices, d.faceVertices);
        gpu::uploadArrayNow<GpuCorner>(ctx, corners, d.corners);
        gpu::uploadArrayNow<glm::vec2>(ctx, uvs, d.uvs);
        gpu::uploadArrayNow<uint32_t>(ctx, triangles, d.triangles);
        gpu::uploadArrayNow<uint32_t>(ctx, edges, d.edges);
    }
    template <class T>
    static uint64_t bytes(const std::vector<T>& v) {
        return v.size() * sizeof(T);
    }

    gpu::Buffer staging, controlPoints, vertices, faceOffsets, faceVertices, faceNormals, corners,
        uvs, triangles, edges;
    gpu::ComputePipeline copyPoints, faceNormalsPass;
    gpu::GraphicsPipeline meshPipeline, wirePipeline;
    gpu::BindGroup copyBindings, normalBindings, meshBindings, wireBindings;
    gpu::RenderTarget target;
    gpu::CommandBuffer cmd;
};

Renderer::Renderer(gpu::Context& ctx, const Mesh& mesh, const RenderSettings& settings)
    : ctx_(ctx), settings_(settings), draw_(prepareControlMesh(mesh)) {
    if (settings.shade == Shade::Uv && !draw_.hasUVs)
        throw Error(ErrorKind::BadInput,
                    "--shade uv: the mesh has no texture coordinates (no FVUV chunk); use --shade "
                    "lit or normal");
    camera_ = frameCamera(settings.view, draw_.bounds, double(settings.width) / settings.height);
    gpu_ = std::make_unique<Gpu>(ctx, draw_, settings.width, settings.height);
}

Renderer::~Renderer() = default;

void Renderer::recordUpload() {
    auto& g = *gpu_;
    g.cmd.beginTimed("upload");
    g.cmd.copy(g.staging, g.controlPoints);
    g.cmd.endTimed();
    timedIsCompute_.push_back(true);
    g.cmd.barrier(gpu::Access::TransferWrite, gpu::Access::ComputeRead);
}

void Renderer::recordCompute() {
    auto& g = *gpu_;
    const VertexPush level0{0};
    g.cmd.beginTimed("copy control points");
    g.cmd.dispatch(g.copyPoints, g.copyBindings, static_cast<uint32_t>(draw_.controlPoints.size()),
                   level0);
    g.cmd.endTimed();
    timedIsCompute_.push_back(true);
    // Subdivision passes (per level: face, edge, vertex points; then limit points) will be
    // recorded here, each followed by this same barrier.
    g.cmd.barrier(gpu::Access::ComputeWrite, gpu::Access::ComputeRead);

    g.cmd.beginTimed("face normals");
    g.cmd.dispatch(g.faceNormalsPass, g.normalBindings,
                   static_cast<uint32_t>(draw_.faceOffsets.size() - 1), level0);
    g.cmd.endTimed();
    timedIsCompute_.push_back(true);
    g.cmd.barrier(gpu::Access::ComputeWrite, gpu::Access::VertexRead | gpu::Access::TransferRead);
}

void Renderer::recordDraw() {
    auto& g = *gpu_;
    const double aspect = double(settings_.width) / settings_.height;
    const glm::dmat4 vp = camera_.viewProjection(aspect);
    DrawPush push{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) push.viewProj[c * 4 + r] = static_cast<float>(vp[c][r]);
    // The camera's axes are the rows of the view matrix's rotation.
    const glm::dmat4 view = camera_.view();
    const glm::dvec3 right(view[0][0], view[1][0], view[2][0]);
    const glm::dvec3 up(view[0][1], view[1][1], view[2][1]);
    const glm::dvec3 forward(-view[0][2], -view[1][2], -view[2][2]);
    // Key light from over the viewer's left shoulder: a headlight, tilted so that faces turned
    // towards the camera are not all equally bright.
    const glm::dvec3 light = glm::normalize(-forward + 0.45 * up - 0.3 * right);
    for (int i = 0; i < 3; ++i) {
        push.eye[i] = static_cast<float>(camera_.eye[i]);
        push.light[i] = static_cast<float>(light[i]);
    }
    push.wireColor[0] = push.wireColor[1] = push.wireColor[2] = 0.006f; // sRGB ~ 0.07
    push.shade = static_cast<uint32_t>(settings_.shade);
    push.wirePull = kWirePull;

    std::array<float, 4> clear{};
    for (int i = 0; i < 3; ++i)
        clear[i] = static_cast<float>(srgbToLinear(settings_.background[i]));
    clear[3] = settings_.alpha ? 0.0f : 1.0f;

    g.cmd.beginTimed("draw");
    g.cmd.beginRendering(g.target, clear);
    g.cmd.drawIndexed(g.meshPipeline, g.meshBindings, g.triangles,
                      static_cast<uint32_t>(draw_.triangles.size()), 1,
                      gpu::CommandBuffer::asBytes(push));
    if (settings_.wire)
        g.cmd.drawIndexed(g.wirePipeline, g.wireBindings, g.edges,
                          static_cast<uint32_t>(draw_.edges.size()), 1,
                          gpu::CommandBuffer::asBytes(push));
    g.cmd.endRendering();
    g.cmd.endTimed();
    timedIsCompute_.push_back(false);

    g.cmd.beginTimed("readback");
    g.cmd.copyToReadback(g.target);
    g.cmd.endTimed();
    timedIsCompute_.push_back(false);
}

void Renderer::renderFrame() {
    auto& g = *gpu_;
    // The "animated mesh" path: the CPU writes this frame's control points, the GPU does the rest.
    g.staging.writeArray<glm::vec4>(draw_.controlPoints);
    timedIsCompute_.clear();
    g.cmd.begin();
    // The topology, corners, UVs and indices were uploaded once, in earlier submissions; a fence
    // wait orders those copies but does not make their writes visible to this frame's reads.
    g.cmd.barrier(gpu::Access::TransferWrite,
                  gpu::Access::ComputeRead | gpu::Access::VertexRead | gpu::Access::IndexRead);
    recordUpload();
    recordCompute();
    recordDraw();
    g.cmd.submitAndWait();
}

Image Renderer::image() const {
    Image img;
    img.width = settings_.width;
    img.height = settings_.height;
    img.channels = settings_.alpha ? 4 : 3;
    auto rgba = gpu_->target.pixels();
    if (settings_.alpha) {
        img.pixels = std::move(rgba);
        return img;
    }
    img.pixels.resize(size_t(img.width) * img.height * 3);
    for (size_t i = 0, n = size_t(img.width) * img.height; i < n; ++i)
        std::memcpy(&img.pixels[3 * i], &rgba[4 * i], 3);
    return img;
}

DrawnMesh Renderer::drawnMesh() {
    auto vertices =
        gpu::readbackArrayNow<glm::vec4>(ctx_, gpu_->vertices, draw_.controlPoints.size());
    auto normals =
        gpu::readbackArrayNow<glm::vec4>(ctx_, gpu_->faceNormals, draw_.faceOffsets.size() - 1);
    DrawnMesh out;
    out.vertices.reserve(draw_.corners.size());
    for (const GpuCorner& c : draw_.corners) {
        DrawnVertex v;
        const glm::vec4& p = vertices[c.vertex];
        const glm::vec4& n = normals[c.face];
        v.x = p.x, v.y = p.y, v.z = p.z;
        v.nx = n.x, v.ny = n.y, v.nz = n.z;
        v.ptex = static_cast<int32_t>(c.ptex);
        v.u = draw_.uvs[c.uv].x;
        v.v = draw_.uvs[c.uv].y;
        out.vertices.push_back(v);
    }
    out.triangles = draw_.triangles;
    return out;
}

FrameTimes Renderer::frameTimes() const {
    FrameTimes t;
    t.passes = gpu_->cmd.passTimes();
    for (size_t i = 0; i < t.passes.size(); ++i) {
        double ms = t.passes[i].ms;
        if (i < timedIsCompute_.size() && timedIsCompute_[i])
            t.computeMs += ms;
        else if (t.passes[i].name == "draw")
            t.drawMs += ms;
        t.totalMs += ms;
    }
    return t;
}

} // namespace limn::render
