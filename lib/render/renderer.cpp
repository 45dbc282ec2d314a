#include "render/renderer.h"

#include "base/cli.h"
#include "base/error.h"
#include "blend/blend_surface.h"
#include "render/blend_pass.h"
#include "render/control_mesh_pass.h"
#include "render/gpu_origin.h"
#include "render/adaptive/adaptive_options.h"
#include "render/subdivision_pass.h"
#include "subdiv/evaluate.h"
#include "render_shaders.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <future>
#include <limits>
#include <memory>

namespace limn::render {

namespace {

struct VertexPush {
    uint32_t firstVertex;
};

constexpr float kWirePull = 2e-3f; // fraction of the distance to the eye
constexpr double kPi = 3.14159265358979323846;

// An sRGB colour, 0..1 per component, as the bits 0x00BBGGRR (what the shaders unpack).
uint32_t packSrgb8(const glm::dvec3& c) {
    uint32_t packed = 0;
    for (int i = 0; i < 3; ++i)
        packed |= uint32_t(std::lround(std::clamp(c[i], 0.0, 1.0) * 255.0)) << (8 * i);
    return packed;
}

// Points on the subdivision surface, for framing: each patch at its corners, edge midpoints and
// centre, and every limit point (the corners of the faces drawn at their limit). The control
// points' hull is looser (on spot at depth 3 the surface fills 10% less of it): a frame fitted
// to it would not be filled. Evaluated on the CPU (subdiv/evaluate.h) once per renderer.
std::vector<glm::dvec3> surfaceSamples(const Mesh& mesh, const Tables& tables) {
    const std::vector<glm::dvec3> vertices = evaluateVertices(tables, mesh.positions);
    std::vector<glm::dvec3> points;
    points.reserve(tables.patches.size() * 9 + tables.limitPosition.rows());
    const double params[3] = {0.0, 0.5, 1.0};
    for (const Patch& p : tables.patches) patchPositions(p, vertices, params, points);
    for (const LimitPoint& l : evaluateLimitPoints(tables, vertices)) points.push_back(l.position);
    return points;
}

} // namespace

// What every frame shares: the per-frame upload of the control points, the copy into level 0 of
// the pass's vertex buffer, the render target and the command buffer.
struct Renderer::Gpu {
    Gpu(gpu::Context& ctx, uint64_t controlBytes, const gpu::Buffer& vertices, uint32_t width,
        uint32_t height, gpu::TargetFormat format, bool depth)
        : staging(ctx, {"control point staging", controlBytes, 0, gpu::MemoryKind::Upload}),
          controlPoints(ctx, {"control points", controlBytes}),
          copyPoints(ctx, {"copy control points", copy_points_comp_spv, 2, sizeof(VertexPush)}),
          target(ctx, width, height, format, depth), cmd(ctx) {
        copyBindings = copyPoints.bind({controlPoints, {vertices, 0, controlBytes}});
    }
    gpu::Buffer staging, controlPoints;
    gpu::ComputePipeline copyPoints;
    gpu::BindGroup copyBindings;
    gpu::RenderTarget target;
    gpu::CommandBuffer cmd;
};

namespace {

void checkUvShade(const Mesh& mesh, const RenderSettings& settings) {
    if (settings.shade == Shade::Uv && !mesh.hasUVs())
        throw Error(ErrorKind::BadInput,
                    "--shade uv: the mesh has no texture coordinates (no FVUV chunk); use --shade "
                    "lit or normal");
}

} // namespace

void Renderer::checkImageSize(const gpu::Context& ctx) {
    const RenderSettings& s = settings_;
    if (s.samples != 1 && s.samples != 4)
        throw Error(ErrorKind::Usage, "--samples must be 1 or 4 (the counts WebGPU offers), not " +
                                          std::to_string(s.samples));
    if (s.supersample < 1 || s.supersample > 4)
        throw Error(ErrorKind::Usage, "--supersample must be 1 to 4");
    const uint64_t w = uint64_t(s.width) * s.supersample, h = uint64_t(s.height) * s.supersample;
    const uint32_t max = ctx.limits().maxImageDimension2D;
    if (w > max || h > max)
        throw Error(ErrorKind::Usage,
                    "--size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                        (s.supersample > 1 ? " with --supersample " + std::to_string(s.supersample) +
                                                 " draws " + std::to_string(w) + "x" + std::to_string(h)
                                           : std::string()) +
                        ", beyond this device's largest image (" + std::to_string(max) +
                        " pixels a side); lower --size or --supersample");
    drawWidth_ = uint32_t(w);
    drawHeight_ = uint32_t(h);
    const bool floatTarget = s.floatOutput || s.supersample > 1 || (s.alpha && s.samples > 1);
    targetFormat_.color = floatTarget ? gpu::RenderTarget::kLinearFormat : gpu::RenderTarget::kColorFormat;
    targetFormat_.samples = s.samples;
    targetFormat_.sampleShading = s.sampleShading && s.samples > 1;
    if (targetFormat_.sampleShading && !ctx.limits().sampleRateShading)
        throw Error(ErrorKind::Capability, "the device " + ctx.deviceName() +
                                               " cannot shade each sample on its own (no sampleRateShading); "
                                               "leave out --sample-shading");
    if (!(ctx.limits().colorSampleCounts & s.samples) || !(ctx.limits().depthSampleCounts & s.samples))
        throw Error(ErrorKind::Capability, "the device " + ctx.deviceName() + " cannot draw with " +
                                               std::to_string(s.samples) +
                                               " samples per pixel; use --samples 1");
    // The target on the device, then on the host: the padded readback copy, the float image
    // (16 bytes a pixel, 4 more with depth) and, supersampled, the filtered one.
    const uint64_t pixels = w * h;
    imageBytes_ = gpu::RenderTarget::estimateBytes(drawWidth_, drawHeight_, targetFormat_, s.depth) +
                  (floatTarget ? pixels * (16 + (s.depth ? 4 : 0)) : 0) +
                  uint64_t(s.width) * s.height * (s.supersample > 1 ? 20 : 0);
    uint64_t budget = s.maxImageBytes;
    if (!budget) {
        budget = cli::defaultMemoryBudget();
        if (ctx.limits().deviceLocalHeapBytes)
            budget = std::min(budget, ctx.limits().deviceLocalHeapBytes);
    }
    if (imageBytes_ > budget)
        throw Error(ErrorKind::BadInput,
                    "a " + std::to_string(drawWidth_) + "x" + std::to_string(drawHeight_) + " image with " +
                        std::to_string(s.samples) + " sample" + (s.samples > 1 ? "s" : "") +
                        " per pixel needs about " + cli::formatBytes(imageBytes_) + ", more than the " +
                        cli::formatBytes(budget) +
                        " allowed (--max-memory); lower --size, --samples or --supersample");
}

