#include "render/adaptive/adaptive_tess.h"

#include "render/adaptive/adaptive_displacement.h"

#include "base/error.h"
#include "render_shaders.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cstring>
#include <future>
#include <vector>

namespace limn::render {

namespace {

struct CullPush { // adaptive_cull.comp
    float viewProj[16];
    float eye[4];
    uint32_t patchCount, enabled; // enabled: bit 0 cull, bits 8-15 the sample positions' count
    float viewport[2];
    uint32_t samples[2]; // 4 sample positions, x | y << 8 in 1/256 pixel, 16 bits each
};
struct RatePush { // adaptive_rates.comp
    float viewProj[16];
    float halfViewport[2];
    float edgePixels;
    uint32_t tess, patchCount;
    float texels;
    float maxError;
    float interiorError;
};
static_assert(sizeof(RatePush) + 16 <= 128); // after LIMN_DISPATCH_HEADER, within WebGPU's immediates
struct CountPush { // adaptive_counts.comp
    uint32_t tess;
    uint32_t vertexLoops; // loop iterations the emit pass spends per vertex beyond its own
    uint32_t sharePoints;
    uint32_t sampleCount; // the flat elements' sample test, with CullPush's positions
    uint32_t samples[2];
    uint32_t partialFans; // not when the whole surface is read (AdaptiveOptions::evaluated)
};
// Smooth UVs: fvar_eval.glsl's quadtree walk, one iteration a level (tables hold at most 10)
// plus the step into the record, per emitted vertex.
constexpr uint32_t kFvarLoopsPerVertex = 12;
struct ScanPush { // adaptive_scan.comp
    uint32_t elementCount, vertexCapacity, triangleCapacity, rowGroups, evalGroupSize, vertexBase;
};
struct EmitPush { // adaptive_emit.comp
    uint32_t pointBase, triangleCapacity, smoothUV;
    float fvarCell;
    uint32_t domainBase, nodeBase, recordBase, sharePoints, vertexCapacity, pixelNormals;
};

constexpr uint32_t kTotalsWords = 24;
constexpr uint32_t kEvalGroupSize = 64; // surface_eval.comp's local_size_x

void copyMatrix(const glm::mat4& m, float out[16]) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out[c * 4 + r] = m[c][r];
}

} // namespace

AdaptivePipelines::AdaptivePipelines(gpu::Context& ctx) {
    auto make = [&ctx](const gpu::ComputePipelineDesc& d) { return std::make_unique<gpu::ComputePipeline>(ctx, d); };
    // Vulkan creates pipelines of one device from any thread. A throw on this thread waits for
    // the other in the future's destructor.
    std::future<void> second = std::async(std::launch::async, [&] {
        cull = make({"adaptive cull", adaptive_cull_comp_spv, 5, sizeof(CullPush)});
        counts = make({"adaptive counts", adaptive_counts_comp_spv, 6, sizeof(CountPush)});
        scan = make({"adaptive scan", adaptive_scan_comp_spv, 2, sizeof(ScanPush)});
    });
    rates = make({"adaptive rates", adaptive_rates_comp_spv, 8, sizeof(RatePush)});
    emit = make({"adaptive emit", adaptive_emit_comp_spv, 8, sizeof(EmitPush)});
    second.get();
}

namespace {

// The draw data's per-element inputs of the emit pass: smooth UVs and crease sides.
AdaptiveOptions withDrawData(AdaptiveOptions options, const SubdivisionDraw& d, bool evaluated) {
    if (!d.adaptive)
        throw Error(ErrorKind::BadInput, "internal: view-adaptive tessellation needs draw data prepared for it");
    options.evaluated = evaluated;
    options.elementDomains = d.elementDomains;
    options.fvarNodes = d.fvarNodes;
    options.fvarRecords = d.fvarRecords;
    options.fvarCell = d.fvarCell;
    options.elementCrease.reserve(d.patches.size());
    for (const GpuPatch& p : d.patches) options.elementCrease.push_back(uint8_t((p.levelBoundary >> 16) & 0xFu));
    return options;
}

} // namespace

AdaptiveTess::AdaptiveTess(gpu::Context& ctx, const SubdivisionDraw& d, const SurfaceBuffers& surface,
                           AdaptiveOptions options, bool evaluated)
    : AdaptiveTess(ctx, d.pieces, static_cast<uint32_t>(d.patches.size()), surface,
                   withDrawData(std::move(options), d, evaluated)) {
    draw_ = &d;
}

