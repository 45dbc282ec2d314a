// limn-tables: builds the feature-adaptive subdivision tables (paper 000, 4.1) of a classified
// container, from topology alone, and adds them as the TBLS chunk; with smooth face-varying UVs,
// also their own surface as the FVSF chunk.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "container/container.h"
#include "container/container_output.h"
#include "mesh/mesh_chunks.h"
#include "subdiv/fvar_chunk.h"
#include "subdiv/tables_chunk.h"
#include "topology/classification.h"

#include <algorithm>
#include <optional>

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-tables", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-";
        int depth = 3, irregularLevels = TablesOptions{}.irregularLevels;
        bool uniform = false, noCreasePatches = false;
        std::string boundaryBases = TablesOptions{}.boundaryBases ? "on" : "off";
        std::string creaseChains = TablesOptions{}.creaseChains ? "on" : "off";
        uint64_t maxMemory = cli::defaultMemoryBudget();
        cli::Parser parser(
            "limn-tables", "[options] [INPUT|-] [-o OUTPUT|-]",
            "Builds the per-level subdivision tables of a classified .limn container: face,\n"
            "edge and vertex point stencils for each level, refined only around irregular\n"
            "features (feature-adaptive isolation), the regular B-spline patches found at each\n"
            "level, the faces left irregular at the last level and the limit stencils of their\n"
            "corners. Tables depend on topology only: re-run when faces or tags change, not when\n"
            "positions move. A mesh with smooth face-varying UVs (TAGS fvar other than \"all\")\n"
            "also gets its UV surface (the FVSF chunk, for limn-web-render): re-run when UVs change.",
            common);
        parser.positional("INPUT", &input,
                          "container made by limn-classify, or a mesh (classified with the defaults)")
            .integer("-d, --depth", "N", &depth, 0, kMaxDepth, "subdivision levels")
            .flag("--uniform", &uniform,
                  "subdivide every face to level N (the paper's full-subdivision baseline)")
            .integer("--irregular-levels", "K", &irregularLevels, 0, kMaxDepth,
                     "levels refined beyond N under the faces left irregular at level N, whose "
                     "surface is then drawn from their regular sub-patches: exact at every point "
                     "at least 2^-K of the face from an extraordinary corner, which covers every "
                     "drawn vertex up to --tess 2^K (capped at depth 16 in all; 0: drawn bilinear "
                     "between their corners' limit points, as before)")
            .choice("--boundary-bases", &boundaryBases, {"on", "off"},
                    "faces around one boundary vertex (smooth or a corner) whose other corners "
                    "are regular drawn from a basis per configuration of the vertex's fan, like "
                    "those around one interior extraordinary vertex, and those whose support "
                    "reaches a boundary or crease only on its rim from their per-valence basis, "
                    "instead of K more levels (off: refined, as TBLS version 6 held them; "
                    "docs/irregular.md)")
            .choice("--crease-chains", &creaseChains, {"on", "off"},
                    "faces at a semi-sharp crease that has not decayed at level N drawn from a "
                    "chain per configuration (one-level programs band by band until the crease "
                    "has decayed) instead of K more levels; written as TBLS version 9 "
                    "(docs/irregular-tables.md)")
            .flag("--no-crease-patches", &noCreasePatches,
                  "isolate creases and sharp corners to level N like extraordinary vertices, "
                  "instead of drawing the regular faces along infinitely sharp ones as boundary "
                  "and corner patches and along straight semi-sharp ones as single-crease "
                  "patches (OpenSubdiv's useInfSharpPatch and useSingleCreasePatch off) "
                  "[default: patches]")
            .custom("--max-memory", "SIZE",
                    [&](const std::string& v) { maxMemory = cli::parseByteSize("--max-memory", v); },
                    cli::formatBytes(maxMemory) + ", half of this machine's memory",
                    "refuse tables whose building is estimated to need more (512M, 8G, ...); the "
                    "estimate comes from the counts, before each level is refined")
            .notes("Non-quad faces are split at the first level, so --depth 0 needs an all-quad\n"
                   "mesh. --depth N is the number of levels stored and drawn: patches of every\n"
                   "level up to N, the faces left irregular at level N drawn on their sub-patches\n"
                   "of levels N+1..N+K (--irregular-levels; docs/irregular.md). A semi-sharp\n"
                   "crease or corner of sharpness s that has not decayed by level N (s > N) is\n"
                   "refined further around its vertices while the tables are built, until it has\n"
                   "(level ceil(s) with uniform creasing), and\n"
                   "its limit points are composed back onto level-N vertices: what is drawn stays\n"
                   "N levels deep and the stored levels are the same, only the limit stencils are\n"
                   "exact. Darts, cone points and corners use the eigenvectors of\n"
                   "their local subdivision matrix (up to 64 faces; more are counted approximate).\n"
                   "Valence-2 vertices and corner sectors whose\n"
                   "normals converge like 1/level have no tangent plane: their limit points keep\n"
                   "the exact position and are counted approximate (limn-info reports how many).\n"
                   "Infinitely sharp creases act as boundaries: a regular face along one (each\n"
                   "crease vertex a straight crease through 4 edges, or a corner whose every edge\n"
                   "is sharp) is a B-spline patch with phantom points beyond the crease, exact\n"
                   "from the level where it appears; limn-classify's regular flags say the same.\n"
                   "Example:\n  limn-classify spot.obj | limn-tables --depth 4 -o spot.limn\n");
        if (!parser.parse(ac, av)) return 0;

        ContainerOutput out(common.output, common.depfile, input);
        const std::string name = displayName(input);
        Tables tables;
        std::optional<Chunk> fvar;
        Warnings warnings;
        std::vector<std::string> inputs = {input}; // and a .gltf's buffers and images
        Container container = loadOrClassify(input, warnings, &inputs);
        try {
            Mesh mesh = loadMesh(container);
            const Chunk* clsf = container.find(kClassificationChunk);
            if (!clsf)
                throwBadInput("the container has no classification (CLSF); run limn-classify first");
            Classification c = decodeClassificationChunk(*clsf, mesh);
            TablesOptions opts;
            opts.depth = depth;
            opts.uniform = uniform;
            opts.irregularLevels = irregularLevels;
            opts.infSharpPatches = opts.singleCreasePatches = !noCreasePatches;
            // With it, faces around one interior extraordinary vertex whose support only reaches a
            // boundary on its rim keep their basis too (the stencils of one level read features
            // at the face's corners only; docs/irregular.md).
            opts.boundaryBases = opts.basisRimFeatures = boundaryBases == "on";
            opts.creaseChains = creaseChains == "on";
            // The tables are only written, and TBLS stores the bases as programs, which readers
            // expand: their weights are not computed here (the bishop's chains took a quarter of
            // the run).
            opts.basisWeights = false;
            opts.maxMemoryBytes = maxMemory;
            tables = buildTables(mesh, c.options, opts, warnings);
            // Smooth face-varying UVs: their own surface, for runtimes that do not build it. Its
            // warnings about the mesh repeat what the geometry's tables reported; only the new
            // ones (e.g. fewer levels over the record budget) are passed on.
            if (mesh.hasUVs() && c.options.fvar != FVarRule::All) {
                Warnings uvWarnings;
                fvar = encodeFvarSurfaceChunk(
                    makeFvarSurfaceChunk(mesh, c.options, depth, tables.irregularLevels, uvWarnings));
                for (std::string& m : uvWarnings.messages)
                    if (std::find(warnings.messages.begin(), warnings.messages.end(), m) == warnings.messages.end())
                        warnings.add(std::move(m));
            }
        } catch (Error& e) {
            e.setFile(name);
            throw;
        }
        cli::printWarnings(warnings, name);
        cli::info("depth " + std::to_string(depth) + (uniform ? " uniform" : " adaptive") + ": " +
                  std::to_string(tables.totalVertices) + " vertices, " +
                  std::to_string(tables.patches.size()) + " patches, " +
                  std::to_string(tables.irregular.size()) + " irregular faces");
        if (tables.approximateLimitPoints)
            cli::warn(name + ": " + std::to_string(tables.approximateLimitPoints) +
                      " limit points have an approximate normal (valence-2 vertices or corner "
                      "sectors, where the surface has no tangent plane, or darts and cone points "
                      "of more than " + std::to_string(kMaxBasisValence) + " faces)");
        container.set(encodeTablesChunk(tables));
        if (fvar)
            container.set(std::move(*fvar));
        else
            container.remove(kFvarSurfaceChunk);
        // Seams belong to the tables they were made from: new tables make them stale.
        if (container.find(FourCC{"SEAM"})) {
            container.remove(FourCC{"SEAM"});
            cli::warn(name + ": dropped the SEAM chunk made for the old tables; run limn-seams "
                             "again (or let limn-render --displace compute the seams)");
        }
        out.commit(container, inputs);
        return 0;
    });
}
