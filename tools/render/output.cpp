// limn-render's outputs: opened before any work, the image encoded in the format its name asked
// for, and the files committed together with the depfile.
#include "job.h"

#include "base/error.h"
#include "image/image_file.h"
#include "image/output_image.h"
#include "image/srgb_image.h"

#include <algorithm>
#include <filesystem>

namespace limn::render_tool {

void refuseOversizedSequence(const RenderJob& job, const RenderInput* in) {
    if (!job.sequence || !job.outputs.imagePattern) return;
    uint64_t triangles = 0;
    if (in)
        for (size_t f = 0; f < in->mesh.faceCount(); ++f) triangles += std::max<uint32_t>(in->mesh.faceSize(f), 2) - 2;
    const uint64_t frameBytes = render::estimateFrameBytes(
        job.outputs, {.width = job.settings.width,
                      .height = job.settings.height,
                      .alpha = job.settings.alpha,
                      .bitDepth = job.bitDepth,
                      .meshTriangles = triangles});
    const uint64_t frames = job.part.size(), total = frames * frameBytes;
    std::filesystem::path folder = std::filesystem::path(render::framePath(*job.outputs.imagePattern, 0)).parent_path();
    if (folder.empty()) folder = ".";
    uint64_t limit = job.maxOutput;
    std::string what = "--max-output";
    if (!limit) {
        std::error_code error;
        const std::filesystem::space_info space = std::filesystem::space(folder, error);
        if (error) return; // a missing folder is refused next, with its name
        limit = space.available;
        what = "the free space in " + folder.string();
    }
    if (total > limit)
        throw Error(ErrorKind::Usage,
                    "the sequence's " + std::to_string(frames) + " frames would write about " +
                        cli::formatBytes(total) + " (" + cli::formatBytes(frameBytes) +
                        " each, counting images uncompressed" + (in && triangles ? " and meshes at least" : "") +
                        "), more than " + what + " (" + cli::formatBytes(limit) +
                        "); render fewer frames, smaller images, or give --max-output SIZE");
}

void openOutputs(const RenderJob& job, OutputFiles& files) {
    const render::OutputPlan& plan = job.outputs;
    const std::vector<std::string>& inputs = job.inputs;
    if (job.sequence) {
        refuseOversizedSequence(job, nullptr);
        files.paths = plan.framePaths(job.partNumbers);
        for (const std::string& o : files.paths) refuseOverwritingInputs(o, inputs);
        for (const std::string& o : {files.paths.front(), files.paths.back()}) {
            const std::filesystem::path folder = std::filesystem::path(o).parent_path();
            if (!folder.empty() && !std::filesystem::is_directory(folder)) {
                Error e(ErrorKind::BadInput, "cannot write the frames: no folder " + folder.string());
                e.setFile(o);
                throw e;
            }
        }
    } else {
        if (plan.writeImage) refuseOverwritingInputs(plan.image, inputs);
        if (!plan.mesh.empty()) refuseOverwritingInputs(plan.mesh, inputs);
        if (plan.writeImage) files.image.emplace(plan.image, OutputFile::Kind::Binary);
        if (!plan.mesh.empty()) files.mesh.emplace(plan.mesh, plan.meshFileKind());
        if (plan.writeImage) files.paths.push_back(plan.image);
        if (!plan.mesh.empty()) files.paths.push_back(plan.mesh);
    }
    files.depfile.emplace(plan.writeImage || files.mesh || job.sequence ? job.common.depfile : std::string(),
                          files.paths, inputs);
}

FramePixels framePixels(const render::Renderer& renderer, const RenderJob& job) {
    FramePixels p;
    if (job.outputs.imageFormat == ImageFormat::Exr || job.bitDepth == 16)
        p.linear = renderer.linearImage();
    else
        p.image = renderer.image();
    return p;
}

// The image in the format its name asked for: 8- or 16-bit PNG, or EXR (linear RGBA and
// camera-space Z).
std::vector<uint8_t> encodeImage(const FramePixels& p, const RenderJob& job) {
    if (job.outputs.imageFormat == ImageFormat::Exr) {
        const LinearImage& li = p.linear;
        const size_t n = size_t(li.width) * li.height;
        std::vector<float> values(n * 5);
        for (size_t i = 0; i < n; ++i) {
            std::copy_n(&li.rgba[4 * i], 4, &values[5 * i]);
            values[5 * i + 4] = li.depth[i];
        }
        return encodeExr(li.width, li.height, {"R", "G", "B", "A", "Z"}, values);
    }
    if (job.bitDepth == 16) {
        std::vector<float> background(3);
        for (int i = 0; i < 3; ++i) background[i] = float(srgbToLinear(job.settings.background[i]));
        return encodePng(toSrgb16(p.linear, job.settings.alpha, background));
    }
    return encodePng(p.image);
}

void removeFrames(const std::vector<std::string>& paths) {
    clearRemovalOnSignal();
    for (const std::string& p : paths) std::filesystem::remove(p);
}

void commitOutputs(const RenderJob& job, const RenderInput& in, OutputFiles& files,
                   const EncodedOutputs& encoded) {
    // Each file once (a glTF given as the input and to --frames, and its buffers, is read twice).
    std::vector<std::string> inputs;
    for (const auto* list : {&job.inputs, &in.filesRead})
        for (const std::string& f : *list)
            if (std::find(inputs.begin(), inputs.end(), f) == inputs.end()) inputs.push_back(f);
    files.depfile->setRule(files.paths, inputs); // the image and/or the mesh
    try {
        // A depfile that cannot be written fails the run before the outputs land; a sequence's
        // frames, already written, are removed.
        files.depfile->prepare();
        if (files.image) {
            files.image->write(encoded.image);
            files.image->finishWriting();
        }
        if (files.mesh) {
            files.mesh->write(encoded.mesh);
            files.mesh->finishWriting();
        }
        if (files.image) files.image->commit();
        if (files.mesh) files.mesh->commit();
        files.depfile->commit();
        clearRemovalOnSignal(); // the run is complete: its frames stay
    } catch (...) {
        removeFrames(files.written);
        throw;
    }
}

} // namespace limn::render_tool
