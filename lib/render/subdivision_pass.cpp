#include "render/subdivision_pass.h"

#include "base/error.h"
#include "render/control_mesh.h"
#include "render_shaders.h"

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace limn::render {

namespace {

// The surface's fragment stage: each covered sample shaded on its own with --sample-shading
// (surface_per_sample.frag; why in draw_common.glsl's LIMN_SMOOTH_IN).
std::span<const uint32_t> surfaceFragment(const gpu::TargetFormat& target) {
    return target.sampleShading ? std::span<const uint32_t>(surface_per_sample_frag_spv)
                                : std::span<const uint32_t>(surface_frag_spv);
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
struct DisplacePush { // displace.comp
    float scale, mid;
};
struct AdaptiveDisplacePush { // adaptive_displace.comp
    float scale, mid;
    uint32_t seamFix, smoothUV;
};
struct AdaptiveNormalsPush { // adaptive_displaced_normals.comp
    uint32_t patchCount;
    float scale, mid;
};

// The displacement map for displace.comp: width, height, then channel 0 of each texel.
std::vector<uint32_t> mapWords(const FloatImage& img) {
    std::vector<uint32_t> w{img.width, img.height};
    w.reserve(2 + size_t(img.width) * img.height);
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
        uint32_t bits;
        std::memcpy(&bits, &img.values[i * img.channels], 4);
        w.push_back(bits);
    }
    return w;
}

using gpu::uploadBufferNow; // absent tables get one zero element

} // namespace

struct SubdivisionPass::Gpu {
    Gpu(gpu::Context& ctx, const SubdivisionDraw& d, bool evaluate, const Displacement* disp,
        const FloatImage* colour, const AdaptiveOptions* adaptiveOptions,
        gpu::TargetFormat target)
        : vertices(ctx, {"table vertices", uint64_t(d.totalVertices) * 16}),
          faceStarts(uploadBufferNow(ctx, "face-point starts", d.faceStarts)),
          faceIndices(uploadBufferNow(ctx, "face-point indices", d.faceIndices)),
          stencilStarts(uploadBufferNow(ctx, "stencil starts", d.stencilStarts)),
          stencilIndices(uploadBufferNow(ctx, "stencil indices", d.stencilIndices)),
          stencilWeights(uploadBufferNow(ctx, "stencil weights", d.stencilWeights)),
          limits(ctx, {"limit points", uint64_t(std::max(d.limitCount, 1u)) * 32}),
          patches(uploadBufferNow(ctx, "patches", d.patchBuffer())),
          irregular(uploadBufferNow(ctx, "irregular faces", d.irregularBuffer())),
          tessVertices(uploadBufferNow(ctx, "tessellation vertices", d.tessVertices)),
          // Indices are also read by the vertex stage for --shade levels.
          triangles(uploadBufferNow(ctx, "triangle indices", d.triangles, gpu::kIndex | gpu::kStorage)),
          triangleLevels(uploadBufferNow(ctx, "triangle levels", d.triangleLevels)),
          wireLines(uploadBufferNow(ctx, "wire lines", d.wireLines, gpu::kIndex)),
          texture(uploadBufferNow(ctx, "colour texture", textureWords(colour))),
          facePass(ctx, {"face points", subdiv_face_points_comp_spv, 3, sizeof(LevelPush)}),
          stencilPass(ctx, {"stencils", subdiv_stencils_comp_spv, 4, sizeof(LevelPush)}),
          limitPass(ctx, {"limit points", subdiv_limit_comp_spv, 5, sizeof(LimitPush)}),
          surface(ctx, {"surface", surface_vert_spv, surfaceFragment(target), 8, sizeof(DrawPush)}, target),
          surfaceFetch(ctx, {"surface (evaluated)", surface_fetch_vert_spv, surfaceFragment(target), 8,
                             sizeof(DrawPush)},
                       target) {
        // View-adaptive: the tessellation is written by compute passes each frame.
        if (adaptiveOptions) {
            AdaptiveOptions options = *adaptiveOptions;
            options.evaluated = evaluate;
            options.elementDomains = d.elementDomains;
            options.fvarNodes = d.fvarNodes;
            options.fvarRecords = d.fvarRecords;
            options.fvarCell = d.fvarCell;
            options.elementCrease.reserve(d.patches.size());
            for (const GpuPatch& p : d.patches) options.elementCrease.push_back(uint8_t((p.levelBoundary >> 16) & 0xFu));
            adaptive = std::make_unique<AdaptiveTess>(ctx, d.pieces, static_cast<uint32_t>(d.patches.size()),
                                                      vertices, patches, irregular, limits, options);
        }
        const gpu::Buffer& tv = adaptive ? adaptive->tessVertices() : tessVertices;
        const gpu::Buffer& tris = adaptive ? adaptive->triangles() : triangles;
        const gpu::Buffer& levels = adaptive ? adaptive->triangleLevels() : triangleLevels;
        faceBindings = facePass.bind({vertices, faceStarts, faceIndices});
        stencilBindings = stencilPass.bind({vertices, stencilStarts, stencilIndices, stencilWeights});
        for (LimitChunk& c : render::limitChunks(d, d.limitChunkBytes)) {
            LimitChunkBuffers b{uploadBufferNow(ctx, "limit starts", c.starts),
                                uploadBufferNow(ctx, "limit indices", c.indices),
                                uploadBufferNow(ctx, "limit weights", c.weights), {}, c.firstRow, c.rows};
            b.bindings = limitPass.bind({vertices, b.starts, b.indices, b.weights, limits});
            limitChunks.push_back(std::move(b));
        }
        surfaceBindings = surface.bind(
            {vertices, patches, irregular, limits, tv, tris, levels, texture});
        if (evaluate) {
            const uint64_t n = adaptive ? adaptive->vertexCapacity()
                                        : std::max<uint64_t>(d.tessVertices.size(), 1);
            evalPositions = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"evaluated positions", n * 16});
            evalNormals = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"evaluated normals", n * 16});
            evalInfo = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"evaluated ptex", n * 16});
            evalPass = std::make_unique<gpu::ComputePipeline>(
                ctx, gpu::ComputePipelineDesc{"evaluate surface", surface_eval_comp_spv, 8, sizeof(EvalPush)});
            evalBindings = evalPass->bind({vertices, patches, irregular, limits, tv,
                                           *evalPositions, *evalNormals, *evalInfo});
            wire = std::make_unique<gpu::GraphicsPipeline>(
                ctx, gpu::GraphicsPipelineDesc{"wire", wire_vert_spv, wire_frag_spv, 1, sizeof(DrawPush),
                                               gpu::Primitive::Lines, gpu::DepthTest::LessOrEqual, false},
                target);
            wireTriangles = std::make_unique<gpu::GraphicsPipeline>(
                ctx, gpu::GraphicsPipelineDesc{"wire (triangles)", wire_triangles_vert_spv, wire_frag_spv, 2,
                                               sizeof(DrawPush), gpu::Primitive::Lines,
                                               gpu::DepthTest::LessOrEqual, false},
                target);
            drawnPositions = evalPositions.get();
            drawnNormals = evalNormals.get();
            if (disp && adaptive) {
                // View-adaptive: samples from the owner's seam record, normals by
                // differences of the displaced surface (adaptive_displace*.comp).
                if (!d.seams) throw Error(ErrorKind::BadInput, "internal: displacement without seam data");
                // Smooth UVs: the records of the smooth UVs instead of SEAM's linear ones.
                const Seams& seams = d.smoothSeams.elements.empty() ? *d.seams : d.smoothSeams;
                sideUVs = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "seam elements", seams.elements));
                sideRanges = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "seam UVs", seams.uvs));
                map = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "displacement map", mapWords(*disp->map)));
                displaced = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"displaced positions", n * 16});
                displacedNormals = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"displaced normals", n * 16});
                displacePass = std::make_unique<gpu::ComputePipeline>(
                    ctx, gpu::ComputePipelineDesc{"displace (adaptive)", adaptive_displace_comp_spv, 7,
                                                  sizeof(AdaptiveDisplacePush)});
                normalsPass = std::make_unique<gpu::ComputePipeline>(
                    ctx, gpu::ComputePipelineDesc{"displaced normals (adaptive)", adaptive_displaced_normals_comp_spv,
                                                  8, sizeof(AdaptiveNormalsPush)});
                displaceBindings = displacePass->bind({*evalPositions, *evalNormals, tv, *sideUVs, *sideRanges,
                                                       *map, *displaced});
                normalsBindings = normalsPass->bind({vertices, patches, irregular, limits, tv,
                                                     adaptive->elementsBuffer(), *map, *displacedNormals});
                drawnPositions = displaced.get();
                drawnNormals = displacedNormals.get();
            } else if (disp) {
                sideRanges = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "displacement sample ranges", d.sideRanges));
                sideUVs = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "displacement sample UVs", d.sideUVs));
                map = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "displacement map", mapWords(*disp->map)));
                displaced = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"displaced positions", n * 16});
                incidentRanges = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "incident ranges", d.incidentRanges));
                incident = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "incident triangles", d.incidentTriangles));
                displacedNormals = std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{"displaced normals", n * 16});
                displacePass = std::make_unique<gpu::ComputePipeline>(
                    ctx, gpu::ComputePipelineDesc{"displace", displace_comp_spv, 6, sizeof(DisplacePush)});
                normalsPass = std::make_unique<gpu::ComputePipeline>(
                    ctx, gpu::ComputePipelineDesc{"displaced normals", displaced_normals_comp_spv, 5, 0});
                displaceBindings = displacePass->bind({*evalPositions, *evalNormals, *sideRanges, *sideUVs,
                                                       *map, *displaced});
                normalsBindings = normalsPass->bind({*displaced, triangles, *incidentRanges, *incident,
                                                     *displacedNormals});
                drawnPositions = displaced.get();
                drawnNormals = displacedNormals.get();
            }
            wireBindings = wire->bind({*drawnPositions});
            wireTriangleBindings = wireTriangles->bind({*drawnPositions, tris});
            fetchBindings = surfaceFetch.bind({*drawnPositions, *drawnNormals, tv, tris, levels, tris,
                                               tris, texture});
        }
    }

    gpu::Buffer vertices, faceStarts, faceIndices, stencilStarts, stencilIndices, stencilWeights,
        limits, patches, irregular, tessVertices, triangles,
        triangleLevels, wireLines, texture;
    std::unique_ptr<gpu::Buffer> sideRanges, sideUVs, map, displaced, incidentRanges, incident,
        displacedNormals;
    std::unique_ptr<gpu::ComputePipeline> displacePass, normalsPass;
    gpu::BindGroup displaceBindings, normalsBindings;
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
    std::unique_ptr<AdaptiveTess> adaptive;
    // The draw with back faces culled by the rasterizer (view-adaptive, closed surface seen from
    // outside; null otherwise).
    std::unique_ptr<gpu::GraphicsPipeline> culledDraw[2]; // [0] drops back faces, [1] front faces
};

