#include "render/subdivision_pass.h"

#include "base/error.h"
#include "render/control_mesh.h"
#include "render/fixed_grids.h"
#include "render_shaders.h"

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace limn::render {

namespace {

// The surface's fragment stage: each covered sample shaded on its own with --sample-shading
// (surface_per_sample.frag; why in draw_common.glsl's LIMN_SMOOTH_IN), and for the lit and
// texture shadings the variants without the other modes' code (why in draw_common.glsl).
std::span<const uint32_t> surfaceFragment(const gpu::TargetFormat& target, Shade shade, bool pixelNormals) {
    using Code = std::span<const uint32_t>;
    if (shade == Shade::Lit && pixelNormals)
        return target.sampleShading ? Code(surface_lit_pixel_per_sample_frag_spv) : Code(surface_lit_pixel_frag_spv);
    if (shade == Shade::Lit)
        return target.sampleShading ? Code(surface_lit_per_sample_frag_spv) : Code(surface_lit_frag_spv);
    if (shade == Shade::Texture)
        return target.sampleShading ? Code(surface_texture_per_sample_frag_spv) : Code(surface_texture_frag_spv);
    return target.sampleShading ? Code(surface_per_sample_frag_spv) : Code(surface_frag_spv);
}

// The surface's vertex stage: with per-pixel normals it also hands the fragment stage each
// triangle's element parameters and control net (surface_vertex.glsl).
std::span<const uint32_t> surfaceVertex(bool pixelNormals) {
    using Code = std::span<const uint32_t>;
    return pixelNormals ? Code(surface_pixel_vert_spv) : Code(surface_vert_spv);
}

struct LevelPush { // subdiv_face_points.comp, subdiv_stencils.comp
    uint32_t firstOut, firstRow;
};
struct LimitPush { // subdiv_limit.comp
    uint32_t rowsPerTable, firstRow;
};
struct EvalPush { // surface_eval.comp
    uint32_t patchCount;
};

using gpu::uploadBufferNow; // absent tables get one zero element

} // namespace

struct SubdivisionPass::Gpu {
    Gpu(gpu::Context& ctx, const SubdivisionDraw& d, bool evaluate, const Displacement* disp,
        const FloatImage* colour, const AdaptiveOptions* adaptiveOptions, gpu::TargetFormat target, Shade shade,
        bool pixelNormals)
        : vertices(ctx, {"table vertices", uint64_t(d.totalVertices) * 16}),
          faceStarts(uploadBufferNow(ctx, "face-point starts", d.faceStarts)),
          faceIndices(uploadBufferNow(ctx, "face-point indices", d.faceIndices)),
          stencilStarts(uploadBufferNow(ctx, "stencil starts", d.stencilStarts)),
          stencilIndices(uploadBufferNow(ctx, "stencil indices", d.stencilIndices)),
          stencilWeights(uploadBufferNow(ctx, "stencil weights", d.stencilWeights)),
          limits(ctx, {"limit points", uint64_t(std::max(d.limitCount, 1u)) * 32}),
          patches(uploadBufferNow(ctx, "patches", d.patchBuffer())),
          irregular(uploadBufferNow(ctx, "irregular faces", d.irregularBuffer())),
          surfaceBuffers{vertices, patches, irregular, limits},
          // The one choice between the tessellations (tessellation.h): view-adaptive passes
          // that write it each frame, or the fixed grids uploaded once.
          tess(adaptiveOptions ? std::unique_ptr<Tessellation>(std::make_unique<AdaptiveTess>(
                                     ctx, d, surfaceBuffers, *adaptiveOptions, evaluate))
                               : std::make_unique<FixedGrids>(ctx, d)),
          texture(uploadBufferNow(ctx, "colour texture", textureWords(colour))),
          facePass(ctx, {"face points", subdiv_face_points_comp_spv, 3, sizeof(LevelPush)}),
          stencilPass(ctx, {"stencils", subdiv_stencils_comp_spv, 4, sizeof(LevelPush)}),
          limitPass(ctx, {"limit points", subdiv_limit_comp_spv, 5, sizeof(LimitPush)}),
          surface(ctx, {"surface", surfaceVertex(pixelNormals), surfaceFragment(target, shade, pixelNormals), 8,
                        sizeof(DrawPush)},
                  target),
          surfaceFetch(ctx, {"surface (evaluated)", surface_fetch_vert_spv, surfaceFragment(target, shade, false), 8,
                             sizeof(DrawPush)},
                       target) {
        const gpu::Buffer& tv = tess->tessVertices();
        const gpu::Buffer& tris = tess->triangles();
        const gpu::Buffer& levels = tess->triangleLevels();
        faceBindings = facePass.bind({vertices, faceStarts, faceIndices});
        stencilBindings = stencilPass.bind({vertices, stencilStarts, stencilIndices, stencilWeights});
        for (LimitChunk& c : render::limitChunks(d, d.limitChunkBytes)) {
            LimitChunkBuffers b{uploadBufferNow(ctx, "limit starts", c.starts),
                                uploadBufferNow(ctx, "limit indices", c.indices),
                                uploadBufferNow(ctx, "limit weights", c.weights), {}, c.firstRow, c.rows};
            b.bindings = limitPass.bind({vertices, b.starts, b.indices, b.weights, limits});
            limitChunks.push_back(std::move(b));
        }
        surfaceBindings = surface.bind({vertices, patches, irregular, limits, tv, tris, levels, texture});
        if (!evaluate) return;
        const uint64_t n = tess->vertexCapacity();
        evalPositions = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"evaluated positions", n * 16});
        evalNormals = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"evaluated normals", n * 16});
        evalInfo = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"evaluated ptex", n * 16});
        evalPass = std::make_unique<gpu::ComputePipeline>(
            ctx, gpu::ComputePipelineDesc{"evaluate surface", surface_eval_comp_spv, 8, sizeof(EvalPush)});
        evalBindings = evalPass->bind({vertices, patches, irregular, limits, tv, *evalPositions, *evalNormals, *evalInfo});
        wire = std::make_unique<gpu::GraphicsPipeline>(
            ctx, gpu::GraphicsPipelineDesc{"wire", wire_vert_spv, wire_frag_spv, 1, sizeof(DrawPush),
                                           gpu::Primitive::Lines, gpu::DepthTest::LessOrEqual, false},
            target);
        wireTriangles = std::make_unique<gpu::GraphicsPipeline>(
            ctx, gpu::GraphicsPipelineDesc{"wire (triangles)", wire_triangles_vert_spv, wire_frag_spv, 2,
                                           sizeof(DrawPush), gpu::Primitive::Lines, gpu::DepthTest::LessOrEqual,
                                           false},
            target);
        drawnPositions = evalPositions.get();
        drawnNormals = evalNormals.get();
        if (disp) {
            displacement = tess->makeDisplacement(
                ctx, d, surfaceBuffers,
                DisplacementInputs{*disp->map, disp->scale, disp->mid, *evalPositions, *evalNormals, n});
            drawnPositions = &displacement->positions();
            drawnNormals = &displacement->normals();
        }
        wireBindings = wire->bind({*drawnPositions});
        wireTriangleBindings = wireTriangles->bind({*drawnPositions, tris});
        fetchBindings = surfaceFetch.bind({*drawnPositions, *drawnNormals, tv, tris, levels, tris, tris, texture});
    }

    gpu::Buffer vertices, faceStarts, faceIndices, stencilStarts, stencilIndices, stencilWeights, limits, patches,
        irregular;
    SurfaceBuffers surfaceBuffers;
    std::unique_ptr<Tessellation> tess;
    gpu::Buffer texture;
    std::unique_ptr<DisplacementPasses> displacement;
    gpu::ComputePipeline facePass, stencilPass, limitPass;
    gpu::GraphicsPipeline surface, surfaceFetch;
    gpu::BindGroup faceBindings, stencilBindings, surfaceBindings, fetchBindings;
    struct LimitChunkBuffers { // the limit tables, cut under the binding limit (limitChunks)
        gpu::Buffer starts, indices, weights;
        gpu::BindGroup bindings;
        uint32_t firstRow, rows;
    };
    std::vector<LimitChunkBuffers> limitChunks;
    std::unique_ptr<gpu::Buffer> evalPositions, evalNormals, evalInfo;
    // What the draw reads: the evaluated or the displaced surface (null without evaluation).
    const gpu::Buffer* drawnPositions = nullptr;
    const gpu::Buffer* drawnNormals = nullptr;
    std::unique_ptr<gpu::ComputePipeline> evalPass;
    std::unique_ptr<gpu::GraphicsPipeline> wire, wireTriangles;
    gpu::BindGroup evalBindings, wireBindings, wireTriangleBindings;
    // The draw with back faces culled by the rasterizer (view-adaptive, closed surface seen from
    // outside; null otherwise).
    std::unique_ptr<gpu::GraphicsPipeline> culledDraw[2]; // [0] drops back faces, [1] front faces
};