Renderer::Renderer(gpu::Context& ctx, const Mesh& mesh, const Tables* tables,
                   const RenderSettings& settings)
    : ctx_(ctx), settings_(settings), origin_(tables ? renderOrigin(mesh) : glm::dvec3(0.0)) {
    checkImageSize(ctx);
    checkUvShade(mesh, settings);
    if (settings.shade == Shade::Levels && !tables)
        throw Error(ErrorKind::BadInput,
                    "--shade levels colours subdivision levels, and the container has no tables "
                    "(TBLS); run limn-tables first");
    if (settings.shade == Shade::Texture && !settings.texture)
        throw Error(ErrorKind::Usage, "--shade texture needs --texture MAP");
    if ((settings.texture || settings.displacementMap) && !mesh.hasUVs())
        throw Error(ErrorKind::BadInput,
                    "--texture and --displace need texture coordinates; the mesh has none");
    if (settings.displacementMap && !tables)
        throw Error(ErrorKind::BadInput,
                    "--displace displaces the subdivision surface; the container has "
                    "no tables (TBLS): run limn-tables first");
    if (settings.trim)
        throw Error(ErrorKind::BadInput,
                    "--trim cuts blending surfaces, and this surface is not one (no BLND); run "
                    "limn-blend first");
    Bounds bounds;
    if (tables) {
        DisplacementPlan plan{settings.seams, settings.seamFix};
        if (settings.displacementMap && !settings.seams)
            throw Error(ErrorKind::BadInput, "internal: displacement without seam data");
        viewAdaptive_ = settings.edgePixels > 0 && settings.wire != Wire::Outlines;
        // Two jobs that need only the inputs run beside the edge pieces' preparation, on a
        // second core where there is one: the view-adaptive passes' pipelines (compiled by
        // lavapipe as they are created) and the framing samples. Their exceptions surface at
        // get(); a throw before that waits for them in the futures' destructors.
        std::future<std::shared_ptr<AdaptivePipelines>> pipelines;
        if (viewAdaptive_)
            pipelines = std::async(std::launch::async, [&ctx] { return std::make_shared<AdaptivePipelines>(ctx); });
        std::future<std::vector<glm::dvec3>> hull;
        if (!settings.displacementMap) // the displaced surface leaves the hull: framed by its box
            hull = std::async(std::launch::async, [&mesh, tables] { return surfaceSamples(mesh, *tables); });
        SubdivisionDraw draw = prepareSubdivision(mesh, *tables, settings.tessCap,
                                                  settings.displacementMap ? &plan : nullptr, viewAdaptive_);
        draw.limitChunkBytes = settings.limitChunkBytes;
        AdaptiveOptions adaptive;
        if (viewAdaptive_)
            adaptive = adaptiveOptions(settings, draw, drawWidth_, drawHeight_, ctx.limits().standardSampleLocations);
        bounds = draw.bounds;
        draw.bounds.min -= origin_, draw.bounds.max -= origin_; // the pass sees the GPU's coordinates
        if (hull.valid()) bounds.hull = hull.get();
        if (settings.displacementMap) {
            // An EXR may hold any finite value: 3e38 times --displace-scale 10 is Inf on the GPU,
            // and the image came out blank with exit 0. The same 1e18 as positions (mesh.cpp).
            double far = 0;
            for (float v : settings.displacementMap->values)
                far = std::max(far, std::abs((double(v) - settings.displaceMid) * settings.displaceScale));
            if (far > 1e18)
                throw Error(ErrorKind::BadInput,
                            "--displace: the map's values times --displace-scale move the surface by up to " +
                                cli::shortNumber(far) + ", beyond the 1e18 that the GPU's float arithmetic carries");
        }
        if (settings.displacementMap) { // leave room for the displaced surface in the framing
            framingPad_ = glm::dvec3(std::abs(settings.displaceScale) * 0.5);
            bounds.min -= framingPad_, bounds.max += framingPad_;
            if (bounds.sphereRadius > 0) bounds.sphereRadius += framingPad_.x;
            bounds.hull.clear(); // boundsOf's control points: frame the padded box instead
        }
        if (pipelines.valid()) adaptive.pipelines = pipelines.get();
        SubdivisionPass::Displacement displacement{
            settings.displacementMap, float(settings.displaceScale), float(settings.displaceMid)};
        pass_ = std::make_unique<SubdivisionPass>(
            ctx, std::move(draw),
            settings.evalInCompute ? SubdivisionPass::Eval::Compute : SubdivisionPass::Eval::Vertex,
            settings.evaluateVertices || settings.wire != Wire::None, settings.shade,
            settings.displacementMap ? &displacement : nullptr, settings.texture,
            viewAdaptive_ ? &adaptive : nullptr, targetFormat_);
    } else {
        if (settings.wire == Wire::Triangles)
            throw Error(ErrorKind::Usage,
                        "--wire-triangles draws the edges of a subdivision surface's triangles; this "
                        "file has no tables (run limn-tables first), or use --wire for the mesh edges");
        ControlMeshDraw draw = prepareControlMesh(mesh);
        bounds = draw.bounds;
        pass_ = std::make_unique<ControlMeshPass>(ctx, std::move(draw), settings.texture, settings.shade,
                                                 targetFormat_);
    }
    finishSetup(mesh, bounds);
}