SubdivisionPass::SubdivisionPass(gpu::Context& ctx, SubdivisionDraw draw, Eval eval,
                                 bool keepEvaluated, bool levels, const Displacement* displacement,
                                 const FloatImage* texture, const AdaptiveOptions* adaptive,
                                 gpu::TargetFormat target)
    : ctx_(ctx), draw_(std::move(draw)), eval_(eval), evaluate_(keepEvaluated || eval == Eval::Compute),
      levels_(levels), target_(target) {
    if (displacement) {
        if (eval != Eval::Compute)
            throw Error(ErrorKind::Usage, "--displace needs --eval compute (the displaced normals "
                                          "come from a compute pass over the displaced vertices)");
        if (!adaptive && draw_.sideRanges.size() != draw_.tessVertices.size())
            throw Error(ErrorKind::BadInput, "internal: draw data prepared without a displacement plan");
        displacement_ = *displacement;
    }
    if (adaptive && !draw_.adaptive)
        throw Error(ErrorKind::BadInput, "internal: view-adaptive tessellation needs draw data "
                                         "prepared for it");
    gpu_ = std::make_unique<Gpu>(ctx, draw_, evaluate_, displacement, texture, adaptive, target);
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
                                                  : std::span<const uint32_t>(surface_vert_spv),
                                            surfaceFragment(target_), 8, sizeof(DrawPush), gpu::Primitive::Triangles,
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
    totalsRead_ = false;
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
    if (g.adaptive) {
        cmd.barrier(compute, read);
        g.adaptive->setView(view_);
        g.adaptive->record(cmd, timed);
    }
    if (evaluate_) {
        cmd.barrier(compute, read);
        timed.begin(cmd, "evaluate surface", true);
        if (g.adaptive)
            cmd.dispatchIndirect(*g.evalPass, g.evalBindings, g.adaptive->totalsBuffer(),
                                 AdaptiveTess::kDispatchArgs, g.adaptive->vertexCapacity(),
                                 AdaptiveTess::kRowGroups,
                                 EvalPush{static_cast<uint32_t>(draw_.patches.size())});
        else
            cmd.dispatch(*g.evalPass, g.evalBindings, static_cast<uint32_t>(draw_.tessVertices.size()),
                         EvalPush{static_cast<uint32_t>(draw_.patches.size())});
        cmd.endTimed();
    }
    if (g.displacePass && g.adaptive) {
        const auto& args = g.adaptive->totalsBuffer();
        const uint32_t cap = g.adaptive->vertexCapacity();
        cmd.barrier(compute, read);
        timed.begin(cmd, "displace", true);
        cmd.dispatchIndirect(*g.displacePass, g.displaceBindings, args, AdaptiveTess::kDispatchArgs, cap,
                             AdaptiveTess::kRowGroups,
                             AdaptiveDisplacePush{displacement_.scale, displacement_.mid,
                                                  draw_.seamFix ? 1u : 0u,
                                                  draw_.smoothSeams.elements.empty() ? 0u : 1u});
        cmd.endTimed();
        cmd.barrier(compute, read);
        timed.begin(cmd, "displaced normals", true);
        cmd.dispatchIndirect(*g.normalsPass, g.normalsBindings, args, AdaptiveTess::kDispatchArgs, cap,
                             AdaptiveTess::kRowGroups,
                             AdaptiveNormalsPush{static_cast<uint32_t>(draw_.patches.size()), displacement_.scale,
                                                 displacement_.mid});
        cmd.endTimed();
    } else if (g.displacePass) {
        const uint32_t n = static_cast<uint32_t>(draw_.tessVertices.size());
        cmd.barrier(compute, read);
        timed.begin(cmd, "displace", true);
        cmd.dispatch(*g.displacePass, g.displaceBindings, n,
                     DisplacePush{displacement_.scale, displacement_.mid});
        cmd.endTimed();
        cmd.barrier(compute, read);
        timed.begin(cmd, "displaced normals", true);
        cmd.dispatch(*g.normalsPass, g.normalsBindings, n);
        cmd.endTimed();
    }
    cmd.barrier(compute, gpu::Access::VertexRead | gpu::Access::TransferRead);
}