SubdivisionPass::SubdivisionPass(gpu::Context& ctx, SubdivisionDraw draw, Eval eval,
                                 bool keepEvaluated, Shade shade, const Displacement* displacement,
                                 const FloatImage* texture, const AdaptiveOptions* adaptive,
                                 gpu::TargetFormat target)
    : ctx_(ctx), draw_(std::move(draw)), eval_(eval), evaluate_(keepEvaluated || eval == Eval::Compute),
      levels_(shade == Shade::Levels),
      pixelNormals_(adaptive && adaptive->pixelNormals && eval == Eval::Vertex && shade == Shade::Lit), shade_(shade),
      target_(target) {
    if (displacement && eval != Eval::Compute)
        throw Error(ErrorKind::Usage, "--displace needs --eval compute (the displaced normals "
                                      "come from a compute pass over the displaced vertices)");
    gpu_ = std::make_unique<Gpu>(ctx, draw_, evaluate_, displacement, texture, adaptive, target, shade, pixelNormals_);
    mayCullBackFaces_ = adaptive && adaptive->backFaceCull && draw_.closed;
    if (mayCullBackFaces_) {
        orientation_ = draw_.orientation;
        // Seen from outside the control points' box (setView), the draw culls the faces that
        // face away by this orientation: lavapipe's compile of it (about 45 ms) overlaps the rest
        // of the set-up. The pipeline object is made here; the other thread only compiles it.
        if (orientation_ != 0) {
            const gpu::GraphicsPipeline& p = culledPipeline(orientation_);
            culledCompile_ = std::async(std::launch::async, [&p] { (void)p.handle(); });
        }
    }
}

