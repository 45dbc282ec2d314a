// Evaluation speed of the blending surface (paper 001, section 5 compares its GPU vertex program
// against "CPU rendering", 15-20x on a GeForce 6800). Prints JSON lines:
//
//   blend_cpu_eval     single-threaded evaluateBlendSurface over a K×K grid of samples per face
//                      (u, v = i/(K−1)), positions and normals, per weight kind.
//   blend_gpu_vs_cpu   the same surface points both ways in one run: the points limn-render
//                      --grid K evaluates (every shared point once, V + E(K−1) + F(K−1)²), by the
//                      CPU evaluator (one thread, f64) and by limn-render's compute pass (f32, on
//                      the Vulkan device: lavapipe spreads it over the host's cores), medians of
//                      RUNS; plus the frame times of --eval compute and --eval vertex.
//
// Usage: bench_blend [MESH.obj] [K] [RUNS]   (default: spot quadrangulated linearly, 16, 7)
#include "base/error.h"
#include "base/json.h"
#include "blend/blend_surface.h"
#include "blend/quadrangulate.h"
#include "gpu/context.h"
#include "mesh/import.h"
#include "render/bench.h"
#include "render/blend_draw.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

using namespace limn;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double passMs(const render::BenchResult& b, const std::string& name) {
    for (const auto& [n, ms] : b.passes)
        if (n == name) return ms;
    return 0;
}

void cpuEvalLines(const Mesh& mesh, const Topology& topo, const std::string& name, int K,
                  int runs) {
    const size_t points = mesh.faceCount() * size_t(K) * K;
    for (auto weights : {blend::WeightKind::Cubic, blend::WeightKind::Quintic}) {
        auto t0 = Clock::now();
        blend::BlendSurface s =
            blend::buildBlendSurface(mesh, topo, {weights, blend::ChartType::Conformal});
        double buildSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
        std::vector<double> seconds;
        double checksum = 0;
        for (int r = 0; r < runs; ++r) {
            auto start = Clock::now();
            for (uint32_t f = 0; f < mesh.faceCount(); ++f)
                for (int i = 0; i < K; ++i)
                    for (int j = 0; j < K; ++j) {
                        auto p = blend::evaluateBlendSurface(s, f, double(i) / (K - 1),
                                                             double(j) / (K - 1));
                        checksum += p.position.x + p.normal.y;
                    }
            seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
        }
        std::sort(seconds.begin(), seconds.end());
        double med = seconds[seconds.size() / 2];
        JsonWriter j;
        j.beginObject()
            .field("bench", "blend_cpu_eval")
            .field("mesh", name)
            .field("vertices", mesh.vertexCount())
            .field("faces", mesh.faceCount())
            .field("grid", K)
            .field("weights", weights == blend::WeightKind::Cubic ? "cubic" : "quintic")
            .field("threads", 1)
            .field("points", points)
            .field("runs", runs)
            .field("build_s", buildSeconds)
            .field("median_s", med)
            .field("min_s", seconds.front())
            .field("points_per_s", double(points) / med)
            .field("checksum", checksum / runs)
            .endObject();
        std::printf("%s\n", j.str().c_str());
    }
}

void gpuVsCpuLine(const Mesh& mesh, const Topology& topo, const std::string& name, int K,
                  int runs) {
    blend::BlendSurface s = blend::buildBlendSurface(mesh, topo, {});
    const render::BlendDraw draw = render::prepareBlend(mesh, s, static_cast<uint32_t>(K));
    const size_t points = draw.points.size();

    std::vector<double> cpuSeconds;
    double checksum = 0;
    for (int r = 0; r < runs; ++r) {
        auto start = Clock::now();
        for (const auto& p : draw.points) {
            auto e = blend::evaluateBlendSurface(s, p.face, double(p.ij & 0xFFFF) / K,
                                                 double(p.ij >> 16) / K);
            checksum += e.position.x + e.normal.y;
        }
        cpuSeconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    const double cpuS = median(cpuSeconds);

    gpu::Context ctx(gpu::ContextOptions{});
    render::RenderSettings settings; // 1024×768, as limn-render by default
    settings.blendGrid = static_cast<uint32_t>(K);
    render::BenchResult compute, vertex;
    {
        render::Renderer renderer(ctx, mesh, s, settings);
        compute = render::runBenchmark(renderer, runs);
    }
    settings.evalInCompute = false;
    {
        render::Renderer renderer(ctx, mesh, s, settings);
        vertex = render::runBenchmark(renderer, runs);
    }
    const double evalMs = passMs(compute, "evaluate blend surface");
    const double gpuPerS = double(points) / (evalMs / 1000);
    JsonWriter j;
    j.beginObject()
        .field("bench", "blend_gpu_vs_cpu")
        .field("mesh", name)
        .field("vertices", mesh.vertexCount())
        .field("faces", mesh.faceCount())
        .field("grid", K)
        .field("weights", "cubic")
        .field("points", points)
        .field("runs", runs)
        .field("cpu_threads", 1)
        .field("cpu_median_s", cpuS)
        .field("cpu_points_per_s", double(points) / cpuS)
        .field("gpu_device", ctx.deviceName())
        .field("host_cores", std::thread::hardware_concurrency())
        .field("gpu_eval_median_ms", evalMs)
        .field("gpu_points_per_s", gpuPerS)
        .field("gpu_over_cpu", gpuPerS / (double(points) / cpuS))
        .field("triangles", draw.triangles.size() / 3)
        .field("compute_path_frame_ms", compute.totalMs)
        .field("compute_path_draw_ms", compute.drawMs)
        .field("vertex_path_frame_ms", vertex.totalMs)
        .field("vertex_path_draw_ms", vertex.drawMs)
        .field("vertex_path_grid_vertices", draw.drawVertices.size())
        .field("checksum", checksum / runs)
        .endObject();
    std::printf("%s\n", j.str().c_str());
}

} // namespace

int main(int argc, char** argv) {
    std::string path = argc > 1 ? argv[1] : LIMN_TEST_DATA_DIR "/quad/spot_control_mesh.obj";
    int K = argc > 2 ? std::stoi(argv[2]) : 16, runs = argc > 3 ? std::stoi(argv[3]) : 7;
    Warnings warnings;
    Mesh mesh = importMeshFile(path, warnings);
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    if (!blend::isQuadMesh(mesh)) {
        mesh = blend::quadrangulateLinear(mesh, topo);
        topo = Topology(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets,
                        mesh.faceVertices);
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    cpuEvalLines(mesh, topo, name, K, runs);
    try {
        gpuVsCpuLine(mesh, topo, name, K, runs);
    } catch (const Error& e) {
        JsonWriter j;
        j.beginObject().field("bench", "blend_gpu_vs_cpu").field("error", e.what()).endObject();
        std::printf("%s\n", j.str().c_str());
        return 1;
    }
    return 0;
}