void SubdivisionPass::recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) {
    auto& g = *gpu_;
    push.patchCount = static_cast<uint32_t>(draw_.patches.size());
    const auto& bindings = eval_ == Eval::Compute ? g.fetchBindings : g.surfaceBindings;
    // --back-faces shows back faces on purpose (crack counts): never culled then.
    const bool cull = mayCullBackFaces_ && view_.facing != 0 && !(push.flags & kDrawBackFaceKey);
    const auto& pipeline = cull ? culledPipeline(view_.facing) : eval_ == Eval::Compute ? g.surfaceFetch : g.surface;
    if (g.adaptive) {
        if (levels_) {
            push.flags |= kDrawPullIndices;
            cmd.drawIndirect(pipeline, bindings, g.adaptive->totalsBuffer(), AdaptiveTess::kDrawArgs,
                             gpu::CommandBuffer::asBytes(push));
        } else {
            push.flags &= ~kDrawPullIndices;
            cmd.drawIndexedIndirect(pipeline, bindings, g.adaptive->triangles(), g.adaptive->totalsBuffer(),
                                    AdaptiveTess::kIndexedDrawArgs, gpu::CommandBuffer::asBytes(push));
        }
        // Outlines exist for the fixed grids only (the renderer picks them for Wire::Outlines).
        if (wire == Wire::Triangles && g.wireTriangles)
            cmd.drawIndirect(*g.wireTriangles, g.wireTriangleBindings, g.adaptive->totalsBuffer(),
                             AdaptiveTess::kWireDrawArgs, gpu::CommandBuffer::asBytes(push));
        return;
    }
    if (levels_) {
        push.flags |= kDrawPullIndices;
        cmd.draw(pipeline, bindings, static_cast<uint32_t>(draw_.triangles.size()), 1,
                 gpu::CommandBuffer::asBytes(push));
    } else {
        push.flags &= ~kDrawPullIndices;
        cmd.drawIndexed(pipeline, bindings, g.triangles, static_cast<uint32_t>(draw_.triangles.size()),
                        1, gpu::CommandBuffer::asBytes(push));
    }
    if (wire == Wire::Outlines && g.wire)
        cmd.drawIndexed(*g.wire, g.wireBindings, g.wireLines, static_cast<uint32_t>(draw_.wireLines.size()),
                        1, gpu::CommandBuffer::asBytes(push));
    if (wire == Wire::Triangles && g.wireTriangles)
        cmd.draw(*g.wireTriangles, g.wireTriangleBindings, static_cast<uint32_t>(2 * draw_.triangles.size()), 1,
                 gpu::CommandBuffer::asBytes(push));
}