// The blending surface keeps the origin at 0: its draw reads the local surfaces limn-blend fitted
// in the model's coordinates, not the control points.
Renderer::Renderer(gpu::Context& ctx, const Mesh& mesh, const blend::BlendSurface& surface,
                   const RenderSettings& settings)
    : ctx_(ctx), settings_(settings) {
    checkImageSize(ctx);
    checkUvShade(mesh, settings);
    if (settings.displacementMap || settings.texture || settings.shade == Shade::Texture)
        throw Error(ErrorKind::Usage,
                    "--displace and --texture apply to the subdivision surface, not "
                    "a blending surface");
    if (settings.wire == Wire::Triangles)
        throw Error(ErrorKind::Usage,
                    "--wire-triangles draws the edges of a subdivision surface's triangles, not a "
                    "blending surface's; use --wire for its face outlines");
    BlendDraw draw = prepareBlend(mesh, surface, settings.blendGrid);
    const Bounds bounds = draw.bounds;
    blend_ = true;
    pass_ = std::make_unique<BlendPass>(ctx, std::move(draw),
                                        settings.evalInCompute ? BlendPass::Eval::Compute
                                                               : BlendPass::Eval::Vertex,
                                        settings.evaluateVertices || settings.wire != Wire::None, settings.trim,
                                        settings.shade, targetFormat_);
    finishSetup(mesh, bounds);
}

