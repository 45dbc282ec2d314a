// Frame, compute and draw times of limn-render's subdivision passes, in one process and one run so
// that the ratios are fair on a shared, noisy machine (paper 000, Figures 11-13):
//   - adaptive (feature-adaptive tables) vs uniform (full subdivision) at depths 1-6;
//   - the vertex-stage evaluation of the B-spline patches (--eval vertex) vs a trivial vertex
//     shader fetching the same grid's precomputed vertices (--eval compute's draw): the lavapipe
//     "roofline" of the draw;
//   - texture displacement with and without the seam fix vs no displacement (paper 000, 4.5).
// Configurations are interleaved in rounds and each figure is the median over rounds of the
// per-round medians. One JSON object per line on stdout; a readable table on stderr.
//
// Usage: bench_render [--frames N] [--rounds R] [--size WxH] [--max-depth D] [--quick] MESH...
// (defaults: 10 frames, 3 rounds, 1024x768, depth 6; --quick: 3 frames, 1 round, depth 3)
//
// bench_render --view-adaptive [--frames N] [--rounds R] [--orbit DEG] [--samples 1|4] SPOT.obj [CAR.obj]:
// view-adaptive tessellation (--edge-pixels 4) against the fixed grids
// (--edge-pixels 0): SPOT at 1024x768, depths 3 and 6, adaptive and uniform tables at 5 and 6;
// CAR at depth 6; the paper's demo sphere (generated: 16 segments x 16 rings, triangle fans at
// the poles, radius 1 as in the paper's demo, and radius 5) at 1280x720 from (0,12,22), depth 6.
// --only MODEL (repeatable: spot's or the car's file stem, sphere, sphere_r5) keeps those
// models' rows. --samples: per pixel, 4 (limn-render's default, and this benchmark's) or 1.
// --irregular: instead, the irregular faces' surface (docs/irregular.md) against the bilinear
// irregular faces of before (tables "bilinear": --irregular-levels 0), view-adaptive only: spot
// at depths 3 and 6, the car at 3, the paper's sphere at 6. --no-boundary-bases: tables whose
// faces around boundary vertices are refined, as before TBLS version 7 (the frame cost of those
// bases: run with and without).
// Per configuration: covered pixels,
// drawn triangles (after culling, from the GPU) and triangles per covered pixel, vertices
// evaluated, buffer bytes, compute/draw/frame GPU ms, cpu_ms of a still camera and with the
// camera orbiting DEG degrees per frame (default 2; 0: no orbiting run), and process_cpu_ms: the CPU
// time of all threads a still frame (steadier than wall time on a shared machine; instructions,
// steadier still: bench/render/frame_instructions.sh).
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

using namespace limn;
using namespace limn::render_bench;

