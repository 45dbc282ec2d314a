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
#include "subdiv/fvar_chunk.h"
#include "subdiv/tables_chunk.h"
#include "topology/classification.h"
#include "topology/quad_pairs.h"

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-classify", argc, argv, [](int ac, char** av) {
        cli::Common common;
        double faceAngle = 60, shapeAngle = 75;
        std::string input = "-", boundary, fvar, quads = "auto";
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
            .choice("--quads", &quads, {"auto", "off", "pairs", "ngon"},
                    "quads back from triangles (see below)")
            .real("--quad-face-angle", "DEG", &faceAngle, 0, 180,
                  "pairs: max angle between the normals")
            .real("--quad-shape-angle", "DEG", &shapeAngle, 0, 180,
                  "pairs: max corner angle off square")
            .notes("The format is chosen by the extension, or by content on standard input.\n"
                   "--fvar is OpenSubdiv's face-varying linear interpolation, stored as the mesh's\n"
                   "tag (OBJ: t facevaryinginterpolateboundary): none smooths UVs everywhere;\n"
                   "corners-only, corners-plus1, corners-plus2 keep UV corners, also junctions of\n"
                   "3+ UV regions, also darts and concave corners sharp; boundaries keeps every UV\n"
                   "boundary linear; all interpolates UVs linearly (the default, as OpenSubdiv's).\n"
                   "Chunks of an input .limn that limn-classify does not own are kept unchanged.\n"
                   "--quads: glTF carries only triangles, and Catmull-Clark of triangles is lumpy.\n"
                   "ngon rebuilds the polygons a glTF stores with FB_ngon_encoding (an error if it\n"
                   "does not); pairs joins two triangles into a quad where their shared edge looks\n"
                   "like a quad's diagonal, with the limits of Blender's Tris to Quads (normals within\n"
                   "--quad-face-angle, corners within --quad-shape-angle of square and convex; same\n"
                   "UVs on the edge, no crease on it; Blender's defaults are 40 and 40): triangles\n"
                   "written one after the other first (exporters write a quad's two so), then the\n"
                   "best-shaped pairs; deterministic; 180 turns a limit off (the shape limit's\n"
                   "convexity check with it). off keeps the triangles. auto: for glTF input ngon\n"
                   "if the file uses FB_ngon_encoding, else pairs; for other input off. Triangles\n"
                   "left unpaired are reported as a warning.\n"
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
            const MeshFormat format = importFormat(input, bytes);
            const bool gltf = format == MeshFormat::Gltf || format == MeshFormat::Glb;
            if (quads == "auto") quads = gltf ? "auto" : "off";
            GltfPolygons polygons;
            polygons.rebuildNgons = quads == "auto" || quads == "ngon";
            mesh = importMesh(input, bytes, warnings, &inputs, &material, &polygons);
            if (quads == "ngon" && !polygons.fileHasNgonEncoding) {
                Error e(ErrorKind::BadInput, "--quads ngon: the file does not use FB_ngon_encoding, so its "
                                             "triangles carry no polygons; use --quads pairs");
                e.setFile(input);
                throw e;
            }
            if (quads == "auto") quads = polygons.fileHasNgonEncoding ? "ngon" : "pairs";
        }
        const std::string name = input == "-" ? std::string("<stdin>") : input;
        if (quads == "ngon" || quads == "pairs") {
            size_t triangles = 0;
            for (size_t f = 0; f < mesh.faceCount(); ++f) triangles += mesh.faceSize(f) == 3;
            std::string made;
            if (quads == "pairs") {
                QuadJoinOptions o;
                o.maxFaceAngle = faceAngle * std::numbers::pi / 180;
                o.maxShapeAngle = shapeAngle * std::numbers::pi / 180;
                const QuadJoinReport r = joinTrianglePairs(mesh, o);
                triangles = r.trianglesLeft;
                made = std::to_string(r.quadsMade) + " quads from " + std::to_string(r.trianglesBefore) + " triangles";
            } else {
                made = "the file's polygons (FB_ngon_encoding)";
            }
            cli::info("--quads " + quads + ": " + made + ", " + std::to_string(triangles) + " triangles left");
            if (triangles)
                cli::warn(name + ": --quads " + quads + ": " + std::to_string(triangles) +
                          " triangles left without a partner (each makes extraordinary vertices); " +
                          std::to_string(mesh.faceCount()) + " faces in all");
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
                container.remove(kFvarSurfaceChunk); // made with the tables, from the same options
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
