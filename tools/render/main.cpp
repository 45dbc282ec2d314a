// limn-render: renders a .limn container (or any mesh limn reads) headlessly on Vulkan and
// writes a deterministic PNG: the blending surface (BLND), the subdivision surface (TBLS) or the
// control mesh, flat shaded.
//
// The tool by concern, around one RenderJob (job.h): options.cpp and help.cpp parse the command
// line; job.cpp checks the options against each other and plans the sequence and the outputs
// (render/sequence_plan.h, render/output_plan.h); input.cpp reads the input, its frames and
// maps; device.cpp draws on the Vulkan device; sequence.cpp renders a sequence frame by frame;
// output.cpp encodes and commits the files.
#include "job.h"

using namespace limn;
using namespace limn::render_tool;

int main(int argc, char** argv) {
    return cli::run("limn-render", argc, argv, [](int ac, char** av) {
        RenderJob job;
        if (!parseOptions(ac, av, job)) return 0;
        planJob(job);
        // Outputs are opened first: a refused terminal or an unwritable directory fails before
        // any work.
        OutputFiles files;
        openOutputs(job, files);
        // The device starts up (Vulkan instance, lavapipe's threads and LLVM) while the input is
        // read and checked: on two cores the two overlap. A bad input still reports first; the
        // future's destructor then waits for the unused context and releases it.
        std::future<std::unique_ptr<gpu::Context>> pendingContext = startDevice(job);
        RenderInput in;
        readRenderInput(job, in);
        if (job.outputs.meshPattern) refuseOversizedSequence(job, &in); // now with the meshes
        const EncodedOutputs encoded = renderOnDevice(job, in, pendingContext.get(), files);
        commitOutputs(job, in, files, encoded);
        return 0;
    });
}
