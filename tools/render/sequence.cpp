// limn-render's sequences (--turntable, --cameras, --frames): every frame rendered with one
// renderer and written as it is done, with progress on a terminal.
#include "job.h"

#include "base/io.h"
#include "export/mesh_export.h"

#include <chrono>
#include <cstdio>
#include <future>
#include <unistd.h>

namespace limn::render_tool {

namespace {

// "frame 3/36, 12 s left" on stderr, rewritten in place; only on a terminal (a log stays clean).
class Progress {
  public:
    Progress(size_t total, bool quiet) : total_(total), show_(!quiet && total > 1 && ::isatty(STDERR_FILENO) == 1) {}
    void done(size_t count) {
        if (!show_) return;
        const double elapsed = seconds();
        const double left = elapsed / double(count) * double(total_ - count);
        std::fprintf(stderr, "\rlimn-render: frame %zu/%zu, %.0f s left   ", count, total_, left);
        if (count == total_) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

  private:
    size_t total_;
    bool show_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

} // namespace

// The tables, buffers and pipelines stay; per frame only the camera (views) or the control
// points (frames) change. Frame files are committed one by one as they are done (`written` lists
// them, so the caller can remove them if a later step fails); an error here removes them itself.
void renderSequence(render::Renderer& renderer, const RenderJob& job, const RenderInput& in,
                    const gpu::ValidationLog* validation, std::vector<std::string>& written) {
    const std::vector<render::ViewSpec>& views = job.views;
    const std::vector<SequenceFrame>& frames = in.frames;
    const std::vector<uint64_t>& numbers = job.frameNumbers;
    const render::OutputPlan& plan = job.outputs;
    // One framing for the whole animation: the box of every frame's control points.
    if (!frames.empty()) {
        for (const SequenceFrame& f : frames) renderer.extendFraming(f.positions);
        renderer.setCamera(renderer.cameraFor(job.settings.view));
    }
    const std::vector<size_t>& part = job.part; // the frames this run writes (--shard, --frame-range)
    Progress progress(part.size(), job.common.quiet);
    // Frame k is encoded and written on a second thread while frame k + 1 is drawn (about 0.83x
    // the wall time of encoding in turn: docs/benchmarks.md). At most one
    // frame is in flight; its bytes depend only on its own pixels. Output files are only ever
    // made by one thread at a time (the signal handler's list of temporary files is not shared
    // safely): the main thread waits for the frame in flight before writing a --mesh-out.
    // A signal (Ctrl-C, SIGTERM) removes the frames already in place, as an error does.
    prepareRemovalOnSignal(plan.framePaths(job.partNumbers));
    std::future<std::string> pending;
    auto finishPending = [&] {
        if (pending.valid()) written.push_back(pending.get());
    };
    try {
        for (size_t i = 0; i < part.size(); ++i) {
            const size_t k = part[i];
            if (!views.empty()) renderer.setCamera(renderer.cameraFor(views[k]));
            if (!frames.empty()) {
                renderer.setControlPoints(frames[k].positions);
                cli::info("frame " + std::to_string(numbers[k]) + ": new control points from " + frames[k].path);
            }
            renderer.renderFrame();
            if (validation && validation->errors()) checkValidation(*validation); // throws
            renderer.refuseTessellationShortfall(displayName(job.input) + ": frame " + std::to_string(numbers[k]));
            FramePixels pixels = framePixels(renderer, job);
            finishPending();
            if (i > 0) progress.done(i);
            if (plan.meshPattern) {
                const std::string mesh = render::framePath(*plan.meshPattern, numbers[k]);
                writeOutput(mesh, exporting::encodeMesh(renderer.drawnMesh(), *plan.meshFormat, plan.meshAscii),
                            plan.meshFileKind());
                markLandedForRemovalOnSignal(mesh);
                written.push_back(mesh);
            }
            const std::string image = render::framePath(*plan.imagePattern, numbers[k]);
            pending = std::async(std::launch::async, [image, &job, p = std::move(pixels)] {
                writeOutput(image, encodeImage(p, job), OutputFile::Kind::Binary);
                markLandedForRemovalOnSignal(image);
                return image;
            });
        }
        finishPending();
        progress.done(part.size());
    } catch (...) {
        // A frame still being written either lands (and is then removed) or fails on its own.
        if (pending.valid()) {
            try {
                written.push_back(pending.get());
            } catch (...) {
            }
        }
        removeFrames(written);
        written.clear();
        throw;
    }
    char line[128];
    std::snprintf(line, sizeof line, "%zu frames in %.2f s (%.1f ms each, encoding and writing included)",
                  part.size(), progress.seconds(), 1000 * progress.seconds() / double(part.size()));
    cli::info(line);
}

} // namespace limn::render_tool
