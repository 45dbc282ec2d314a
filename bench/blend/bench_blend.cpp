// CPU evaluation speed of the blending surface (paper 001, section 5 compares its GPU vertex
// program against this "CPU rendering"): single-threaded evaluateBlendSurface over a K×K grid of
// samples per face, positions and normals. Prints one JSON line per configuration.
//
// Usage: bench_blend [MESH.obj] [K] [RUNS]   (default: spot quadrangulated linearly, 16, 7)
#include "base/json.h"
#include "blend/blend_surface.h"
#include "blend/quadrangulate.h"
#include "mesh/import.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

using namespace limn;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
    std::string path = argc > 1 ? argv[1] : LIMN_SHARED_DIR "/models/quad/spot_control_mesh.obj";
    int K = argc > 2 ? std::stoi(argv[2]) : 16, runs = argc > 3 ? std::stoi(argv[3]) : 7;
    Warnings warnings;
    Mesh mesh = importMeshFile(path, warnings);
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    if (!blend::isQuadMesh(mesh)) {
        mesh = blend::quadrangulateLinear(mesh, topo);
        topo = Topology(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    }
    const size_t points = mesh.faceCount() * size_t(K) * K;
    for (auto weights : {blend::WeightKind::Cubic, blend::WeightKind::Quintic}) {
        auto t0 = Clock::now();
        blend::BlendSurface s = blend::buildBlendSurface(mesh, topo, {weights, blend::ChartType::Conformal});
        double buildSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
        std::vector<double> seconds;
        double checksum = 0;
        for (int r = 0; r < runs; ++r) {
            auto start = Clock::now();
            for (uint32_t f = 0; f < mesh.faceCount(); ++f)
                for (int i = 0; i < K; ++i)
                    for (int j = 0; j < K; ++j) {
                        auto p = blend::evaluateBlendSurface(s, f, double(i) / (K - 1), double(j) / (K - 1));
                        checksum += p.position.x + p.normal.y;
                    }
            seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
        }
        std::sort(seconds.begin(), seconds.end());
        double median = seconds[seconds.size() / 2];
        JsonWriter j;
        j.beginObject()
            .field("bench", "blend_cpu_eval")
            .field("mesh", path.substr(path.find_last_of('/') + 1))
            .field("vertices", mesh.vertexCount())
            .field("faces", mesh.faceCount())
            .field("grid", K)
            .field("weights", weights == blend::WeightKind::Cubic ? "cubic" : "quintic")
            .field("threads", 1)
            .field("points", points)
            .field("runs", runs)
            .field("build_s", buildSeconds)
            .field("median_s", median)
            .field("min_s", seconds.front())
            .field("points_per_s", double(points) / median)
            .field("checksum", checksum / runs)
            .endObject();
        std::printf("%s\n", j.str().c_str());
    }
    return 0;
}