// On a closed, consistently oriented surface seen from outside, the first face along any ray from
// the eye is a front face, so back faces never show and the rasterizer may drop them (the same
// image, bytes included; on lavapipe triangle setup is most of a view-adaptive draw). Which
// winding is "back" follows the orientation: with positive volume the faces wind
// counter-clockwise seen from outside, as the pipeline's front faces do (the projection flips Y
// for Vulkan's framebuffer and the winding with it). Made on first use: an animated surface may
// turn inside out and need the other one.
const gpu::GraphicsPipeline& SubdivisionPass::culledPipeline(float facing) {
    if (culledCompile_.valid()) culledCompile_.get(); // compiled (or its error thrown) before use
    auto& slot = gpu_->culledDraw[facing > 0 ? 0 : 1];
    if (!slot) {
        const bool fetch = eval_ == Eval::Compute;
        slot = std::make_unique<gpu::GraphicsPipeline>(
            ctx_, gpu::GraphicsPipelineDesc{"surface (back faces culled)",
                                            fetch ? std::span<const uint32_t>(surface_fetch_vert_spv)
                                                  : surfaceVertex(pixelNormals_),
                                            surfaceFragment(target_, shade_, pixelNormals_), 8, sizeof(DrawPush), gpu::Primitive::Triangles,
                                            gpu::DepthTest::Less, true, facing > 0 ? gpu::Cull::Back : gpu::Cull::Front},
            target_);
    }
    return *slot;
}

void SubdivisionPass::setControlPoints(const Bounds& bounds, float orientation) {
    draw_.bounds = bounds;
    if (mayCullBackFaces_) orientation_ = orientation;
}

SubdivisionPass::~SubdivisionPass() = default;

void SubdivisionPass::setView(const glm::mat4& viewProj, const glm::dvec3& eye, uint32_t width,
                              uint32_t height) {
    view_ = {viewProj, width, height, glm::vec3(eye), 0.0f};
    // Back faces hide behind front faces only on a closed surface seen from outside it: outside
    // the control points' box, which holds the limit surface (convex hull property).
    const Bounds& b = draw_.bounds;
    const bool outside = glm::any(glm::lessThan(eye, b.min)) || glm::any(glm::greaterThan(eye, b.max));
    if (outside) view_.facing = orientation_;
}

const gpu::Buffer& SubdivisionPass::vertexBuffer() const { return gpu_->vertices; }