AdaptiveTess::AdaptiveTess(gpu::Context& ctx, const EdgePieces& ep, uint32_t patchCount, const SurfaceBuffers& surface,
                           const AdaptiveOptions& options)
    : options_(options), elementCount_(static_cast<uint32_t>(ep.elements.size())),
      pieceCount_(static_cast<uint32_t>(ep.pieces.size())), patchCount_(patchCount) {
    if (options.tess < 1) throw Error(ErrorKind::Usage, "--tess must be at least 1");
    std::vector<GpuAdaptiveElement> elements;
    elements.reserve(ep.elements.size());
    // Capacity: what the finest rates could need, within the budget.
    uint64_t maxV = 0, maxT = 0;
    const uint64_t tess = options.tess;
    for (const AdaptiveElement& e : ep.elements) {
        GpuAdaptiveElement g{};
        uint64_t B = 0;
        for (int k = 0; k < 4; ++k) {
            g.sideFirst[k] = e.sideFirst[k], g.sideCount[k] = e.sideCount[k];
            for (uint32_t p = 0; p < e.sideCount[k]; ++p)
                B += std::max<uint64_t>(1, std::min<uint64_t>(tess, ep.pieces[ep.sidePieces[e.sideFirst[k] + p].piece].span));
            g.uv[2 * k] = e.cornerUV[k].x, g.uv[2 * k + 1] = e.cornerUV[k].y;
        }
        g.level = e.level;
        g.crease = elements.size() < options.elementCrease.size() ? options.elementCrease[elements.size()] : 0;
        elements.push_back(g);
        const uint64_t m = tess;
        maxV += B + (m <= 2 ? 1 : (m - 1) * (m - 1));
        maxT += m <= 2 ? B : 2 * (m - 2) * (m - 2) + B + 4 * (m - 2);
    }
    const uint64_t limitV = gpu::kMaxStorageBufferBytes / 16, limitT = gpu::kMaxStorageBufferBytes / 12;
    // Shared points: the first slots are the points', so that elements draw their corners
    // from one vertex each instead of four copies (the vertex stage evaluates each slot once
    // per batch of triangles, the compute evaluation once); only where nothing reads a
    // vertex's own-chart UV (which differs across a UV seam) or the whole surface.
    if (options.sharePoints && ep.points.size() < limitV / 2) {
        sharedPoints_ = static_cast<uint32_t>(ep.points.size());
        maxV += sharedPoints_;
    }
    uint64_t budgetV = (options.maxVertices ? options.maxVertices : limitV) + sharedPoints_;
    uint64_t budgetT = options.maxTriangles ? options.maxTriangles : limitT;
    capV_ = static_cast<uint32_t>(std::max<uint64_t>(1, std::min({maxV, budgetV, limitV})));
    capT_ = static_cast<uint32_t>(std::max<uint64_t>(1, std::min({maxT, budgetT, limitT})));

    std::vector<glm::uvec4> pieces;
    pieces.reserve(2 * ep.pieces.size() + ep.points.size() + ep.sidePieces.size());
    for (const EdgePiece& p : ep.pieces) {
        uint32_t uvBits;
        std::memcpy(&uvBits, &p.uvLength, 4);
        pieces.push_back({p.owner, p.ownerStart, p.ownerEnd, p.span});
        pieces.push_back({p.users[0], p.users[1], uvBits, 0});
    }
    pointBase_ = static_cast<uint32_t>(pieces.size());
    for (const EdgePoint& q : ep.points) pieces.push_back({q.owner, q.st, 0, 0});
    if (!options.fvarNodes.empty()) { // smooth UVs: domains, quadtree, records (EmitPush)
        auto bits = [](const glm::vec4& v) {
            glm::uvec4 u;
            std::memcpy(&u, &v, 16);
            return u;
        };
        domainBase_ = static_cast<uint32_t>(pieces.size());
        for (const glm::vec4& d : options.elementDomains) pieces.push_back(bits(d));
        nodeBase_ = static_cast<uint32_t>(pieces.size());
        for (size_t i = 0; i < options.fvarNodes.size(); i += 4) {
            glm::uvec4 q(0xFFFFFFFFu);
            for (size_t k = 0; k < 4 && i + k < options.fvarNodes.size(); ++k) q[int(k)] = options.fvarNodes[i + k];
            pieces.push_back(q);
        }
        recordBase_ = static_cast<uint32_t>(pieces.size());
        for (const glm::vec4& r : options.fvarRecords) pieces.push_back(bits(r));
    }
    // The side pieces last, the elements' sideFirst made indices into this buffer: the counts
    // and emit passes read them from it, which leaves the emit pass (at WebGPU's 8 storage
    // buffers) a binding for the totals, where it reports an element it could not finish.
    // z: bit 0 the side runs against the piece owner's direction, bit 1 it is the owner's side
    // (the first side piece naming the piece, buildEdgePieces's registration), which writes the
    // piece's shared points (adaptive_emit.comp).
    const auto sideBase = static_cast<uint32_t>(pieces.size());
    std::vector<bool> registered(ep.pieces.size(), false);
    for (const SidePiece& s : ep.sidePieces) {
        const uint32_t owns = registered[s.piece] ? 0u : 2u;
        registered[s.piece] = true;
        pieces.push_back({s.piece, s.startPoint, s.reversed | owns, s.from | s.to << 16});
    }
    for (GpuAdaptiveElement& g : elements)
        for (uint32_t& first : g.sideFirst) first += sideBase;

    using gpu::uploadBufferNow;
    auto make = [&](const char* name, uint64_t bytes, uint32_t usage = gpu::kStorage) {
        return std::make_unique<gpu::Buffer>(ctx, gpu::BufferDesc{name, std::max<uint64_t>(bytes, 16), usage});
    };
    elements_ = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "adaptive elements", elements));
    pieces_ = std::make_unique<gpu::Buffer>(uploadBufferNow(ctx, "adaptive edge pieces", pieces));
    cull_ = make("adaptive cull flags", uint64_t(elementCount_) * 4);
    rates_ = make("adaptive edge rates", uint64_t(pieceCount_) * 4);
    pieceEnds_ = make("adaptive piece ends", uint64_t(pieceCount_) * 16);
    // Per element, then (shared points) per edge piece, four a record (adaptive_counts.comp).
    info_ = make("adaptive element offsets", uint64_t(elementCount_) * 16 + (uint64_t(pieceCount_) + 3) / 4 * 16);
    totals_ = make("adaptive totals", kTotalsWords * 4, gpu::kStorage | gpu::kIndirect);
    tessVertices_ = make("adaptive tessellation vertices", uint64_t(capV_) * 16);
    triangles_ = make("adaptive triangle indices", uint64_t(capT_) * 12, gpu::kStorage | gpu::kIndex);
    triangleLevels_ = make("adaptive triangle levels", uint64_t(capT_) * 4);
    // Stale slots past a frame's count stay valid records (element 0) for the evaluation pass,
    // which runs over the whole capacity. Triangles past the count are never read (the draw's
    // count comes from the scan), so they are not cleared: on lavapipe a clear writes, and
    // page-faults in, every byte of buffers sized for the closest view.
    {
        gpu::CommandBuffer cmd(ctx);
        cmd.begin();
        if (options.evaluated) cmd.fill(*tessVertices_, 0);
        cmd.fill(*totals_, 0);
        cmd.submitAndWait();
    }

    passes_ = options.pipelines ? options.pipelines : std::make_shared<AdaptivePipelines>(ctx);
    options_.pipelines.reset();
    const auto& [vertices, patches, irregular, limits] = surface;
    cullBind_ = passes_->cull->bind({vertices, patches, irregular, limits, *cull_});
    rateBind_ = passes_->rates->bind({vertices, patches, irregular, limits, *pieces_, *cull_, *rates_, *pieceEnds_});
    countBind_ = passes_->counts->bind({*elements_, *pieces_, *rates_, *cull_, *info_, *pieceEnds_});
    scanBind_ = passes_->scan->bind({*info_, *totals_});
    emitBind_ = passes_->emit->bind({*elements_, *totals_, *pieces_, *rates_, *info_, *tessVertices_,
                                 *triangles_, *triangleLevels_});
}

