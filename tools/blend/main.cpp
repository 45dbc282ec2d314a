// limn-blend: adds the BLND chunk to a classified .limn container: per vertex its chart and the 9
// coefficients of its local surface, per face its corners' ring indices (paper 001; math.md A).
// Everything a vertex shader needs to evaluate the blending surface (A.9).
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "blend/blend_chunk.h"
#include "blend/blend_surface.h"
#include "blend/quadrangulate.h"
#include "container/container.h"
#include "container/container_output.h"
#include "mesh/mesh_chunks.h"
#include "topology/classification.h"

#include <map>

using namespace limn;

namespace {

std::string valenceHistogram(const blend::BlendSurface& s) {
    std::map<std::pair<int, uint32_t>, size_t> h;
    for (const auto& v : s.vertices)
        if (v.chart.k) ++h[{static_cast<int>(v.chart.kind), v.chart.k}];
    std::string out;
    const char* names[] = {"interior", "boundary", "corner"};
    for (const auto& [key, n] : h)
        out += (out.empty() ? "" : ", ") + std::string(names[key.first]) + " k=" +
               std::to_string(key.second) + ": " + std::to_string(n);
    return out;
}

} // namespace

int main(int argc, char** argv) {
    return cli::run("limn-blend", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-", weights = "cubic", chart = "conformal";
        bool quadrangulate = false;
        cli::Parser parser(
            "limn-blend", "[options] [INPUT|-] [-o OUTPUT|-]",
            "Adds a BLND chunk to a .limn container made by limn-classify: the manifold blending\n"
            "surface of its quad mesh (Ko, after Ying-Zorin 2004): per vertex a chart z -> z^(4/k)\n"
            "and a biquadratic local surface fitted to its one-ring, per face the ring index of\n"
            "each corner. Other chunks are kept unchanged.",
            common);
        parser.positional("INPUT", &input, ".limn container (output of limn-classify)")
            .choice("--weights", &weights, {"cubic", "quintic"},
                    "Hermite step of the blending weights: cubic gives a C1\n"
                    "                            surface, quintic C2")
            .choice("--chart", &chart, {"conformal", "characteristic", "isodistance"},
                    "radial exponent of interior charts: p = q (z^(4/k)), the Catmull-Clark\n"
                    "                            characteristic map's, or 1")
            .flag("--quadrangulate", &quadrangulate,
                  "if the mesh has faces that are not quads, first split every face linearly\n"
                  "                            (face centroids + edge midpoints, n-gon -> n quads; UVs and\n"
                  "                            tags follow; MESH, FVUV, TAGS and CLSF are rewritten)")
            .notes("Input must be a consistently oriented 2-manifold mesh; a face that is not a quad\n"
                   "(without --quadrangulate), a non-manifold edge or vertex is an error naming it.\n"
                   "Boundary vertices get half-disk charts, one-face corners bilinear patches.\n"
                   "The BLND layout is in formats/limn.md; the construction in docs/blend.md.\n"
                   "Example:\n"
                   "  limn-classify spot.obj | limn-blend --quadrangulate -o spot.limn\n")
            .exitCodes("Exit codes:\n"
                       "  0  success\n"
                       "  1  bad input: not a container, damaged chunks, a non-quad face (without\n"
                       "     --quadrangulate), a non-manifold edge or vertex\n"
                       "  2  usage error\n");
        if (!parser.parse(ac, av)) return 0;
        const std::string name = displayName(input);

        ContainerOutput out(common.output, common.depfile, input);
        Warnings importWarnings;
        std::vector<std::string> inputs = {input}; // and a .gltf's buffers and images
        Container container = loadOrClassify(input, importWarnings, &inputs);
        cli::printWarnings(importWarnings, displayName(input));
        try {
            Mesh mesh = loadMesh(container);
            std::optional<Classification> clsf;
            if (const Chunk* c = container.find(kClassificationChunk))
                clsf = decodeClassificationChunk(*c, mesh);
            Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets,
                          mesh.faceVertices);
            blend::requireManifold(mesh, topo);
            if (!blend::isQuadMesh(mesh)) {
                if (!quadrangulate) {
                    try {
                        blend::requireQuads(mesh);
                    } catch (Error& e) {
                        throw Error(e.kind(), std::string(e.what()) + " (use --quadrangulate to split it first)");
                    }
                }
                size_t before = mesh.faceCount();
                mesh = blend::quadrangulateLinear(mesh, topo);
                topo = Topology(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets,
                                mesh.faceVertices);
                cli::info("quadrangulated " + std::to_string(before) + " faces into " +
                          std::to_string(mesh.faceCount()) + " quads");
                storeMesh(container, mesh);
                if (clsf) {
                    Warnings w;
                    container.set(encodeClassificationChunk(classifyMesh(mesh, topo, clsf->options, w)));
                }
                std::string stale;
                for (const Chunk& c : container.chunks)
                    if (!(c.type == kMeshChunk || c.type == kUVChunk || c.type == kTagsChunk ||
                          c.type == kClassificationChunk || c.type == blend::kBlendChunk))
                        stale += " " + c.type.str();
                if (!stale.empty())
                    cli::warn(name + ": --quadrangulate changed the mesh; chunks" + stale +
                              " were built for the old mesh and are passed through unchanged");
            }
            blend::BlendOptions options;
            options.weights = weights == "quintic" ? blend::WeightKind::Quintic : blend::WeightKind::Cubic;
            options.chart = chart == "characteristic" ? blend::ChartType::CharacteristicMap
                            : chart == "isodistance"  ? blend::ChartType::Isodistance
                                                      : blend::ChartType::Conformal;
            blend::BlendSurface surface = blend::buildBlendSurface(mesh, topo, options);
            container.set(blend::encodeBlendChunk(surface, blend::meshPayloadHash(container)));
            cli::info("blending surface: " + std::to_string(mesh.vertexCount()) + " vertices (" +
                      valenceHistogram(surface) + "), " + std::to_string(mesh.faceCount()) +
                      " quads");
        } catch (Error& e) {
            e.setFile(input);
            throw;
        }
        out.commit(container, inputs);
        return 0;
    });
}
