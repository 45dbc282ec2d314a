// What bench_render's two halves share (render_bench.cpp: adaptive vs uniform, evaluation and
// displacement; view_adaptive_bench.cpp: --view-adaptive and --irregular).
#pragma once

#include <algorithm>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace limn::render_bench {

struct Options {
    int frames = 10, rounds = 3, maxDepth = 6;
    uint32_t width = 1024, height = 768;
    uint32_t samples = 4; // --view-adaptive: limn-render's default
    // --no-boundary-bases (--view-adaptive): tables with faces around boundary vertices refined
    // (TablesOptions::boundaryBases and basisRimFeatures off), as before TBLS version 7.
    bool boundaryBases = true;
    std::vector<std::string> meshes;
};

inline double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}


// --view-adaptive (and --irregular): view_adaptive_bench.cpp.
int runViewAdaptive(const Options& o, double orbitDeg, const std::set<std::string>& only, bool irregular);

} // namespace limn::render_bench
