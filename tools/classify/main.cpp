// limn-classify: reads a mesh (OBJ, glTF/GLB, PLY, OFF or .limn) and writes a .limn container with
// the mesh, its UVs and tags, and the classification of extraordinary regions (paper 000, 4.1).
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "container/container.h"
#include "container/container_output.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "seams/seams.h"
#include "subdiv/tables_chunk.h"
#include "topology/classification.h"

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-classify", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-", boundary, fvar;
        cli::Parser parser(
            "limn-classify", "[options] [INPUT|-] [-o OUTPUT|-]",
            "Reads a polygon mesh and writes a .limn container holding the mesh, its UVs and\n"
            "OpenSubdiv tags, and its classification: valence, boundary/crease/corner flags,\n"
            "extraordinary vertices and regular (B-spline) faces.",
            common);
        parser.positional("INPUT", &input, "mesh: .obj, .gltf, .glb, .ply, .off or .limn")
            .choice("--boundary", &boundary, {"none", "edge", "edge-corner"},
                    "boundary rule [default: the mesh's interpolateboundary tag, else edge]")
            .choice("--fvar", &fvar,
                    {"none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"},
                    "UV smoothing rule [default: the mesh's fvar tag, else all]")
            .notes("The format is chosen by the extension, or by content on standard input.\n"
                   "--fvar is OpenSubdiv's face-varying linear interpolation, stored as the mesh's\n"
                   "tag (OBJ: t facevaryinginterpolateboundary): none smooths UVs everywhere;\n"
                   "corners-only, corners-plus1, corners-plus2 keep UV corners, also junctions of\n"
                   "3+ UV regions, also darts and concave corners sharp; boundaries keeps every UV\n"
                   "boundary linear; all interpolates UVs linearly (the default, as OpenSubdiv's).\n"
                   "Chunks of an input .limn that limn-classify does not own are kept unchanged.\n"
                   "A glTF's base colour (factor and texture image bytes) is kept in a MATL chunk\n"
                   "(formats/limn.md), which limn-render draws.\n"
                   "Example:\n  limn-classify frog.obj | limn-tables --depth 4 | limn-render -o frog.png\n");
        if (!parser.parse(ac, av)) return 0;

        ContainerOutput out(common.output, common.depfile, input);
        auto bytes = readInput(input);
        Warnings warnings;
        Container container;
        Mesh mesh;
        std::optional<MeshMaterial> material;
        std::vector<std::string> inputs = {input}; // and a .gltf's buffers and images
        if (looksLikeContainer(bytes)) {
            try {
                container = parseContainer(bytes);
                mesh = loadMesh(container);
            } catch (Error& e) {
                e.setFile(input);
                throw;
            }
        } else {
            // A glTF's base colour (factor, texture bytes) travels in MATL, so that a pipeline
            // from the container draws what the asset shows.
            mesh = importMesh(input, bytes, warnings, &inputs, &material);
        }
        if (!fvar.empty()) {
            static const char* const names[] = {"none", "corners-only", "corners-plus1",
                                                "corners-plus2", "boundaries", "all"};
            for (int i = 0; i < 6; ++i)
                if (fvar == names[i]) mesh.tags.fvar = static_cast<FVarRule>(i); // as Sdc numbers them
        }
        std::optional<BoundaryRule> override;
        if (boundary == "none") override = BoundaryRule::None;
        if (boundary == "edge") override = BoundaryRule::EdgeOnly;
        if (boundary == "edge-corner") override = BoundaryRule::EdgeAndCorner;
        SchemeOptions options = resolveSchemeOptions(mesh.tags, override);
        Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
        Classification c = classifyMesh(mesh, topo, options, warnings);
        cli::printWarnings(warnings, displayName(input));
        if (c.nonManifoldEdges)
            cli::warn(displayName(input) + ": " +
                      std::to_string(c.nonManifoldEdges) +
                      " non-manifold edges; later stages refuse non-manifold meshes");
        cli::info("classified " + std::to_string(mesh.vertexCount()) + " vertices, " +
                  std::to_string(mesh.faceCount()) + " faces");

        // The tables follow the topology, tags and scheme options, the seams the tables: a
        // container classified again with another --boundary or --fvar (or other tags) would
        // otherwise keep tables that draw the old surface, without a word. Tables that cannot be
        // decoded are kept as they are, for the tools that read them to refuse.
        if (const Chunk* tb = container.find(kTablesChunk)) {
            bool stale = false;
            try {
                const Tables old = decodeTablesChunk(*tb, nullptr);
                stale = !(old.options == options) || old.topologyHash != topologyHash(mesh, options);
            } catch (const Error&) {
            }
            if (stale) {
                const bool hadSeams = container.has(kSeamsChunk);
                container.remove(kTablesChunk);
                container.remove(kSeamsChunk);
                cli::warn(displayName(input) + ": its tables" +
                          (hadSeams ? " and seams were" : " were") +
                          " made for other scheme options or tags; dropped: run limn-tables" +
                          (hadSeams ? " and limn-seams" : "") + " again");
            }
        }
        storeMesh(container, mesh);
        if (material) container.set(encodeMaterialChunk(*material));
        container.set(encodeClassificationChunk(c));
        out.commit(container, inputs);
        return 0;
    });
}