void Renderer::finishSetup(const Mesh& mesh, const Bounds& bounds) {
    controlPoints_.reserve(mesh.vertexCount());
    for (const auto& p : mesh.positions) controlPoints_.emplace_back(glm::vec3(p - origin_), 1.0f);
    framing_ = bounds;
    faces_.faceOffsets = mesh.faceOffsets;
    faces_.faceVertices = mesh.faceVertices;
    camera_ = cameraFor(settings_.view);
    gpu_ = std::make_unique<Gpu>(ctx_, controlPoints_.size() * sizeof(glm::vec4),
                                 pass_->vertexBuffer(), drawWidth_, drawHeight_, targetFormat_,
                                 settings_.depth);
}

Renderer::~Renderer() = default;

Camera Renderer::cameraFor(const ViewSpec& view) const {
    return frameCamera(view, framing_, double(settings_.width) / settings_.height);
}

void Renderer::extendFraming(const std::vector<glm::dvec3>& positions) {
    for (const glm::dvec3& p : positions) {
        framing_.min = glm::min(framing_.min, p - framingPad_);
        framing_.max = glm::max(framing_.max, p + framingPad_);
    }
    // The fit takes the frames' control points too (looser than surface samples, but never
    // cutting a frame off); the sphere about the grown box's centre is no longer known.
    if (!framing_.hull.empty()) framing_.hull.insert(framing_.hull.end(), positions.begin(), positions.end());
    framing_.sphereRadius = 0;
}

void Renderer::setControlPoints(const std::vector<glm::dvec3>& positions) {
    if (blend_)
        throw Error(ErrorKind::Usage, "a blending surface is built from its control points on the CPU "
                                      "(charts, local surfaces); new positions need limn-blend again");
    if (positions.size() != controlPoints_.size())
        throwBadInput("the frame has " + std::to_string(positions.size()) + " vertices, the tables " +
                      std::to_string(controlPoints_.size()));
    Bounds box{positions.empty() ? glm::dvec3(0.0) : positions[0], positions.empty() ? glm::dvec3(0.0) : positions[0]};
    for (size_t i = 0; i < positions.size(); ++i) {
        controlPoints_[i] = glm::vec4(glm::vec3(positions[i] - origin_), 1.0f);
        box.min = glm::min(box.min, positions[i]);
        box.max = glm::max(box.max, positions[i]);
    }
    box.min -= origin_, box.max -= origin_; // the first frame's origin: the GPU's coordinates stay put
    pass_->setControlPoints(box, surfaceOrientation(faces_, positions));
}

uint64_t Renderer::bufferBytes() const {
    return pass_->bufferBytes() + gpu_->staging.size() + gpu_->controlPoints.size();
}

void Renderer::recordUpload() {
    auto& g = *gpu_;
    timed_.begin(g.cmd, "upload", true);
    g.cmd.copy(g.staging, g.controlPoints);
    g.cmd.endTimed();
    g.cmd.barrier(gpu::Access::TransferWrite, gpu::Access::ComputeRead);
}

