#include "render/bench.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <map>

// Under `valgrind --tool=callgrind --instr-atstart=no` only the measured frames are counted, on
// every thread (instrumentation is process-wide: lavapipe's rasterizer threads too), not start-up
// or the warm-up frames where lavapipe's LLVM compiles the shaders: instructions a frame, the one
// frame cost that a shared machine's load does not move (bench/render/error_rates.sh -I). Without
// valgrind the requests are a few no-op instructions; without its header, nothing.
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define LIMN_CALLGRIND 1
#endif

namespace limn::render {

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

} // namespace

BenchResult runBenchmark(Renderer& renderer, int frames, int warmup, double orbitDeg) {
    using Clock = std::chrono::steady_clock;
    auto orbit = [&] {
        if (orbitDeg == 0) return;
        Camera cam = renderer.camera();
        const glm::dvec3 axis = glm::normalize(cam.up);
        const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), glm::radians(orbitDeg), axis);
        cam.eye = cam.target + glm::dvec3(turn * glm::dvec4(cam.eye - cam.target, 0.0));
        renderer.setCamera(cam);
    };
    for (int i = 0; i < warmup; ++i) renderer.renderFrame();
    std::vector<double> cpu, compute, draw, total;
    std::map<std::string, std::vector<double>> passes;
    std::vector<std::string> order;
    cpu.reserve(frames), compute.reserve(frames), draw.reserve(frames), total.reserve(frames);
#ifdef LIMN_CALLGRIND
    CALLGRIND_START_INSTRUMENTATION;
#endif
    for (int i = 0; i < frames; ++i) {
        auto start = Clock::now();
        orbit();
        renderer.renderFrame();
        cpu.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        FrameTimes t = renderer.frameTimes();
        compute.push_back(t.computeMs);
        draw.push_back(t.drawMs);
        total.push_back(t.totalMs);
        for (const auto& p : t.passes) {
            if (!passes.count(p.name)) order.push_back(p.name);
            passes[p.name].push_back(p.ms);
        }
    }
#ifdef LIMN_CALLGRIND
    CALLGRIND_STOP_INSTRUMENTATION;
#endif
    BenchResult r;
    r.frames = frames;
    r.computeMs = median(compute);
    r.drawMs = median(draw);
    r.totalMs = median(total);
    r.cpuMs = median(cpu);
    for (const auto& name : order) r.passes.emplace_back(name, median(passes[name]));
    return r;
}

} // namespace limn::render
