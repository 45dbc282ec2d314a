// bench_import [OBJ] [RUNS]: times what limn-classify does with a mesh (OBJ parse, topology,
// classification) next to OpenSubdiv building its topology for the same parsed mesh
// (Far::TopologyRefinerFactory::Create), in one process, alternating which goes first. Prints
// one JSON line per stage with the median and min in milliseconds; limn_total and osd_total
// both include the run's parse.
// Default mesh: catmark_car_level3.obj (100,800 quads, creases), which the build generates from
// tests/data/osd/catmark/catmark_car.obj into <build>/data/.
#include "base/error.h"
#include "base/io.h"
#include "base/json.h"
#include "mesh/obj.h"
#include "topology/classification.h"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>

using namespace limn;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

double millis(const std::function<void()>& f) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::unique_ptr<Far::TopologyRefiner> osdCreate(const Mesh& m) {
    std::vector<int> sizes(m.faceCount()), pairs;
    std::vector<float> weights;
    for (size_t f = 0; f < m.faceCount(); ++f) sizes[f] = static_cast<int>(m.faceSize(f));
    for (const auto& c : m.tags.creases) {
        pairs.push_back(static_cast<int>(c.v0));
        pairs.push_back(static_cast<int>(c.v1));
        weights.push_back(c.sharpness);
    }
    Far::TopologyDescriptor d;
    d.numVertices = static_cast<int>(m.vertexCount());
    d.numFaces = static_cast<int>(m.faceCount());
    d.numVertsPerFace = sizes.data();
    d.vertIndicesPerFace = reinterpret_cast<const int*>(m.faceVertices.data());
    d.numCreases = static_cast<int>(weights.size());
    d.creaseVertexIndexPairs = pairs.data();
    d.creaseWeights = weights.data();
    Sdc::Options o;
    o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return std::unique_ptr<Far::TopologyRefiner>(
        Factory::Create(d, Factory::Options(Sdc::SCHEME_CATMARK, o)));
}

} // namespace

int main(int argc, char** argv) {
    std::string path =
        argc > 1 ? argv[1] : std::string(LIMN_CAR_LEVEL3);
    int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 15;
    std::vector<uint8_t> bytes;
    try {
        bytes = readInput(path);
    } catch (const Error& e) {
        std::fprintf(stderr, "bench_import: %s: %s\n", path.c_str(), e.what());
        return 1;
    }

    std::map<std::string, std::vector<double>> times;
    size_t checksum = 0; // keeps the work observable
    for (int run = 0; run < runs; ++run) {
        // Both sides start from the same OBJ parse (limn's reader), timed once per run.
        Mesh mesh;
        double parse = millis([&] {
            Warnings w;
            mesh = readObj(bytes, w);
        });
        // limn: what limn-classify does next, before serializing.
        auto limnSide = [&] {
            std::unique_ptr<Topology> topo;
            Classification c;
            double topology = millis([&] {
                topo = std::make_unique<Topology>(static_cast<uint32_t>(mesh.vertexCount()),
                                                  mesh.faceOffsets, mesh.faceVertices);
            });
            double classify = millis([&] {
                Warnings w;
                c = classifyMesh(mesh, *topo, resolveSchemeOptions(mesh.tags, {}), w);
            });
            times["limn_topology"].push_back(topology);
            times["limn_classify"].push_back(classify);
            times["limn_total"].push_back(parse + topology + classify);
            checksum += c.edges;
        };
        // OpenSubdiv: Far's base level (edges, relations, tags and sharpness).
        auto osdSide = [&] {
            std::unique_ptr<Far::TopologyRefiner> refiner;
            double create = millis([&] { refiner = osdCreate(mesh); });
            times["osd_create"].push_back(create);
            times["osd_total"].push_back(parse + create);
            checksum += static_cast<size_t>(refiner->GetLevel(0).GetNumEdges());
        };
        // Alternate which side runs first, so neither always inherits a warm or cold heap.
        if (run % 2) {
            limnSide();
            osdSide();
        } else {
            osdSide();
            limnSide();
        }
        times["parse"].push_back(parse);
    }

    for (auto& [stage, t] : times) {
        std::sort(t.begin(), t.end());
        JsonWriter j;
        j.beginObject()
            .field("bench", "import")
            .field("mesh", path.substr(path.find_last_of('/') + 1))
            .field("stage", stage)
            .field("runs", runs)
            .field("median_ms", t[t.size() / 2])
            .field("min_ms", t.front())
            .endObject();
        std::printf("%s\n", j.str().c_str());
    }
    std::fprintf(stderr, "checksum %zu\n", checksum);
    return 0;
}