glm::dmat4 Renderer::gpuViewProjection(double aspect) const {
    return translatedViewProjection(camera_.viewProjection(aspect), origin_);
}

void Renderer::recordCompute() {
    auto& g = *gpu_;
    const glm::mat4 vp(gpuViewProjection(double(settings_.width) / settings_.height));
    // The view-adaptive tessellation sizes its segments in drawn (supersampled) pixels.
    pass_->setView(vp, camera_.eye - origin_, drawWidth_, drawHeight_);
    timed_.begin(g.cmd, "copy control points", true);
    g.cmd.dispatch(g.copyPoints, g.copyBindings, static_cast<uint32_t>(controlPoints_.size()),
                   VertexPush{0});
    g.cmd.endTimed();
    g.cmd.barrier(gpu::Access::ComputeWrite, gpu::Access::ComputeRead);
    pass_->recordCompute(g.cmd, timed_);
}

void Renderer::recordDraw() {
    auto& g = *gpu_;
    const double aspect = double(settings_.width) / settings_.height;
    const glm::dmat4 vp = gpuViewProjection(aspect);
    DrawPush push{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) push.viewProj[c * 4 + r] = static_cast<float>(vp[c][r]);
    // The camera's axes are the rows of the view matrix's rotation.
    const glm::dmat4 view = camera_.view();
    const glm::dvec3 right(view[0][0], view[1][0], view[2][0]);
    const glm::dvec3 up(view[0][1], view[1][1], view[2][1]);
    const glm::dvec3 forward(-view[0][2], -view[1][2], -view[2][2]);
    // The key light (--light), fixed to the camera: azimuth from the direction towards the
    // camera towards its right, elevation towards its up.
    const double az = settings_.lightAzimuthDeg * kPi / 180, el = settings_.lightElevationDeg * kPi / 180;
    // --shade levels keeps its old light (over the viewer's left shoulder, levelsLight in
    // draw_common.glsl) so that level pictures stay comparable.
    const glm::dvec3 light =
        settings_.shade == Shade::Levels
            ? glm::normalize(-forward + 0.45 * up - 0.3 * right)
            : glm::normalize(std::cos(el) * std::cos(az) * -forward +
                             std::cos(el) * std::sin(az) * right + std::sin(el) * up);
    for (int i = 0; i < 3; ++i) {
        push.eye[i] = static_cast<float>(camera_.eye[i] - origin_[i]);
        push.light[i] = static_cast<float>(light[i]);
    }
    const glm::dvec3 base = settings_.baseColor.value_or(
        glm::dvec3(settings_.texture ? 1.0 : kDefaultBaseColor));
    const uint32_t baseBits = packSrgb8(base);
    std::memcpy(&push.eye[3], &baseBits, 4);
    if (settings_.view.zUp) push.flags |= kDrawZUp;
    push.wireColor[0] = push.wireColor[1] = push.wireColor[2] = 0.006f; // sRGB ~ 0.07
    push.shade = static_cast<uint32_t>(settings_.shade);
    push.wirePull = kWirePull;
    if (settings_.backFaceColor) {
        const uint32_t packed = packSrgb8(*settings_.backFaceColor);
        std::memcpy(&push.light[3], &packed, 4);
        push.flags |= kDrawBackFaceKey;
    }

    std::array<float, 4> clear{};
    for (int i = 0; i < 3; ++i)
        clear[i] = static_cast<float>(srgbToLinear(settings_.background[i]));
    clear[3] = settings_.alpha ? 0.0f : 1.0f;
    // The float target averages premultiplied colour (MSAA resolve, box filter): a transparent
    // background is black there, and image() puts the background colour back.
    if (settings_.alpha && targetFormat_.color == gpu::RenderTarget::kLinearFormat) clear = {};

    timed_.begin(g.cmd, "draw", false);
    g.cmd.beginRendering(g.target, clear);
    pass_->recordDraw(g.cmd, push, settings_.wire);
    g.cmd.endRendering();
    g.cmd.endTimed();

    timed_.begin(g.cmd, "readback", false);
    g.cmd.copyToReadback(g.target);
    g.cmd.endTimed();
}

