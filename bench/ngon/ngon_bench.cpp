// ngon_bench [RUNS]: how the cost of one n-gon grows with n (it was quadratic:
// docs/benchmarks.md). Builds a regular n-gon in memory for n = 1,250 .. 32,000
// (the largest face the tables accept is 32,767 sides) and times topology + classification and
// the depth-1 tables, as limn-classify | limn-tables -d 1 do. Prints one JSON line per n (median
// of RUNS, default 5) and, on stderr, the time per side, which stays flat when the cost is linear.
#include "base/json.h"
#include "subdiv/tables.h"
#include "topology/classification.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

using namespace limn;

namespace {

Mesh ngon(uint32_t n) {
    Mesh m;
    std::vector<uint32_t> face(n);
    for (uint32_t i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        m.positions.push_back({std::cos(a), std::sin(a), 0});
        face[i] = i;
    }
    m.addFace(face);
    return m;
}

template <class F> double medianMs(int runs, F&& f) {
    std::vector<double> ms;
    for (int r = 0; r < runs; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                         .count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
    const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    std::fprintf(stderr, "%8s %14s %14s %16s\n", "sides", "classify_ms", "tables_d1_ms",
                 "tables_us/side");
    for (uint32_t n : {1250u, 5000u, 20000u, 32000u}) {
        const Mesh mesh = ngon(n);
        Warnings w;
        const SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
        const double classifyMs = medianMs(runs, [&] {
            Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets,
                          mesh.faceVertices);
            Classification c = classifyMesh(mesh, topo, so, w);
            (void)c;
        });
        TablesOptions to;
        to.depth = 1;
        size_t vertices = 0;
        const double tablesMs = medianMs(runs, [&] { vertices = buildTables(mesh, so, to, w).totalVertices; });
        JsonWriter j;
        j.beginObject().field("bench", "ngon").field("sides", uint64_t(n)).field("runs", runs);
        j.field("classify_ms", classifyMs).field("tables_d1_ms", tablesMs);
        j.field("table_vertices", uint64_t(vertices)).endObject();
        std::printf("%s\n", j.str().c_str());
        std::fprintf(stderr, "%8u %14.2f %14.2f %16.3f\n", n, classifyMs, tablesMs,
                     1000 * tablesMs / n);
    }
    return 0;
}