namespace {

// One measured configuration: everything it needs lives here so rounds can revisit it.
struct Config {
    std::string model, mode, eval, displace; // displace: none, fix, nofix
    int depth = 0;
    std::shared_ptr<Tables> tables;
    std::shared_ptr<Seams> seams;
    std::string skipped; // why it cannot run (reported instead of numbers)
    std::vector<double> frame, compute, draw, cpu;
    uint64_t triangles = 0, vertices = 0, bufferBytes = 0;
};

// Uniform tables store every vertex of every level as a vec4: when the last levels alone pass the
// storage-buffer limit, limn-render refuses them with a clear message (a GPU buffer over 128 MiB);
// building multi-gigabyte tables only to be refused would dominate the benchmark's time. The
// level-N vertex count of a uniform Catmull-Clark mesh is V_N = V_{N-1} + E_{N-1} + F_{N-1}, with
// E_N = 2 E_{N-1} + S_{N-1} (S: face corners) and F_N = S_{N-1}, S_N = 4 F_N.
uint64_t uniformVertexBytes(const Mesh& mesh, int depth) {
    uint64_t V = mesh.vertexCount(), F = mesh.faceCount(), S = mesh.cornerCount();
    uint64_t E = (S + 0) / 2; // closed-mesh estimate; boundaries make it slightly larger
    uint64_t total = V;
    for (int l = 1; l <= depth; ++l) {
        uint64_t V2 = V + E + F, E2 = 2 * E + S, F2 = S, S2 = 4 * F2;
        V = V2, E = E2, F = F2, S = S2;
        total += V;
    }
    return total * 16;
}

void measure(render::Renderer& r, Config& c, int frames) {
    render::BenchResult b = render::runBenchmark(r, frames, 2);
    c.frame.push_back(b.totalMs);
    c.compute.push_back(b.computeMs);
    c.draw.push_back(b.drawMs);
    c.cpu.push_back(b.cpuMs);
    c.triangles = r.triangleCount();
    c.vertices = r.verticesEvaluated();
    c.bufferBytes = r.bufferBytes();
}

std::string json(const Config& c) {
    char buf[1024];
    if (!c.skipped.empty()) {
        std::snprintf(
            buf, sizeof buf,
            "{\"bench\":\"render\",\"model\":\"%s\",\"depth\":%d,\"mode\":\"%s\",\"eval\":\"%s\","
            "\"displace\":\"%s\",\"skipped\":\"%s\"}",
            c.model.c_str(), c.depth, c.mode.c_str(), c.eval.c_str(), c.displace.c_str(),
            c.skipped.c_str());
        return buf;
    }
    std::snprintf(
        buf, sizeof buf,
        "{\"bench\":\"render\",\"model\":\"%s\",\"depth\":%d,\"mode\":\"%s\",\"eval\":\"%s\","
        "\"displace\":\"%s\",\"frame_ms\":%.3f,\"compute_ms\":%.3f,\"draw_ms\":%.3f,"
        "\"cpu_ms\":%.3f,\"triangles\":%llu,\"vertices_evaluated\":%llu,\"buffer_bytes\":%llu}",
        c.model.c_str(), c.depth, c.mode.c_str(), c.eval.c_str(), c.displace.c_str(),
        median(c.frame), median(c.compute), median(c.draw), median(c.cpu),
        (unsigned long long)c.triangles, (unsigned long long)c.vertices,
        (unsigned long long)c.bufferBytes);
    return buf;
}


int usageError(const std::string& why) {
    std::fprintf(stderr,
                 "bench_render: %s\nusage: bench_render [--frames N] [--rounds R] [--size WxH] "
                 "[--max-depth D] [--quick] MESH...\n",
                 why.c_str());
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    bool viewAdaptive = false, irregular = false;
    double orbitDeg = 2;
    std::set<std::string> only;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--view-adaptive")
            viewAdaptive = true;
        else if (a == "--irregular")
            irregular = true;
        else if (a == "--no-boundary-bases")
            o.boundaryBases = false;
        else if (a == "--only")
            only.insert(next());
        else if (a == "--samples") {
            o.samples = static_cast<uint32_t>(std::atoi(next().c_str()));
            if (o.samples != 1 && o.samples != 4) return usageError("--samples is 1 or 4");
        } else if (a == "--orbit")
            orbitDeg = std::atof(next().c_str());
        else if (a == "--frames")
            o.frames = std::atoi(next().c_str());
        else if (a == "--rounds")
            o.rounds = std::atoi(next().c_str());
        else if (a == "--max-depth")
            o.maxDepth = std::atoi(next().c_str());
        else if (a == "--size") {
            if (std::sscanf(next().c_str(), "%ux%u", &o.width, &o.height) != 2)
                return usageError("bad --size");
        } else if (a == "--quick")
            o.frames = 3, o.rounds = 1, o.maxDepth = 3;
        else if (a.rfind("--", 0) == 0)
            return usageError("unknown option " + a);
        else
            o.meshes.push_back(a);
    }
    if (o.meshes.empty() || o.frames < 1 || o.rounds < 1 || o.maxDepth < 1 || o.maxDepth > 8)
        return usageError("give at least one mesh; frames, rounds >= 1; depth 1-8");
    if (viewAdaptive) {
        try {
            return runViewAdaptive(o, orbitDeg, only, irregular);
        } catch (const Error& e) {
            std::fprintf(stderr, "bench_render: %s\n", e.what());
            return int(e.kind());
        }
    }

