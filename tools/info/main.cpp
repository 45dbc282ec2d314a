// limn-info: summarizes a .limn container (or any mesh limn reads): counts, histograms, feature
// classification and the chunks it holds. Human-readable by default, one JSON object with --json.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "base/json.h"
#include "container/container.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "blend/blend_chunk.h"
#include "seams/seams.h"
#include "subdiv/fvar_chunk.h"
#include "subdiv/tables_chunk.h"
#include "topology/classification.h"

#include <cstdio>
#include <optional>
#include <iostream>
#include <map>

using namespace limn;

namespace {

const char* boundaryName(BoundaryRule b) {
    switch (b) {
    case BoundaryRule::None: return "none";
    case BoundaryRule::EdgeOnly: return "edge";
    case BoundaryRule::EdgeAndCorner: return "edge-corner";
    }
    return "?";
}

struct Summary {
    size_t vertices = 0, faces = 0;
    std::map<uint32_t, size_t> faceSizes, interiorValence;
    size_t extraordinary = 0, regularFaces = 0, irregularFaces = 0, holeFaces = 0;
    size_t uvs = 0;
    Classification c;
};

Summary summarize(const Mesh& mesh, const Classification& c) {
    Summary s;
    s.c = c;
    s.vertices = mesh.vertexCount();
    s.faces = mesh.faceCount();
    s.uvs = mesh.uvs.size();
    for (size_t f = 0; f < mesh.faceCount(); ++f) {
        ++s.faceSizes[mesh.faceSize(f)];
        uint32_t flags = c.faceFlags[f];
        if (flags & kFaceNoLimit)
            ++s.holeFaces;
        else if (flags & kFaceRegular)
            ++s.regularFaces;
        else
            ++s.irregularFaces;
    }
    // Faces around each interior vertex (boundary and unused vertices excluded).
    std::vector<uint32_t> facesAround(mesh.vertexCount(), 0);
    for (uint32_t v : mesh.faceVertices) ++facesAround[v];
    for (size_t v = 0; v < mesh.vertexCount(); ++v) {
        uint32_t flags = c.vertexFlags[v];
        if (flags & (kVertexBoundary | kVertexIsolated)) continue;
        ++s.interiorValence[facesAround[v]];
    }
    for (size_t v = 0; v < mesh.vertexCount(); ++v)
        if ((c.vertexFlags[v] & kVertexExtraordinary) && !(c.vertexFlags[v] & kVertexIsolated))
            ++s.extraordinary;
    return s;
}

void histogram(JsonWriter& j, const std::string& key, const std::map<uint32_t, size_t>& h) {
    j.key(key).beginObject();
    for (const auto& [k, n] : h) j.field(std::to_string(k), n);
    j.endObject();
}

std::string histogramText(const std::map<uint32_t, size_t>& h) {
    std::string s;
    for (const auto& [k, n] : h) s += (s.empty() ? "" : ", ") + std::to_string(k) + ": " + std::to_string(n);
    return s.empty() ? "-" : s;
}

} // namespace