AdaptiveTess::~AdaptiveTess() = default;

void AdaptiveTess::record(gpu::CommandBuffer& cmd, TimedPasses& timed, const AdaptiveView& view) {
    totalsRead_ = false;
    cmd.barrier(gpu::Access::ComputeWrite, gpu::Access::ComputeRead); // the limit points
    view_ = view;
    recordPasses(cmd, timed);
}

void AdaptiveTess::recordPasses(gpu::CommandBuffer& cmd, TimedPasses& timed) {
    const auto write = gpu::Access::ComputeWrite, read = gpu::Access::ComputeRead;
    CullPush cp{};
    copyMatrix(view_.viewProj, cp.viewProj);
    for (int i = 0; i < 3; ++i) cp.eye[i] = view_.eye[i];
    cp.eye[3] = view_.facing;
    cp.patchCount = patchCount_;
    cp.enabled = options_.cull ? 1u : 0u;
    cp.viewport[0] = float(view_.width), cp.viewport[1] = float(view_.height);
    const uint32_t samples = uint32_t(std::min<size_t>(options_.samplePositions.size(), 4));
    cp.enabled |= samples << 8;
    for (uint32_t k = 0; k < samples; ++k) {
        const glm::vec2 p = glm::clamp(options_.samplePositions[k] * 256.0f, 0.0f, 255.0f);
        cp.samples[k / 2] |= (uint32_t(p.x) | uint32_t(p.y) << 8) << (16 * (k % 2));
    }
    timed.begin(cmd, "adaptive cull", true);
    cmd.dispatch(*passes_->cull, cullBind_, elementCount_, cp);
    cmd.endTimed();
    cmd.barrier(write, read);
    RatePush rp{};
    copyMatrix(view_.viewProj, rp.viewProj);
    rp.halfViewport[0] = 0.5f * float(view_.width);
    rp.halfViewport[1] = 0.5f * float(view_.height);
    rp.edgePixels = options_.edgePixels;
    rp.tess = options_.tess;
    rp.patchCount = patchCount_;
    rp.texels = options_.texelsPerUV;
    rp.maxError = options_.maxError;
    rp.interiorError = options_.interiorError;
    timed.begin(cmd, "adaptive rates", true);
    cmd.dispatch(*passes_->rates, rateBind_, pieceCount_, rp);
    cmd.endTimed();
    cmd.barrier(write, read);
    CountPush np{options_.tess, options_.fvarNodes.empty() ? 0u : kFvarLoopsPerVertex, sharedPoints_ ? 1u : 0u,
                 samples, {cp.samples[0], cp.samples[1]}, options_.evaluated && !sharedPoints_ ? 0u : 1u};
    timed.begin(cmd, "adaptive counts", true);
    cmd.dispatch(*passes_->counts, countBind_, elementCount_, np);
    cmd.endTimed();
    cmd.barrier(write, read);
    // The previous frame's draw read the totals as indirect arguments.
    cmd.barrier(gpu::Access::IndirectRead | gpu::Access::VertexRead | gpu::Access::IndexRead, write);
    timed.begin(cmd, "adaptive scan", true);
    cmd.dispatch(*passes_->scan, scanBind_, 1,
                 ScanPush{elementCount_, capV_, capT_, kRowGroups, kEvalGroupSize, sharedPoints_});
    cmd.endTimed();
    cmd.barrier(write, read);
    timed.begin(cmd, "adaptive emit", true);
    cmd.dispatch(*passes_->emit, emitBind_, elementCount_,
                 EmitPush{pointBase_, capT_, options_.fvarNodes.empty() ? 0u : 1u, options_.fvarCell, domainBase_,
                          nodeBase_, recordBase_, sharedPoints_ ? 1u : 0u, capV_,
                          options_.pixelNormals ? 1u : 0u});
    cmd.endTimed();
    cmd.barrier(write, read | gpu::Access::VertexRead | gpu::Access::IndexRead | gpu::Access::IndirectRead);
}