void SubdivisionPass::recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) {
    auto& g = *gpu_;
    const auto compute = gpu::Access::ComputeWrite, read = gpu::Access::ComputeRead;
    for (const LevelPasses& p : draw_.levels) {
        // Face points first: the edge and vertex points of the same level read them.
        const std::string L = " L" + std::to_string(p.level);
        timed.begin(cmd, "face points" + L, true);
        cmd.dispatch(g.facePass, g.faceBindings, p.faceCount, LevelPush{p.faceFirstOut, p.faceFirstRow});
        cmd.endTimed();
        cmd.barrier(compute, read);
        timed.begin(cmd, "edge points" + L, true);
        cmd.dispatch(g.stencilPass, g.stencilBindings, p.edgeCount, LevelPush{p.edgeFirstOut, p.edgeFirstRow});
        cmd.endTimed();
        timed.begin(cmd, "vertex points" + L, true);
        cmd.dispatch(g.stencilPass, g.stencilBindings, p.vertexCount,
                     LevelPush{p.vertexFirstOut, p.vertexFirstRow});
        cmd.endTimed();
        cmd.barrier(compute, read);
    }
    timed.begin(cmd, "limit points", true);
    for (const auto& c : g.limitChunks)
        cmd.dispatch(g.limitPass, c.bindings, c.rows, LimitPush{c.rows, c.firstRow});
    cmd.endTimed();
    g.tess->record(cmd, timed, view_);
    if (evaluate_) {
        cmd.barrier(compute, read);
        timed.begin(cmd, "evaluate surface", true);
        g.tess->dispatchPerVertex(cmd, *g.evalPass, g.evalBindings,
                                  gpu::CommandBuffer::asBytes(EvalPush{static_cast<uint32_t>(draw_.patches.size())}));
        cmd.endTimed();
    }
    if (g.displacement) g.displacement->record(cmd, timed);
    cmd.barrier(compute, gpu::Access::VertexRead | gpu::Access::TransferRead);
}

void SubdivisionPass::recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) {
    auto& g = *gpu_;
    if (push.shade != static_cast<uint32_t>(shade_))
        throw Error(ErrorKind::BadInput, "internal: a subdivision draw shaded otherwise than its pass was built for");
    push.patchCount = static_cast<uint32_t>(draw_.patches.size());
    const auto& bindings = eval_ == Eval::Compute ? g.fetchBindings : g.surfaceBindings;
    // --back-faces shows back faces on purpose (crack counts): never culled then.
    const bool cull = mayCullBackFaces_ && view_.facing != 0 && !(push.flags & kDrawBackFaceKey);
    const auto& pipeline = cull ? culledPipeline(view_.facing) : eval_ == Eval::Compute ? g.surfaceFetch : g.surface;
    if (levels_)
        push.flags |= kDrawPullIndices;
    else
        push.flags &= ~kDrawPullIndices;
    g.tess->drawTriangles(cmd, pipeline, bindings, gpu::CommandBuffer::asBytes(push), levels_);
    if (wire != Wire::None && g.wire)
        g.tess->drawWire(cmd, wire, {*g.wire, g.wireBindings, *g.wireTriangles, g.wireTriangleBindings},
                         gpu::CommandBuffer::asBytes(push));
}

std::string SubdivisionPass::tessellationShortfall() const { return gpu_->tess->shortfall(ctx_); }

exporting::DrawnMesh SubdivisionPass::drawnMesh() {
    const size_t n = gpu_->tess->drawnVertexCount(ctx_);
    exporting::DrawnMesh out = readDrawnVertices(ctx_, gpu_->drawnPositions, gpu_->drawnNormals, n);
    auto info = gpu::readbackArrayNow<glm::uvec4>(ctx_, *gpu_->evalInfo, n);
    for (size_t i = 0; i < n; ++i) {
        exporting::DrawnVertex& v = out.vertices[i];
        v.ptex = static_cast<int32_t>(info[i].x);
        std::memcpy(&v.u, &info[i].y, 4);
        std::memcpy(&v.v, &info[i].z, 4);
    }
    out.hasTexCoords = draw_.hasUVs; // the tessellation split its vertices at UV seams
    gpu_->tess->finishDrawnMesh(ctx_, out);
    return out;
}

const AdaptiveTotals* SubdivisionPass::lastTotals() const { return gpu_->tess->lastTotals(ctx_); }

uint64_t SubdivisionPass::triangleCount() const { return gpu_->tess->triangleCount(ctx_); }

uint64_t SubdivisionPass::verticesEvaluated() const {
    // Table vertices computed by the passes, limit points, and tessellation vertices evaluated
    // by the vertex stage (at least once each; the draw may evaluate a shared one more often).
    return draw_.totalVertices - draw_.baseVertices + draw_.limitCount + gpu_->tess->verticesEvaluated(ctx_);
}

uint64_t SubdivisionPass::bufferBytes() const {
    auto& g = *gpu_;
    uint64_t sum = g.tess->bufferBytes();
    for (const gpu::Buffer* b : {&g.vertices, &g.faceStarts, &g.faceIndices, &g.stencilStarts, &g.stencilIndices,
                                 &g.stencilWeights, &g.limits, &g.patches, &g.irregular, &g.texture})
        sum += b->size();
    for (const auto* b : {g.evalPositions.get(), g.evalNormals.get(), g.evalInfo.get()})
        if (b) sum += b->size();
    if (g.displacement) sum += g.displacement->bufferBytes();
    for (const auto& c : g.limitChunks) sum += c.starts.size() + c.indices.size() + c.weights.size();
    return sum;
}

} // namespace limn::render