std::string SubdivisionPass::tessellationShortfall() const {
    const AdaptiveTotals* t = lastTotals();
    if (!t || !t->overflow) return {};
    return "the view-adaptive tessellation of this view needs " + t->need() +
           (t->overBudget || t->cutShort
                ? std::string()
                : ", more than its buffers hold (" + std::to_string(gpu_->adaptive->vertexCapacity()) +
                      " vertices, " + std::to_string(gpu_->adaptive->triangleCapacity()) + " triangles)") +
           "; nothing written: raise --max-error or --edge-pixels, or lower --tess";
}

DrawnMesh SubdivisionPass::drawnMesh() {
    size_t n = draw_.tessVertices.size();
    AdaptiveTotals totals;
    if (gpu_->adaptive) {
        if (std::string shortfall = tessellationShortfall(); !shortfall.empty())
            throw Error(ErrorKind::BadInput, "--mesh-out: " + shortfall);
        totals = *lastTotals();
        n = totals.writtenVertices;
    }
    DrawnMesh out = readDrawnVertices(ctx_, gpu_->drawnPositions, gpu_->drawnNormals, n);
    auto info = gpu::readbackArrayNow<glm::uvec4>(ctx_, *gpu_->evalInfo, n);
    for (size_t i = 0; i < n; ++i) {
        DrawnVertex& v = out.vertices[i];
        v.ptex = static_cast<int32_t>(info[i].x);
        std::memcpy(&v.u, &info[i].y, 4);
        std::memcpy(&v.v, &info[i].z, 4);
        if (draw_.hasUVs && !gpu_->adaptive)
            v.s = draw_.tessVertices[i].u, v.t = draw_.tessVertices[i].v;
        if (!gpu_->adaptive)
            v.approximate = drawnPointIsApproximate(draw_, draw_.tessVertices[i].element, draw_.tessVertices[i].st);
    }
    out.hasTexCoords = draw_.hasUVs; // the tessellation split its vertices at UV seams
    if (gpu_->adaptive) {
        // The vertices the view-adaptive passes emitted this frame: (element, s|t, own-chart UV).
        auto emitted = gpu::readbackArrayNow<glm::uvec4>(ctx_, gpu_->adaptive->tessVertices(), n);
        for (size_t i = 0; i < n; ++i) {
            if (draw_.hasUVs) {
                std::memcpy(&out.vertices[i].s, &emitted[i].z, 4);
                std::memcpy(&out.vertices[i].t, &emitted[i].w, 4);
            }
            out.vertices[i].approximate = drawnPointIsApproximate(draw_, emitted[i].x, emitted[i].y);
        }
        auto tris = gpu::readbackArrayNow<uint32_t>(ctx_, gpu_->adaptive->triangles(),
                                                    size_t(totals.writtenTriangles) * 3);
        out.triangles = std::move(tris);
    } else {
        out.triangles = draw_.triangles;
    }
    return out;
}

