// limn-render on the device: the Vulkan context, the renderer for the input's surface, one frame
// (or a sequence, or --bench's frames with their JSON), the encoded outputs, the validation log.
#include "job.h"

#include "base/error.h"
#include "base/json.h"
#include "render/bench.h"
#include "export/mesh_export.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sys/resource.h>

namespace limn::render_tool {

namespace {

double peakRssMb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0; // kilobytes on Linux
}

// --bench: FRAMES frames after 3 warm-up ones, one JSON object of medians on standard output.
void benchmark(render::Renderer& renderer, const RenderJob& job, const gpu::Context& ctx) {
    const render::RenderSettings& settings = job.settings;
    render::BenchResult b = render::runBenchmark(renderer, job.bench, 3, job.benchOrbit);
    renderer.refuseTessellationShortfall(displayName(job.input)); // before any JSON
    JsonWriter j;
    j.beginObject().field("frames", b.frames);
    j.field("samples", settings.samples).field("sample_shading", settings.sampleShading);
    j.field("supersample", settings.supersample);
    j.field("size", std::to_string(settings.width) + "x" + std::to_string(settings.height));
    j.key("gpu_ms").beginObject();
    j.field("compute", b.computeMs).field("draw", b.drawMs).field("total", b.totalMs);
    j.endObject();
    j.key("passes").beginObject();
    for (const auto& [name, ms] : b.passes) j.field(name, ms);
    j.endObject();
    j.field("cpu_ms", b.cpuMs)
        .field("triangles", renderer.triangleCount())
        .field("vertices_evaluated", renderer.verticesEvaluated())
        .field("buffer_bytes", renderer.bufferBytes())
        .field("peak_rss_mb", peakRssMb())
        .field("device", ctx.deviceName());
    j.endObject();
    std::cout << j.str() << "\n";
    std::cout.flush();
}

} // namespace

void checkValidation(const gpu::ValidationLog& log) {
    auto messages = log.messages();
    const size_t shown = std::min<size_t>(messages.size(), 10);
    for (size_t i = 0; i < shown; ++i)
        if (log.errors() || messages[i].rfind("warning", 0) == 0)
            cli::warn("validation " + messages[i]);
    if (log.errors())
        throw Error(ErrorKind::BadInput, std::to_string(log.errors()) +
                                             " Vulkan validation errors, " +
                                             std::to_string(log.warnings()) +
                                             " warnings (first ones above); no output written");
    cli::info("validation: 0 errors, " + std::to_string(log.warnings()) + " warnings");
}

std::future<std::unique_ptr<gpu::Context>> startDevice(const RenderJob& job) {
    gpu::ContextOptions options;
    options.device = job.device;
    options.validation = job.syncValidation ? gpu::Validation::Synchronization
                         : job.validate     ? gpu::Validation::On
                                            : gpu::Validation::Off;
    return std::async(std::launch::async, [options] { return std::make_unique<gpu::Context>(options); });
}

EncodedOutputs renderOnDevice(const RenderJob& job, const RenderInput& in, std::unique_ptr<gpu::Context> context,
                              OutputFiles& files) {
    const render::RenderSettings& settings = job.settings;
    std::shared_ptr<gpu::ValidationLog> validation;
    EncodedOutputs encoded;
    {
        gpu::Context& ctx = *context;
        validation = ctx.sharedValidationLog();
        for (const auto& line : ctx.selectionReport()) cli::info(line);
        std::optional<render::Renderer> chosen;
        if (in.blend)
            chosen.emplace(ctx, in.mesh, *in.blend, settings);
        else
            chosen.emplace(ctx, in.mesh, in.tables ? &*in.tables : nullptr, settings);
        render::Renderer& renderer = *chosen;
        // Once per run, also for a sequence: its frames reuse these buffers and pipelines.
        cli::info("set up the GPU surface: " + cli::formatBytes(renderer.bufferBytes()) +
                  " of buffers (tables, tessellation, frame)");
        const auto& cam = renderer.camera();
        cli::info("camera eye " + std::to_string(cam.eye.x) + "," + std::to_string(cam.eye.y) +
                  "," + std::to_string(cam.eye.z) + " target " + std::to_string(cam.target.x) +
                  "," + std::to_string(cam.target.y) + "," + std::to_string(cam.target.z));

        if (job.sequence)
            renderSequence(renderer, job, in, validation.get(), files.written);
        else if (job.bench)
            benchmark(renderer, job, ctx);
        else
            renderer.renderFrame();
        if (!job.sequence) renderer.refuseTessellationShortfall(displayName(job.input));
        for (const auto& p : renderer.frameTimes().passes) {
            char ms[32];
            std::snprintf(ms, sizeof ms, "%.3f", p.ms);
            cli::info("GPU " + p.name + ": " + ms + " ms");
        }
        if (files.image) encoded.image = encodeImage(framePixels(renderer, job), job);
        if (files.mesh) {
            if (in.blend && in.mesh.hasUVs())
                cli::info("--mesh-out: a blending surface shares its vertices across faces; "
                          "no texture UVs written");
            encoded.mesh =
                exporting::encodeMesh(renderer.drawnMesh(), *job.outputs.meshFormat, job.meshAscii);
        }
        // The renderer goes before the context it was made with.
        chosen.reset();
        context.reset();
    }
    if (validation) {
        try {
            checkValidation(*validation);
        } catch (...) {
            removeFrames(files.written);
            throw;
        }
    }
    return encoded;
}

} // namespace limn::render_tool
