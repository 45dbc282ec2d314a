// --bench: the whole frame (upload, compute, draw, readback) re-recorded and re-run many times;
// medians of GPU timestamps and of host time per frame. Numbers for measuring, never for output
// files (they vary run to run).
#pragma once

#include "render/renderer.h"

#include <string>
#include <utility>
#include <vector>

namespace limn::render {

struct BenchResult {
    int frames = 0;
    double computeMs = 0, drawMs = 0, totalMs = 0; // GPU medians (FrameTimes)
    double cpuMs = 0;                              // host median per frame: record, submit, wait
    std::vector<std::pair<std::string, double>> passes; // GPU median per pass, in frame order
};

// Renders `warmup` frames (shader compilation, caches), then `frames` measured ones. With
// `orbitDeg`, the camera turns that many degrees about its target (around its up vector) before
// every frame, the way an interactive viewer would move it: only GPU passes re-run.
BenchResult runBenchmark(Renderer& renderer, int frames, int warmup = 3, double orbitDeg = 0);

} // namespace limn::render