AdaptiveTotals AdaptiveTess::readTotals(gpu::Context& ctx) const {
    auto t = gpu::readbackArrayNow<uint32_t>(ctx, *totals_, kTotalsWords);
    AdaptiveTotals r;
    r.vertices = t[12];
    r.visibleTriangles = t[13];
    r.drawnTriangles = t[0] / 3; // adaptive_scan.comp: the indexed draw's index count
    r.culledTriangles = t[14];
    r.overflow = t[15] != 0;
    r.writtenTriangles = t[16];
    r.writtenVertices = t[17];
    r.overBudget = t[22] != 0;
    r.cutShort = t[23] != 0;
    r.overflow = r.overflow || r.cutShort;
    return r;
}

std::string AdaptiveTotals::need() const {
    constexpr uint64_t kSaturated = 0x7FFFFFFF; // adaptive_scan.comp
    auto count = [&](uint64_t n) {
        return n >= kSaturated ? "over " + std::to_string(kSaturated - 1) : std::to_string(n);
    };
    if (overBudget || cutShort)
        return "more segments on some patch's sides than one GPU invocation may emit (lavapipe ends a shader's "
               "loops after 65,535 iterations)";
    return count(vertices) + " vertices and " + count(uint64_t(visibleTriangles) + culledTriangles) + " triangles";
}

