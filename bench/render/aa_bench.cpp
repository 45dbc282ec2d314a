// The cost of anti-aliasing: limn-render's frame with --samples 1, --samples 4 (the
// default), --samples 4 --sample-shading and --supersample 2, in one process and one run, configurations interleaved in rounds
// (the machine is shared and noisy: only ratios measured together mean something). Each figure
// is the median over rounds of per-round medians of GPU timestamps (frame = every timed pass,
// readback included; draw = the draw pass, where MSAA and its resolve happen) and of host time
// per frame. The supersample row leaves out the CPU box filter (it runs once per image, not per
// frame); the tool's output conversion is not part of a frame either.
//
// Usage: bench_aa [--frames N] [--rounds R] [--size WxH] [--depth D] MESH
// (defaults: 10 frames, 5 rounds, 1024x768, depth 4). One JSON object per configuration on
// stdout, then one with the ratios; a table on stderr.
#include "base/error.h"
#include "gpu/context.h"
#include "mesh/import.h"
#include "render/bench.h"
#include "render/renderer.h"
#include "subdiv/tables.h"
#include "topology/features.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace limn;

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Config {
    const char* name;
    uint32_t samples, supersample;
    bool sampleShading;
    std::vector<double> frame, draw, cpu;
};

} // namespace

int main(int argc, char** argv) {
    int frames = 10, rounds = 5, depth = 4;
    uint32_t width = 1024, height = 768;
    std::string path;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--frames") frames = std::atoi(next().c_str());
        else if (a == "--rounds") rounds = std::atoi(next().c_str());
        else if (a == "--depth") depth = std::atoi(next().c_str());
        else if (a == "--size") {
            if (std::sscanf(next().c_str(), "%ux%u", &width, &height) != 2) path.clear(), frames = 0;
        } else if (a.rfind("--", 0) == 0 || !path.empty()) frames = 0;
        else path = a;
    }
    if (path.empty() || frames < 1 || rounds < 1 || depth < 1 || depth > 8) {
        std::fprintf(stderr, "usage: bench_aa [--frames N] [--rounds R] [--size WxH] [--depth D] MESH\n");
        return 2;
    }
    try {
        gpu::Context ctx;
        Warnings w;
        Mesh mesh = importMeshFile(path, w);
        TablesOptions to;
        to.depth = depth;
        const Tables tables = buildTables(mesh, resolveSchemeOptions(mesh.tags, {}), to, w);
        std::vector<Config> configs = {{"samples 1", 1, 1, false, {}, {}, {}},
                                       {"samples 4", 4, 1, false, {}, {}, {}},
                                       {"samples 4, sample shading", 4, 1, true, {}, {}, {}},
                                       {"supersample 2 (samples 4)", 4, 2, false, {}, {}, {}}};
        uint64_t triangles = 0;
        for (int round = 0; round < rounds; ++round)
            for (Config& c : configs) {
                render::RenderSettings s; // limn-render's defaults otherwise
                s.width = width, s.height = height;
                s.edgePixels = 4;
                s.evalInCompute = false;
                s.samples = c.samples;
                s.supersample = c.supersample;
                s.sampleShading = c.sampleShading;
                render::Renderer r(ctx, mesh, &tables, s);
                render::BenchResult b = render::runBenchmark(r, frames, 2);
                c.frame.push_back(b.totalMs);
                c.draw.push_back(b.drawMs);
                c.cpu.push_back(b.cpuMs);
                if (c.samples == 1) triangles = r.triangleCount();
            }
        std::fprintf(stderr, "| configuration | frame ms | draw ms | cpu ms |\n|---|---|---|---|\n");
        for (const Config& c : configs) {
            std::printf("{\"bench\":\"antialiasing\",\"config\":\"%s\",\"samples\":%u,"
                        "\"sample_shading\":%s,\"supersample\":%u,\"width\":%u,\"height\":%u,"
                        "\"depth\":%d,\"frame_ms\":%.3f,\"draw_ms\":%.3f,\"cpu_ms\":%.3f}\n",
                        c.name, c.samples, c.sampleShading ? "true" : "false", c.supersample, width,
                        height, depth, median(c.frame), median(c.draw), median(c.cpu));
            std::fprintf(stderr, "| %s | %.2f | %.2f | %.2f |\n", c.name, median(c.frame),
                         median(c.draw), median(c.cpu));
        }
        const double f1 = median(configs[0].frame), d1 = median(configs[0].draw), c1 = median(configs[0].cpu);
        std::printf("{\"bench\":\"antialiasing_ratio\",\"frame_4_over_1\":%.3f,\"draw_4_over_1\":%.3f,"
                    "\"cpu_4_over_1\":%.3f,\"frame_shading_over_4\":%.3f,\"draw_shading_over_4\":%.3f,"
                    "\"frame_ss2_over_1\":%.3f,\"triangles\":%llu,\"device\":\"%s\"}\n",
                    median(configs[1].frame) / f1, median(configs[1].draw) / d1,
                    median(configs[1].cpu) / c1, median(configs[2].frame) / median(configs[1].frame),
                    median(configs[2].draw) / median(configs[1].draw), median(configs[3].frame) / f1,
                    (unsigned long long)triangles, ctx.deviceName().c_str());
        std::fprintf(stderr, "\n%s, depth %d, %ux%u, %d rounds x %d frames; device %s\n", path.c_str(),
                     depth, width, height, rounds, frames, ctx.deviceName().c_str());
        return 0;
    } catch (const Error& e) {
        std::fprintf(stderr, "bench_aa: %s\n", e.what());
        return int(e.kind());
    }
}
