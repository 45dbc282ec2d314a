// limn-render's options checked against each other, and what they mean: the renderer's settings,
// the sequence and its frames, the outputs (render/output_plan.h, render/sequence_plan.h).
#include "job.h"

#include "base/error.h"
#include "base/io.h"
#include "image/image_file.h"
#include "mesh/import.h"
#include "render/sequence_plan.h"

#include <glm/geometric.hpp>

namespace limn::render_tool {

namespace {

// The explicit camera (--eye, --target, --up) and --view.
void checkCamera(const RenderJob& job) {
    const render::ViewSpec& view = job.settings.view;
    if (view.eye && job.viewGiven) throwUsage("--view and --eye exclude each other");
    if ((view.target || view.up) && !view.eye)
        throwUsage("--target and --up describe an explicit camera; give --eye too");
    if (view.eye && view.target && *view.eye == *view.target)
        throwUsage("--eye and --target are the same point, so the camera has no direction");
    // The same checks as a --cameras line (sequence.cpp), so both ways of placing a camera agree.
    if (view.up && glm::length(*view.up) == 0) throwUsage("--up: the up vector is zero");
    if (view.up && view.eye && view.target &&
        glm::length(glm::cross(glm::normalize(*view.target - *view.eye), glm::normalize(*view.up))) < 1e-9)
        throwUsage("--up is parallel to the view direction (--eye to --target), so the image has no up");
}

// What the options set in the renderer's settings, but for the input's maps and material
// (input.cpp).
void mapSettings(RenderJob& job) {
    render::RenderSettings& settings = job.settings;
    if (job.shade == "normal") settings.shade = render::Shade::Normal;
    if (job.shade == "uv") settings.shade = render::Shade::Uv;
    if (job.shade == "levels") settings.shade = render::Shade::Levels;
    if (job.shade == "texture") settings.shade = render::Shade::Texture;
    if (job.wire && job.wireTriangles)
        throw Error(ErrorKind::Usage, "--wire and --wire-triangles draw different overlays; choose one");
    settings.wire = job.wire ? render::Wire::Outlines : job.wireTriangles ? render::Wire::Triangles : render::Wire::None;
    settings.alpha = job.alpha;
    settings.samples = static_cast<uint32_t>(job.samples);
    settings.supersample = static_cast<uint32_t>(job.supersample);
    settings.sampleShading = job.sampleShading;
    settings.maxImageBytes = job.maxMemory;
    settings.view.zUp = job.upAxis == "z";
}

// --frames FILE.gltf: the morph-target animation, read whole before any work (a file without one,
// or one too long to hold, is refused here); its positions are held for one framing of the whole
// sequence, within the memory the --frames meshes may take.
void readAnimation(RenderJob& job) {
    Warnings warnings;
    job.animation = importGltfMorphFrames(job.framesPattern, limn::readInput(job.framesPattern), warnings,
                                          {.fps = job.fps,
                                           .maxFrames = render::kMaxFrames,
                                           .maxPositionBytes = cli::defaultMemoryBudget(),
                                           .filesRead = &job.animationFiles});
    cli::printWarnings(warnings, displayName(job.framesPattern));
}

// A sequence's views (--turntable, --cameras), mesh files or glTF animation (--frames), and its
// frame numbers.
void readSequence(RenderJob& job) {
    if (job.turntable) job.views = render::turntableViews(job.settings.view, job.turntable);
    if (!job.camerasPath.empty()) {
        if (isStdio(job.camerasPath) && isStdio(job.input))
            throwUsage("--cameras - and the input cannot both be standard input");
        auto bytes = limn::readInput(job.camerasPath);
        try {
            job.views = render::parseCameraFile(std::string(bytes.begin(), bytes.end()), job.settings.view.fovDeg);
        } catch (Error& e) {
            e.setFile(displayName(job.camerasPath));
            throw;
        }
    }
    if (!job.framesPattern.empty() && render::isAnimationFile(job.framesPattern))
        readAnimation(job);
    else if (!job.framesPattern.empty())
        job.frameFiles = render::findFrameFiles(render::parseFramePattern("--frames", job.framesPattern));
    job.frameNumbers = render::sequenceFrameNumbers(job.views, job.frameFiles,
                                                    job.animation ? job.animation->positions.size() : 0);
    if (!job.sequence) return;
    job.part = render::framesOfPart(job.frameNumbers, job.frameRange.value_or(render::FrameRange{}),
                                    job.shard.value_or(render::Shard{}));
    for (size_t k : job.part) job.partNumbers.push_back(job.frameNumbers[k]);
}

} // namespace

void planJob(RenderJob& job) {
    checkCamera(job);
    if (job.benchOrbit != 0 && !job.bench)
        throwUsage("--bench-orbit turns the camera between --bench frames; give --bench FRAMES too");
    job.sequence = render::planSequence({.turntable = job.turntable,
                                         .cameras = !job.camerasPath.empty(),
                                         .frames = !job.framesPattern.empty(),
                                         .animation = render::isAnimationFile(job.framesPattern),
                                         .fps = job.fps > 0,
                                         .eye = bool(job.settings.view.eye),
                                         .view = job.viewGiven,
                                         .bench = job.bench > 0,
                                         .part = job.shard || job.frameRange});
    job.outputs = render::planOutputs({.image = job.common.output,
                                       .mesh = job.meshOut,
                                       .meshAscii = job.meshAscii,
                                       .bitDepthGiven = job.bitDepthGiven,
                                       .bench = job.bench > 0,
                                       .sequence = job.sequence});
    mapSettings(job);
    const render::OutputPlan& out = job.outputs;
    render::RenderSettings& settings = job.settings;
    settings.floatOutput = out.writeImage && (out.imageFormat == ImageFormat::Exr || job.bitDepth == 16);
    settings.depth = out.writeImage && out.imageFormat == ImageFormat::Exr;
    // Without the OpenImageIO plugin no .exr can be written: fail before any file exists.
    if (settings.depth) requireImageWriter();
    job.surface = job.surfaceName == "blend"         ? Surface::Blend
                  : job.surfaceName == "subdivision" ? Surface::Subdivision
                  : job.surfaceName == "control"     ? Surface::Control
                                                     : Surface::Auto;
    if (!job.trimPath.empty() && (job.surface == Surface::Subdivision || job.surface == Surface::Control))
        throwUsage("--trim cuts blending surfaces; it does not go with --surface " + job.surfaceName);
    if (job.surface == Surface::Control && (!job.displace.empty() || job.shade == "levels"))
        throwUsage("--displace and --shade levels draw the subdivision surface, and "
              "--surface control draws the control mesh; leave out --surface control");
    readSequence(job);
    job.inputs = {job.input};
    for (const std::string* extra : {&job.trimPath, &job.displace, &job.texture, &job.camerasPath})
        if (!extra->empty()) job.inputs.push_back(*extra);
    for (const auto& f : job.frameFiles) job.inputs.push_back(f.path);
    if (job.animation) {
        job.inputs.push_back(job.framesPattern);
        job.inputs.insert(job.inputs.end(), job.animationFiles.begin(), job.animationFiles.end());
    }
}

} // namespace limn::render_tool