const AdaptiveTotals* SubdivisionPass::lastTotals() const {
    if (!gpu_->adaptive) return nullptr;
    if (!totalsRead_) {
        totals_ = gpu_->adaptive->readTotals(ctx_);
        totalsRead_ = true;
    }
    return &totals_;
}

uint64_t SubdivisionPass::triangleCount() const {
    if (const AdaptiveTotals* t = lastTotals()) return t->drawnTriangles; // after culling and any overflow
    return draw_.triangles.size() / 3;
}

uint64_t SubdivisionPass::verticesEvaluated() const {
    // Table vertices computed by the passes, limit points, and tessellation vertices evaluated
    // by the vertex stage (at least once each; the draw may evaluate a shared one more often).
    // View-adaptive: also the three points per edge piece that decide its rate.
    const uint64_t tables = draw_.totalVertices - draw_.baseVertices + draw_.limitCount;
    if (const AdaptiveTotals* t = lastTotals())
        return tables + 3ull * gpu_->adaptive->pieceCount() + t->writtenVertices;
    return tables + draw_.tessVertices.size();
}

uint64_t SubdivisionPass::bufferBytes() const {
    auto& g = *gpu_;
    uint64_t sum = 0;
    for (const gpu::Buffer* b : {&g.vertices, &g.faceStarts, &g.faceIndices, &g.stencilStarts,
                                 &g.stencilIndices, &g.stencilWeights, &g.limits, &g.patches, &g.irregular, &g.tessVertices,
                                 &g.triangles, &g.triangleLevels, &g.wireLines, &g.texture})
        sum += b->size();
    for (const auto* b : {g.evalPositions.get(), g.evalNormals.get(), g.evalInfo.get(), g.sideRanges.get(),
                          g.sideUVs.get(), g.map.get(), g.displaced.get(), g.incidentRanges.get(),
                          g.incident.get(), g.displacedNormals.get()})
        if (b) sum += b->size();
    for (const auto& c : g.limitChunks) sum += c.starts.size() + c.indices.size() + c.weights.size();
    if (g.adaptive) sum += g.adaptive->bufferBytes();
    return sum;
}

} // namespace limn::render