uint64_t AdaptiveTess::bufferBytes() const {
    uint64_t sum = 0;
    for (const auto* b : {elements_.get(), pieces_.get(), cull_.get(), rates_.get(), pieceEnds_.get(),
                          info_.get(), totals_.get(), tessVertices_.get(), triangles_.get(),
                          triangleLevels_.get()})
        sum += b->size();
    return sum;
}

const AdaptiveTotals* AdaptiveTess::lastTotals(gpu::Context& ctx) const {
    if (!totalsRead_) {
        lastTotals_ = readTotals(ctx);
        totalsRead_ = true;
    }
    return &lastTotals_;
}

void AdaptiveTess::dispatchPerVertex(gpu::CommandBuffer& cmd, const gpu::ComputePipeline& pipeline,
                                     const gpu::BindGroup& bindings, std::span<const uint8_t> push) const {
    cmd.dispatchIndirect(pipeline, bindings, *totals_, kDispatchArgs, capV_, kRowGroups, push);
}

void AdaptiveTess::drawTriangles(gpu::CommandBuffer& cmd, const gpu::GraphicsPipeline& pipeline,
                                 const gpu::BindGroup& bindings, std::span<const uint8_t> push,
                                 bool pullIndices) const {
    if (pullIndices)
        cmd.drawIndirect(pipeline, bindings, *totals_, kDrawArgs, push);
    else
        cmd.drawIndexedIndirect(pipeline, bindings, *triangles_, *totals_, kIndexedDrawArgs, push);
}

void AdaptiveTess::drawWire(gpu::CommandBuffer& cmd, Wire wire, const WirePipelines& p,
                            std::span<const uint8_t> push) const {
    if (wire == Wire::Triangles)
        cmd.drawIndirect(p.triangleEdges, p.triangleEdgeBindings, *totals_, kWireDrawArgs, push);
}

std::string AdaptiveTess::shortfall(gpu::Context& ctx) const {
    const AdaptiveTotals* t = lastTotals(ctx);
    if (!t->overflow) return {};
    return "the view-adaptive tessellation of this view needs " + t->need() +
           (t->overBudget || t->cutShort
                ? std::string()
                : ", more than its buffers hold (" + std::to_string(capV_) + " vertices, " + std::to_string(capT_) +
                      " triangles)") +
           "; nothing written: raise --max-error or --edge-pixels, or lower --tess";
}

size_t AdaptiveTess::drawnVertexCount(gpu::Context& ctx) const {
    if (std::string s = shortfall(ctx); !s.empty()) throw Error(ErrorKind::BadInput, "--mesh-out: " + s);
    return lastTotals(ctx)->writtenVertices;
}

void AdaptiveTess::finishDrawnMesh(gpu::Context& ctx, exporting::DrawnMesh& out) const {
    // The vertices the passes emitted this frame: (element, s|t, own-chart UV).
    const size_t n = out.vertices.size();
    auto emitted = gpu::readbackArrayNow<glm::uvec4>(ctx, *tessVertices_, n);
    for (size_t i = 0; i < n; ++i) {
        if (draw_->hasUVs) {
            std::memcpy(&out.vertices[i].s, &emitted[i].z, 4);
            std::memcpy(&out.vertices[i].t, &emitted[i].w, 4);
        }
        out.vertices[i].approximate = drawnPointIsApproximate(*draw_, emitted[i].x, emitted[i].y);
    }
    out.triangles = gpu::readbackArrayNow<uint32_t>(ctx, *triangles_, size_t(lastTotals(ctx)->writtenTriangles) * 3);
}

uint64_t AdaptiveTess::triangleCount(gpu::Context& ctx) const {
    return lastTotals(ctx)->drawnTriangles; // after culling and any overflow
}

uint64_t AdaptiveTess::verticesEvaluated(gpu::Context& ctx) const {
    // Also the three points per edge piece that decide its rate.
    return 3ull * pieceCount_ + lastTotals(ctx)->writtenVertices;
}

std::unique_ptr<DisplacementPasses> AdaptiveTess::makeDisplacement(gpu::Context& ctx, const SubdivisionDraw& draw,
                                                                   const SurfaceBuffers& surface,
                                                                   const DisplacementInputs& in) const {
    return makeAdaptiveDisplacement(ctx, draw, surface, *this, in);
}

} // namespace limn::render