int main(int argc, char** argv) {
    return cli::run("limn-info", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-";
        bool json = false;
        cli::Parser parser("limn-info", "[options] [INPUT|-]",
                           "Summarizes a .limn container (or a mesh file, classified on the fly).",
                           common, /*hasOutput=*/false, /*hasDepfile=*/false);
        parser.positional("INPUT", &input, ".limn container or mesh file")
            .flag("--json", &json, "print one JSON object instead of text")
            .notes("JSON fields: vertices, faces, face_size_histogram, edges, boundary_edges,\n"
                   "nonmanifold_edges, interior_valence_histogram (faces around each interior\n"
                   "vertex), extraordinary_vertices, regular_faces, irregular_faces, hole_faces\n"
                   "(holes and faces without a limit surface), uv_seam_edges, boundary_rule and\n"
                   "chunks (type, version, bytes). With subdivision tables (limn-tables): depth,\n"
                   "uniform, table_bytes, table_vertices, patches, limit_points,\n"
                   "approximate_limit_points, irregular_surface (how the faces left irregular at\n"
                   "level N are drawn: basis, sub_patches, bilinear counts, boundary_basis (of\n"
                   "basis, those around a boundary vertex, from a basis per configuration),\n"
                   "crease_chain (of basis, those from a decaying-crease chain, TBLS version 8 on),\n"
                   "basis_below (smooth faces below level N inside the sub-patch faces), and\n"
                   "exact_levels K: every point at least 2^-K of a face from its extraordinary\n"
                   "corners is on the limit surface; docs/irregular.md) and levels (per level\n"
                   "0..N+K: vertices computed at\n"
                   "that level, regular_patches at it, irregular_faces: faces refined further, or\n"
                   "at the last level drawn at their limit corners).\n");
        if (!parser.parse(ac, av)) return 0;

        auto bytes = readInput(input);
        Warnings warnings;
        Container container;
        Mesh mesh;
        Classification c;
        try {
            if (looksLikeContainer(bytes)) {
                container = parseContainer(bytes);
                mesh = loadMesh(container);
            } else {
                mesh = importMesh(input, bytes, warnings);
            }
            if (const Chunk* clsf = container.find(kClassificationChunk)) {
                c = decodeClassificationChunk(*clsf, mesh);
            } else {
                Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets,
                              mesh.faceVertices);
                c = classifyMesh(mesh, topo, resolveSchemeOptions(mesh.tags, {}), warnings);
            }
        } catch (Error& e) {
            e.setFile(input);
            throw;
        }
        std::optional<Tables> tables;
        size_t tableBytes = 0;
        if (const Chunk* tb = container.find(kTablesChunk)) {
            try {
                tables = decodeTablesChunk(*tb, &mesh);
            } catch (Error& e) {
                e.setFile(input);
                throw;
            }
            tableBytes = tb->payload.size();
        }
        // Every chunk summarised is validated as limn-render reads it, and a SEAM made from
        // other tables or UVs is reported stale (limn-render would refuse it).
        bool seamsStale = false, fvarStale = false;
        try {
            if (const Chunk* sm = container.find(kSeamsChunk)) {
                const uint32_t elements =
                    tables ? static_cast<uint32_t>(tables->patches.size() + tables->irregular.size())
                           : kNone;
                const Seams seams = decodeSeamsChunk(*sm, elements, 0);
                seamsStale = !tables || seams.sourceHash != seamsSourceHash(container);
            }
            if (const Chunk* fv = container.find(kFvarSurfaceChunk)) {
                // Its structure is checked; made from other tables, options or UVs, it is stale.
                const FvarSurfaceChunk f = decodeFvarSurfaceChunk(*fv, nullptr, nullptr);
                fvarStale = !tables || !mesh.hasUVs() || f.depth != tables->depth ||
                            f.ptexCount != ptexFaceCount(mesh) ||
                            f.topologyHash != topologyHash(mesh, tables->options) || f.uvHash != fvarUVHash(mesh);
                if (!fvarStale) checkFvarSurfaceCoverage(f, *tables);
            }
            if (container.find(blend::kBlendChunk)) (void)blend::loadBlendSurface(container, mesh);
        } catch (Error& e) {
            e.setFile(input);
            throw;
        }
        if (seamsStale)
            cli::warn(displayName(input) +
                      ": the SEAM chunk was made from other tables or UVs (stale); re-run limn-seams");
        if (fvarStale)
            cli::warn(displayName(input) +
                      ": the FVSF chunk was made from other tables, tags or UVs (stale); re-run limn-tables");
        cli::printWarnings(warnings, displayName(input));
        Summary s = summarize(mesh, c);
        // The bounding box, in the mesh's units: --displace-scale is in the same units.
        const MeshBox box = boundingBox(mesh);
        const glm::dvec3 lo = box.lo, hi = box.hi;
        const double diagonal = box.diagonal();

        if (json) {
            JsonWriter j;
            j.beginObject();
            j.field("vertices", s.vertices).field("faces", s.faces);
            histogram(j, "face_size_histogram", s.faceSizes);
            j.field("edges", c.edges)
                .field("boundary_edges", c.boundaryEdges)
                .field("nonmanifold_edges", c.nonManifoldEdges);
            histogram(j, "interior_valence_histogram", s.interiorValence);
            j.field("extraordinary_vertices", s.extraordinary)
                .field("regular_faces", s.regularFaces)
                .field("irregular_faces", s.irregularFaces)
                .field("hole_faces", s.holeFaces)
                .field("uvs", s.uvs)
                .field("uv_seam_edges", c.uvSeamEdges)
                .field("boundary_rule", boundaryName(c.options.boundary));
            j.key("bounds").beginObject();
            j.key("min").beginArray().value(lo.x).value(lo.y).value(lo.z).endArray();
            j.key("max").beginArray().value(hi.x).value(hi.y).value(hi.z).endArray();
            j.field("diagonal", diagonal).endObject();
            if (tables) {
                j.field("depth", tables->depth)
                    .field("uniform", tables->uniform)
                    .field("table_bytes", tableBytes)
                    .field("table_vertices", tables->totalVertices)
                    .field("patches", tables->patches.size())
                    .field("limit_points", tables->limitPosition.rows())
                    .field("approximate_limit_points", tables->approximateLimitPoints);
                const IrregularSurfaceCounts irr = irregularSurfaceCounts(*tables);
                j.key("irregular_surface").beginObject();
                j.field("basis", irr.basis).field("sub_patches", irr.subPatches).field("bilinear", irr.bilinear)
                    .field("boundary_basis", irr.boundaryBasis).field("crease_chain", irr.creaseChain)
                    .field("basis_below", irr.basisBelow)
                    .field("exact_levels", irr.exactLevels);
                j.endObject();
                j.key("levels").beginArray();
                for (const auto& L : tables->levels) {
                    j.beginObject();
                    j.field("vertices", L.count())
                        .field("regular_patches", L.regularPatches)
                        .field("irregular_faces", L.irregularFaces);
                    j.endObject();
                }
                j.endArray();
            }
            j.key("chunks").beginArray();
            for (const auto& ch : container.chunks) {
                j.beginObject();
                j.field("type", ch.type.str()).field("version", ch.version).field("bytes", ch.payload.size());
                if (ch.type == kSeamsChunk) j.field("stale", seamsStale);
                if (ch.type == kFvarSurfaceChunk) j.field("stale", fvarStale);
                j.endObject();
            }
            j.endArray();
            j.endObject();
            std::cout << j.str() << "\n";
        } else {
            std::printf("%s\n", displayName(input).c_str());
            std::printf("  vertices               %zu\n", s.vertices);
            std::printf("  faces                  %zu (sizes %s)\n", s.faces, histogramText(s.faceSizes).c_str());
            std::printf("  edges                  %u (%u boundary, %u non-manifold, %u UV seam)\n",
                        c.edges, c.boundaryEdges, c.nonManifoldEdges, c.uvSeamEdges);
            std::printf("  interior valences      %s\n", histogramText(s.interiorValence).c_str());
            std::printf("  extraordinary vertices %zu\n", s.extraordinary);
            std::printf("  regular faces          %zu\n", s.regularFaces);
            std::printf("  irregular faces        %zu\n", s.irregularFaces);
            std::printf("  holes / no limit       %zu\n", s.holeFaces);
            std::printf("  UVs                    %zu\n", s.uvs);
            std::printf("  boundary rule          %s\n", boundaryName(c.options.boundary));
            std::printf("  bounds                 %.6g %.6g %.6g .. %.6g %.6g %.6g (diagonal %.6g)\n",
                        lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, diagonal);
            if (tables) {
                std::printf("  tables                 depth %u %s, %zu bytes, %u vertices, %zu patches, "
                            "%zu limit points (%u approximate)\n",
                            tables->depth, tables->uniform ? "uniform" : "adaptive", tableBytes,
                            tables->totalVertices, tables->patches.size(),
                            tables->limitPosition.rows(), tables->approximateLimitPoints);
                const IrregularSurfaceCounts irr = irregularSurfaceCounts(*tables);
                const std::string chains =
                    irr.creaseChain ? ", " + std::to_string(irr.creaseChain) + " from a decaying-crease chain" : "";
                // The bilinear faces are exact at their corners only; the others everywhere but within
                // 2^-K of an extraordinary corner (none without the extra levels, --irregular-levels 0).
                const std::string exact =
                    irr.exactLevels && irr.basis + irr.subPatches
                        ? "; the others exact beyond 2^-" + std::to_string(irr.exactLevels) + " of their extraordinary corners"
                        : "";
                std::printf("  irregular surface      %zu from a basis (%zu around a boundary vertex%s), %zu on "
                            "sub-patches (%zu smooth faces below level N from a basis), %zu bilinear between their "
                            "corners' limit points%s\n",
                            irr.basis, irr.boundaryBasis, chains.c_str(), irr.subPatches, irr.basisBelow, irr.bilinear,
                            exact.c_str());
                // Levels below N hold only the irregular faces' sub-patch quadtrees: where every such
                // face takes its surface from a basis they are empty, said once, not K times.
                size_t shown = tables->levels.size();
                while (shown > size_t(tables->depth) + 1 && tables->levels[shown - 1].count() == 0) --shown;
                for (size_t l = 0; l < shown; ++l)
                    std::printf("    level %zu: %u vertices, %u regular patches, %u irregular faces\n", l,
                                tables->levels[l].count(), tables->levels[l].regularPatches,
                                tables->levels[l].irregularFaces);
                if (shown < tables->levels.size())
                    std::printf("    level%s %zu%s: no vertices (no irregular face is refined this deep)\n",
                                shown + 1 < tables->levels.size() ? "s" : "", shown,
                                shown + 1 < tables->levels.size()
                                    ? ("-" + std::to_string(tables->levels.size() - 1)).c_str()
                                    : "");
            }
            if (!container.chunks.empty()) {
                std::printf("  chunks                ");
                for (const auto& ch : container.chunks)
                    std::printf(" %s v%u (%zu bytes)", ch.type.str().c_str(), ch.version, ch.payload.size());
                std::printf("\n");
            }
        }
        return 0;
    });
}