void Renderer::renderFrame() {
    auto& g = *gpu_;
    // The "animated mesh" path: the CPU writes this frame's control points, the GPU does the rest.
    g.staging.writeArray<glm::vec4>(controlPoints_);
    timed_.isCompute.clear();
    g.cmd.begin();
    // Topology and tables were uploaded once, in earlier submissions; a fence wait orders those
    // copies but does not make their writes visible to this frame's reads.
    g.cmd.barrier(gpu::Access::TransferWrite, gpu::Access::ComputeRead | gpu::Access::VertexRead |
                                                  gpu::Access::IndexRead |
                                                  gpu::Access::FragmentRead);
    recordUpload();
    recordCompute();
    recordDraw();
    g.cmd.submitAndWait();
}

LinearImage Renderer::drawnLinear() const {
    const auto& t = gpu_->target;
    LinearImage out;
    out.width = t.width();
    out.height = t.height();
    const size_t n = size_t(out.width) * out.height;
    out.rgba.resize(n * 4);
    const auto bytes = t.pixels();
    if (t.format().color == gpu::RenderTarget::kLinearFormat) {
        for (size_t i = 0; i < n * 4; ++i) {
            uint16_t h;
            std::memcpy(&h, &bytes[2 * i], 2);
            out.rgba[i] = halfToFloat(h);
        }
    } else { // 8-bit sRGB (alpha 0 or 1 here: no MSAA with --alpha on this target)
        for (size_t i = 0; i < n; ++i) {
            const float a = bytes[4 * i + 3] / 255.0f;
            for (int c = 0; c < 3; ++c)
                out.rgba[4 * i + c] = float(srgbToLinear(bytes[4 * i + c] / 255.0)) * a;
            out.rgba[4 * i + 3] = a;
        }
    }
    if (t.readsDepth()) {
        // perspectiveRH_ZO maps the distance z along the view direction to
        // d = f (z - n) / (z (f - n)), so z = f n / (f - d (f - n)); the cleared 1 is +Inf.
        const double nearP = camera_.nearPlane, farP = camera_.farPlane;
        auto d = t.depth();
        out.depth.resize(n);
        for (size_t i = 0; i < n; ++i)
            out.depth[i] = d[i] >= 1.0f ? std::numeric_limits<float>::infinity()
                                        : float(farP * nearP / (farP - double(d[i]) * (farP - nearP)));
    }
    return out;
}

LinearImage Renderer::linearImage() const {
    return boxFilter(drawnLinear(), settings_.supersample);
}

Image Renderer::image() const {
    if (targetFormat_.color == gpu::RenderTarget::kLinearFormat) {
        std::vector<float> background(3);
        for (int i = 0; i < 3; ++i) background[i] = float(srgbToLinear(settings_.background[i]));
        return toSrgb8(linearImage(), settings_.alpha, background);
    }
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

void Renderer::refuseTessellationShortfall(const std::string& where) const {
    const auto* sp = dynamic_cast<const SubdivisionPass*>(pass_.get());
    if (std::string shortfall = sp ? sp->tessellationShortfall() : std::string(); !shortfall.empty())
        throw Error(ErrorKind::BadInput, where + ": " + shortfall);
}

exporting::DrawnMesh Renderer::drawnMesh() {
    exporting::DrawnMesh m = pass_->drawnMesh();
    if (origin_ != glm::dvec3(0.0))
        for (exporting::DrawnVertex& v : m.vertices) { // back to the model's coordinates
            v.x = float(double(v.x) + origin_.x);
            v.y = float(double(v.y) + origin_.y);
            v.z = float(double(v.z) + origin_.z);
        }
    return m;
}

FrameTimes Renderer::frameTimes() const {
    FrameTimes t;
    t.passes = gpu_->cmd.passTimes();
    for (size_t i = 0; i < t.passes.size(); ++i) {
        double ms = t.passes[i].ms;
        if (i < timed_.isCompute.size() && timed_.isCompute[i])
            t.computeMs += ms;
        else if (t.passes[i].name == "draw")
            t.drawMs += ms;
        t.totalMs += ms;
    }
    return t;
}

} // namespace limn::render
