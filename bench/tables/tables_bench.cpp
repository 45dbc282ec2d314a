// Table size and build time of limn-tables next to OpenSubdiv on the same mesh in the same run
// (issue: spot and the 100,800-quad car, depths 1-6, adaptive and uniform). Prints one JSON
// object per line and a readable table on stderr. Usage: tables_bench [--quick] MESH...
#include "mesh/import.h"
#include "subdiv/tables_chunk.h"
#include "topology/features.h"

#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace limn;
using namespace OpenSubdiv;

namespace {

double median(std::vector<double> ms) {
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

double elapsedMs(const std::function<void()>& f) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

Far::TopologyRefiner* osdRefiner(const Mesh& m, const SchemeOptions& o) {
    static std::vector<int> sizes, verts, creaseVerts, cornerVerts, holes;
    static std::vector<float> creaseW, cornerW;
    sizes.clear();
    for (size_t f = 0; f < m.faceCount(); ++f) sizes.push_back(int(m.faceSize(f)));
    verts.assign(m.faceVertices.begin(), m.faceVertices.end());
    creaseVerts.clear();
    creaseW.clear();
    for (const auto& c : m.tags.creases) {
        creaseVerts.push_back(int(c.v0));
        creaseVerts.push_back(int(c.v1));
        creaseW.push_back(c.sharpness);
    }
    cornerVerts.clear();
    cornerW.clear();
    for (const auto& c : m.tags.corners) {
        cornerVerts.push_back(int(c.vertex));
        cornerW.push_back(c.sharpness);
    }
    holes.assign(m.tags.holes.begin(), m.tags.holes.end());
    Far::TopologyDescriptor d;
    d.numVertices = int(m.vertexCount());
    d.numFaces = int(m.faceCount());
    d.numVertsPerFace = sizes.data();
    d.vertIndicesPerFace = verts.data();
    d.numCreases = int(creaseW.size());
    d.creaseVertexIndexPairs = creaseVerts.data();
    d.creaseWeights = creaseW.data();
    d.numCorners = int(cornerW.size());
    d.cornerVertexIndices = cornerVerts.data();
    d.cornerWeights = cornerW.data();
    d.numHoles = int(holes.size());
    d.holeIndices = holes.data();
    Sdc::Options so;
    so.SetVtxBoundaryInterpolation(o.boundary == BoundaryRule::EdgeOnly ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                   : o.boundary == BoundaryRule::None ? Sdc::Options::VTX_BOUNDARY_NONE
                                                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    so.SetCreasingMethod(o.creaseMethod == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                 : Sdc::Options::CREASE_UNIFORM);
    using F = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return F::Create(d, F::Options(Sdc::SCHEME_CATMARK, so));
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false, adaptiveOnly = false;
    std::vector<std::string> models;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--quick") quick = true;
        else if (a == "--adaptive") adaptiveOnly = true;
        else models.push_back(a);
    }
    if (models.empty()) {
        std::fprintf(stderr, "usage: tables_bench [--quick] [--adaptive] MESH...\n");
        return 2;
    }
    const int runs = quick ? 1 : 3;
    Far::SetErrorCallback([](Far::ErrorType, const char* m) { std::fprintf(stderr, "osd: %s\n", m); });
    Far::SetWarningCallback([](const char*) {});
    std::fprintf(stderr, "%-28s %5s %-8s %12s %10s %10s %7s %8s\n", "mesh", "depth", "mode",
                 "table_bytes", "limn_ms", "osd_ms", "ratio", "patches");
    for (const auto& path : models) {
        Warnings w;
        Mesh mesh;
        try {
            mesh = importMeshFile(path, w);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "tables_bench: error: %s: %s\n", path.c_str(), e.what());
            return 1;
        }
        SchemeOptions options = resolveSchemeOptions(mesh.tags, {});
        std::string name = path.substr(path.find_last_of('/') + 1);
        for (bool uniform : {false, true}) {
            if (uniform && adaptiveOnly) continue;
            for (int depth = 1; depth <= 6; ++depth) {
                // Uniform tables grow 4x per level: stop before they exceed ~8 M vertices.
                double estimate = double(mesh.faceCount()) * std::pow(4.0, depth);
                if (uniform && estimate > 8e6) {
                    std::printf("{\"mesh\":\"%s\",\"depth\":%d,\"mode\":\"uniform\",\"skipped\":"
                                "\"about %.0f vertices\"}\n", name.c_str(), depth, estimate);
                    continue;
                }
                TablesOptions to;
                to.depth = depth;
                to.uniform = uniform;
                Tables tables;
                size_t bytes = 0;
                auto buildLimn = [&] {
                    Warnings ww;
                    tables = buildTables(mesh, options, to, ww);
                    bytes = encodeTablesChunk(tables).payload.size();
                };
                auto buildOsd = [&] {
                    std::unique_ptr<Far::TopologyRefiner> r(osdRefiner(mesh, options));
                    if (uniform) {
                        r->RefineUniform(Far::TopologyRefiner::UniformOptions(depth));
                        Far::StencilTableFactory::Options so;
                        so.generateIntermediateLevels = true;
                        delete Far::StencilTableFactory::Create(*r, so);
                    } else {
                        Far::PatchTableFactory::Options po(depth);
                        po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
                        r->RefineAdaptive(po.GetRefineAdaptiveOptions());
                        delete Far::PatchTableFactory::Create(*r, po);
                    }
                };
                // Interleaved, so a burst of load on the shared machine hits both alike.
                std::vector<double> limnRuns, osdRuns;
                for (int run = 0; run < runs; ++run) {
                    limnRuns.push_back(elapsedMs(buildLimn));
                    osdRuns.push_back(elapsedMs(buildOsd));
                }
                const double limnMs = median(limnRuns), osdMs = median(osdRuns);
                std::string levels;
                for (const auto& L : tables.levels)
                    levels += std::string(levels.empty() ? "" : ",") + "{\"vertices\":" + std::to_string(L.count()) +
                              ",\"regular_patches\":" + std::to_string(L.regularPatches) +
                              ",\"irregular_faces\":" + std::to_string(L.irregularFaces) + "}";
                std::printf("{\"mesh\":\"%s\",\"depth\":%d,\"mode\":\"%s\",\"table_bytes\":%zu,"
                            "\"limn_build_ms\":%.2f,\"osd_build_ms\":%.2f,\"limn_over_osd\":%.3f,"
                            "\"patches\":%zu,\"limit_points\":%zu,\"levels\":[%s]}\n",
                            name.c_str(), depth, uniform ? "uniform" : "adaptive", bytes, limnMs, osdMs,
                            limnMs / osdMs, tables.patches.size(), tables.limitPosition.rows(), levels.c_str());
                std::fprintf(stderr, "%-28s %5d %-8s %12zu %10.1f %10.1f %7.2f %8zu\n", name.c_str(), depth,
                             uniform ? "uniform" : "adaptive", bytes, limnMs, osdMs, limnMs / osdMs,
                             tables.patches.size());
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
