// bench_render --view-adaptive and --irregular (see render_bench.cpp's usage): the view-adaptive
// tessellation against the fixed grids, and the irregular faces' surface against bilinear ones,
// interleaved in rounds; one JSON object per configuration on stdout, a table on stderr.
#include "render_bench.h"

#include "bake/heightmap.h"
#include "base/error.h"
#include "gpu/context.h"
#include "mesh/import.h"
#include "render/bench.h"
#include "render/renderer.h"
#include "seams/seams.h"
#include "paper_sphere.h" // tests/support
#include "subdiv/tables.h"
#include "image/srgb_image.h"
#include "topology/features.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <time.h>

// Under `valgrind --tool=callgrind --instr-atstart=no` (bench/render/frame_instructions.sh) each
// configuration's measured frames are counted alone and dumped under its label: instructions
// are the one measure of a frame that a shared machine's load does not move. Without valgrind
// the requests are a few no-op instructions; without its header, nothing.
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define LIMN_CALLGRIND 1
#endif

namespace limn::render_bench {

namespace {

struct ViewConfig {
    std::string model, tables; // tables: adaptive or uniform
    int depth = 6;
    double edgePixels = 4;
    uint32_t width = 1024, height = 768;
    std::optional<glm::dvec3> eye;
    const Mesh* mesh = nullptr;
    std::shared_ptr<Tables> built;
    std::string skipped;
    std::vector<double> frame, compute, draw, cpu, cpuOrbit, processCpu;
    uint64_t triangles = 0, vertices = 0, bufferBytes = 0, covered = 0;
};

// CPU time of every thread of this process (the main thread's vertex stage and compute passes,
// lavapipe's rasterizer threads), in ms: unlike wall time it does not count the time other
// processes hold the cores, so it is the steadier frame cost on a shared machine.
double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

} // namespace

int runViewAdaptive(const Options& o, double orbitDeg, const std::set<std::string>& only, bool irregular) {
    gpu::Context ctx;
    std::map<std::string, Mesh> meshes;
    Warnings w;
    meshes["sphere"] = test::paperSphere(1);
    meshes["sphere_r5"] = test::paperSphere(5);
    std::string spot, car;
    for (const std::string& path : o.meshes) {
        const std::string model = std::filesystem::path(path).stem().string();
        meshes[model] = importMeshFile(path, w);
        (spot.empty() ? spot : car) = model;
    }
    std::vector<ViewConfig> configs;
    auto add = [&](const std::string& model, const std::string& tables, int depth, double ep,
                   uint32_t W, uint32_t H, std::optional<glm::dvec3> eye = std::nullopt) {
        if (!only.empty() && !only.count(model)) return;
        ViewConfig c;
        c.model = model, c.tables = tables, c.depth = depth, c.edgePixels = ep, c.width = W, c.height = H;
        c.eye = eye;
        configs.push_back(c);
    };
    if (irregular)
        for (const char* tables : {"adaptive", "bilinear"}) {
            if (!spot.empty())
                for (int d : {3, 6}) add(spot, tables, d, 4.0, 1024, 768);
            if (!car.empty()) add(car, tables, 3, 4.0, 1024, 768);
            add("sphere", tables, 6, 4.0, 1280, 720, glm::dvec3(0, 12, 22));
        }
    for (double ep : {4.0, 0.0}) {
        if (irregular) break;
        if (!spot.empty()) {
            for (int d : {3, 5, 6}) add(spot, "adaptive", d, ep, 1024, 768);
            for (int d : {5, 6}) add(spot, "uniform", d, ep, 1024, 768);
        }
        if (!car.empty()) {
            add(car, "adaptive", 6, ep, 1024, 768);
            // The car's uniform tables at depth 5 (1.6 M faces, their limit tables in chunks): the
            // full-subdivision baseline, view-adaptive only (about 9 s a frame here); depth 6
            // is refused (208 MiB of limit points).
            if (ep > 0)
                for (const char* tables : {"adaptive", "uniform"}) add(car, tables, 5, ep, 1024, 768);
        }
        for (const char* sphere : {"sphere", "sphere_r5"})
            add(sphere, "adaptive", 6, ep, 1280, 720, glm::dvec3(0, 12, 22));
    }
    std::map<std::string, std::shared_ptr<Tables>> tableCache;
    for (ViewConfig& c : configs) {
        c.mesh = &meshes.at(c.model);
        const std::string key = c.model + c.tables + std::to_string(c.depth);
        auto& t = tableCache[key];
        if (!t) {
            TablesOptions to;
            to.depth = c.depth;
            to.uniform = c.tables == "uniform";
            if (c.tables == "bilinear") to.irregularLevels = 0;
            to.boundaryBases = to.basisRimFeatures = o.boundaryBases;
            try {
                t = std::make_shared<Tables>(buildTables(*c.mesh, resolveSchemeOptions(c.mesh->tags, {}), to, w));
            } catch (const Error& e) {
                c.skipped = e.what();
            }
        }
        c.built = t;
    }
    for (int round = 0; round < o.rounds; ++round)
        for (ViewConfig& c : configs) {
            if (!c.skipped.empty() || !c.built) continue;
            render::RenderSettings s;
            s.width = c.width, s.height = c.height;
            s.edgePixels = c.edgePixels;
            s.evalInCompute = false; // limn-render's default without displacement
            s.samples = o.samples;
            if (c.eye) s.view.eye = c.eye, s.view.target = glm::dvec3(0.0);
            try {
                render::Renderer r(ctx, *c.mesh, c.built.get(), s);
                for (int i = 0; i < 2; ++i) r.renderFrame(); // shader compilation, caches
                const double cpuStart = processCpuMs();
#ifdef LIMN_CALLGRIND
                CALLGRIND_ZERO_STATS;
                CALLGRIND_START_INSTRUMENTATION;
#endif
                render::BenchResult still = render::runBenchmark(r, o.frames, 0);
#ifdef LIMN_CALLGRIND
                CALLGRIND_STOP_INSTRUMENTATION;
                const std::string label = "frames " + c.model + " " + c.tables + " " + std::to_string(c.depth) +
                                          " " + std::to_string(round);
                CALLGRIND_DUMP_STATS_AT(label.c_str());
#endif
                c.processCpu.push_back((processCpuMs() - cpuStart) / o.frames);
                c.triangles = r.triangleCount();
                c.vertices = r.verticesEvaluated();
                c.bufferBytes = r.bufferBytes();
                Image img = r.image();
                uint64_t covered = 0;
                for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
                    const uint8_t* p = &img.pixels[i * img.channels];
                    covered += !(p[0] == 51 && p[1] == 51 && p[2] == 51); // --background 0.2
                }
                c.covered = covered;
                c.frame.push_back(still.totalMs);
                c.compute.push_back(still.computeMs);
                c.draw.push_back(still.drawMs);
                c.cpu.push_back(still.cpuMs);
                // --orbit 0: no orbiting run (frame_instructions.sh, where each frame is slow).
                c.cpuOrbit.push_back(orbitDeg == 0 ? still.cpuMs : render::runBenchmark(r, o.frames, 0, orbitDeg).cpuMs);
            } catch (const Error& e) {
                c.skipped = e.what();
            }
        }
    std::fprintf(stderr, "| model | size | tables | depth | edge px | covered px | triangles | tri/px | "
                         "vertices eval. | buffers MiB | compute / draw / frame ms | cpu ms still / orbit |\n"
                         "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const ViewConfig& c : configs) {
        if (!c.skipped.empty()) {
            std::printf("{\"bench\":\"view_adaptive\",\"model\":\"%s\",\"tables\":\"%s\",\"depth\":%d,"
                        "\"edge_pixels\":%g,\"skipped\":\"%s\"}\n",
                        c.model.c_str(), c.tables.c_str(), c.depth, c.edgePixels, c.skipped.c_str());
            std::fprintf(stderr, "| %s | %ux%u | %s | %d | %g | refused: %s |\n", c.model.c_str(), c.width,
                         c.height, c.tables.c_str(), c.depth, c.edgePixels, c.skipped.c_str());
            continue;
        }
        const double perPixel = c.covered ? double(c.triangles) / double(c.covered) : 0;
        std::printf("{\"bench\":\"view_adaptive\",\"model\":\"%s\",\"width\":%u,\"height\":%u,"
                    "\"tables\":\"%s\",\"depth\":%d,\"edge_pixels\":%g,\"covered_pixels\":%llu,"
                    "\"triangles\":%llu,\"triangles_per_covered_pixel\":%.4f,\"vertices_evaluated\":%llu,"
                    "\"buffer_bytes\":%llu,\"compute_ms\":%.3f,\"draw_ms\":%.3f,\"frame_ms\":%.3f,"
                    "\"cpu_ms\":%.3f,\"cpu_ms_orbit\":%.3f,\"orbit_deg\":%g,\"process_cpu_ms\":%.3f}\n",
                    c.model.c_str(), c.width, c.height, c.tables.c_str(), c.depth, c.edgePixels,
                    (unsigned long long)c.covered, (unsigned long long)c.triangles, perPixel,
                    (unsigned long long)c.vertices, (unsigned long long)c.bufferBytes, median(c.compute),
                    median(c.draw), median(c.frame), median(c.cpu), median(c.cpuOrbit), orbitDeg,
                    median(c.processCpu));
        std::fprintf(stderr, "| %s | %ux%u | %s | %d | %g | %llu | %llu | %.3f | %llu | %.1f | %.1f / %.1f / %.1f | %.1f / %.1f |\n",
                     c.model.c_str(), c.width, c.height, c.tables.c_str(), c.depth, c.edgePixels,
                     (unsigned long long)c.covered, (unsigned long long)c.triangles, perPixel,
                     (unsigned long long)c.vertices, double(c.bufferBytes) / 1048576.0, median(c.compute),
                     median(c.draw), median(c.frame), median(c.cpu), median(c.cpuOrbit));
    }
    // Adaptive over uniform tables, both view-adaptive at the default edge pixels (view-adaptive
    // tessellation's target: at most 0.3 at depths 5 and 6).
    for (const ViewConfig& a : configs)
        for (const ViewConfig& u : configs)
            if (a.tables == "adaptive" && u.tables == "uniform" && a.model == u.model && a.depth == u.depth &&
                a.edgePixels == u.edgePixels && a.edgePixels > 0 && a.skipped.empty() && u.skipped.empty()) {
                std::printf("{\"bench\":\"view_adaptive_tables_ratio\",\"model\":\"%s\",\"depth\":%d,"
                            "\"frame_adaptive_over_uniform\":%.4f}\n",
                            a.model.c_str(), a.depth, median(a.frame) / median(u.frame));
                std::fprintf(stderr, "%s depth %d: adaptive / uniform frame %.3f\n", a.model.c_str(), a.depth,
                             median(a.frame) / median(u.frame));
            }
    // The irregular faces' surface over bilinear irregular faces (at most 1.1 wanted).
    for (const ViewConfig& a : configs)
        for (const ViewConfig& b : configs)
            if (a.tables == "adaptive" && b.tables == "bilinear" && a.model == b.model && a.depth == b.depth &&
                a.skipped.empty() && b.skipped.empty()) {
                std::printf("{\"bench\":\"irregular_surface_ratio\",\"model\":\"%s\",\"depth\":%d,"
                            "\"frame_over_bilinear\":%.4f,\"process_cpu_over_bilinear\":%.4f,"
                            "\"triangles_over_bilinear\":%.4f}\n",
                            a.model.c_str(), a.depth, median(a.frame) / median(b.frame),
                            median(a.processCpu) / median(b.processCpu),
                            double(a.triangles) / double(std::max<uint64_t>(b.triangles, 1)));
                std::fprintf(stderr, "%s depth %d: irregular surface / bilinear frame %.3f, process CPU %.3f, triangles %.3f\n",
                             a.model.c_str(), a.depth, median(a.frame) / median(b.frame),
                             median(a.processCpu) / median(b.processCpu),
                             double(a.triangles) / double(std::max<uint64_t>(b.triangles, 1)));
            }
    std::fprintf(stderr, "\ndevice: %s; %d rounds x %d frames; %u sample(s) a pixel; orbit %g deg/frame\n",
                 ctx.deviceName().c_str(), o.rounds, o.frames, o.samples, orbitDeg);
    return 0;
}

} // namespace limn::render_bench