    try {
        gpu::Context ctx;
        std::vector<Config> configs;
        std::map<std::string, Mesh> meshes;
        const uint64_t limit = std::min<uint64_t>(ctx.limits().maxStorageBufferRange, 128ull << 20);
        for (const std::string& path : o.meshes) {
            const std::string model = std::filesystem::path(path).stem().string();
            Warnings w;
            Mesh& mesh = meshes[model] = importMeshFile(path, w);
            const SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
            for (int depth = 1; depth <= o.maxDepth; ++depth)
                for (bool uniform : {false, true}) {
                    Config base;
                    base.model = model;
                    base.depth = depth;
                    base.mode = uniform ? "uniform" : "adaptive";
                    base.displace = "none";
                    if (uniform && uniformVertexBytes(mesh, depth) > limit) {
                        base.eval = "compute";
                        char why[160];
                        std::snprintf(why, sizeof why,
                                      "uniform tables need about %.0f MiB of vertices, more than a "
                                      "%.0f MiB storage buffer (limn-render refuses them)",
                                      double(uniformVertexBytes(mesh, depth)) / 1048576.0,
                                      double(limit) / 1048576.0);
                        base.skipped = why;
                        configs.push_back(base);
                        continue;
                    }
                    TablesOptions to;
                    to.depth = depth;
                    to.uniform = uniform;
                    base.tables = std::make_shared<Tables>(buildTables(mesh, so, to, w));
                    for (const char* eval : {"compute", "vertex"}) {
                        Config c = base;
                        c.eval = eval;
                        configs.push_back(c);
                    }
                    // Displacement at depths 2-4 (adaptive and uniform): the seam fix's cost.
                    if (depth >= 2 && depth <= 4 && mesh.hasUVs()) {
                        auto seams = std::make_shared<Seams>(computeSeams(mesh, *base.tables, 0));
                        for (const char* d : {"fix", "nofix"}) {
                            Config c = base;
                            c.eval = "compute";
                            c.displace = d;
                            c.seams = seams;
                            configs.push_back(c);
                        }
                    }
                }
        }
        // The displacement map: 2D noise in UV space, 1024 x 1024 (limn-heightmap --kind uv).
        HeightmapOptions ho;
        ho.kind = HeightmapKind::Uv;
        FloatImage map;
        map.width = map.height = ho.size;
        map.channels = 1;
        map.values = bakeHeightmap(meshes.begin()->second, ho);

        for (int round = 0; round < o.rounds; ++round)
            for (Config& c : configs) {
                if (!c.skipped.empty()) continue;
                render::RenderSettings s;
                s.width = o.width;
                s.height = o.height;
                s.evalInCompute = c.eval == "compute";
                if (c.displace != "none") {
                    s.displacementMap = &map;
                    s.displaceScale = 0.02;
                    s.displaceMid = 0.5;
                    s.seamFix = c.displace == "fix";
                    s.seams = c.seams.get();
                }
                try {
                    render::Renderer r(ctx, meshes.at(c.model), c.tables.get(), s);
                    measure(r, c, o.frames);
                } catch (const Error& e) {
                    c.skipped = e.what();
                }
            }

        for (const Config& c : configs) std::printf("%s\n", json(c).c_str());

        // Ratios in the same run, and the table for the notes.
        auto find = [&](const std::string& model, int depth, const std::string& mode,
                        const std::string& eval, const std::string& displace) -> const Config* {
            for (const Config& c : configs)
                if (c.model == model && c.depth == depth && c.mode == mode && c.eval == eval &&
                    c.displace == displace && c.skipped.empty())
                    return &c;
            return nullptr;
        };
        // limn-render's default for an undisplaced subdivision surface is --eval vertex (the
        // paper's draw); the --eval compute frame ratio is listed too.
        std::fprintf(stderr,
                     "| model | depth | adaptive frame / compute / draw ms | uniform frame / "
                     "compute / draw ms | frame A/U | compute A/U | frame A/U, eval compute | "
                     "vertices A / U | buffers A / U MiB | draw VS-eval / fetch |\n"
                     "|---|---|---|---|---|---|---|---|---|---|\n");
        for (const auto& [model, mesh] : meshes)
            for (int depth = 1; depth <= o.maxDepth; ++depth) {
                const Config* a = find(model, depth, "adaptive", "vertex", "none");
                const Config* u = find(model, depth, "uniform", "vertex", "none");
                const Config* ac = find(model, depth, "adaptive", "compute", "none");
                const Config* uc = find(model, depth, "uniform", "compute", "none");
                if (!a || !ac) continue;
                const double fa = median(a->frame), ca = median(a->compute), da = median(a->draw);
                const double vs = da / median(ac->draw);
                char uCols[256] = "refused (buffer limit) | - | - | -", verts[64], bufs[64];
                std::snprintf(verts, sizeof verts, "%llu / -", (unsigned long long)a->vertices);
                std::snprintf(bufs, sizeof bufs, "%.1f / -", double(a->bufferBytes) / 1048576.0);
                if (u && uc) {
                    const double fu = median(u->frame), cu = median(u->compute),
                                 du = median(u->draw);
                    const double computeFrame = median(ac->frame) / median(uc->frame);
                    std::snprintf(uCols, sizeof uCols, "%.1f / %.1f / %.1f | %.2f | %.3f | %.2f",
                                  fu, cu, du, fa / fu, ca / cu, computeFrame);
                    std::snprintf(verts, sizeof verts, "%llu / %llu",
                                  (unsigned long long)a->vertices, (unsigned long long)u->vertices);
                    std::snprintf(bufs, sizeof bufs, "%.1f / %.1f",
                                  double(a->bufferBytes) / 1048576.0,
                                  double(u->bufferBytes) / 1048576.0);
                    std::printf("{\"bench\":\"render_ratio\",\"model\":\"%s\",\"depth\":%d,"
                                "\"frame_adaptive_over_uniform\":%.4f,"
                                "\"compute_adaptive_over_uniform\":%.4f,"
                                "\"frame_adaptive_over_uniform_eval_compute\":%.4f}\n",
                                model.c_str(), depth, fa / fu, ca / cu, computeFrame);
                }
                std::printf("{\"bench\":\"render_ratio\",\"model\":\"%s\",\"depth\":%d,"
                            "\"draw_vertex_eval_over_fetch\":%.4f}\n",
                            model.c_str(), depth, vs);
                std::fprintf(stderr, "| %s | %d | %.1f / %.1f / %.1f | %s | %s | %s | %.2f |\n",
                             model.c_str(), depth, fa, ca, da, uCols, verts, bufs, vs);
            }
        std::fprintf(
            stderr,
            "\n| model | depth | mode | frame: none / seam fix / no fix ms | fix / none | fix / no "
            "fix |\n|---|---|---|---|---|---|\n");
        for (const auto& [model, mesh] : meshes)
            for (int depth = 2; depth <= std::min(4, o.maxDepth); ++depth)
                for (const char* mode : {"adaptive", "uniform"}) {
                    const Config* n = find(model, depth, mode, "compute", "none");
                    const Config* f = find(model, depth, mode, "compute", "fix");
                    const Config* x = find(model, depth, mode, "compute", "nofix");
                    if (!n || !f || !x) continue;
                    double fn = median(n->frame), ff = median(f->frame), fx = median(x->frame);
                    std::printf("{\"bench\":\"displace_ratio\",\"model\":\"%s\",\"depth\":%d,"
                                "\"mode\":\"%s\","
                                "\"frame_fix_over_none\":%.4f,\"frame_fix_over_nofix\":%.4f}\n",
                                model.c_str(), depth, mode, ff / fn, ff / fx);
                    std::fprintf(stderr, "| %s | %d | %s | %.1f / %.1f / %.1f | %.2f | %.2f |\n",
                                 model.c_str(), depth, mode, fn, ff, fx, ff / fn, ff / fx);
                }
        std::fprintf(stderr, "\ndevice: %s; %d rounds x %d frames, %ux%u\n",
                     ctx.deviceName().c_str(), o.rounds, o.frames, o.width, o.height);
    } catch (const Error& e) {
        std::fprintf(stderr, "bench_render: %s\n", e.what());
        return int(e.kind());
    }
    return 0;
}
