// limn-seams: adds the auxiliary texture coordinates that make displacement crack-free across UV
// seams (paper 000, 4.1 and 4.5) to a container with subdivision tables.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "topology/classification.h"
#include "container/container.h"
#include "container/container_output.h"
#include "mesh/mesh_chunks.h"
#include "seams/seams.h"
#include "subdiv/tables_chunk.h"

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-seams", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-";
        cli::Parser parser(
            "limn-seams", "[options] [INPUT|-] [-o OUTPUT|-]",
            "Adds the SEAM chunk to a container made by limn-tables: for every patch and irregular\n"
            "face, the UVs of its corners in every face around them and of its edges on both\n"
            "sides, so limn-render --displace samples a shared point identically from every side\n"
            "(paper 000, Figures 5, 8, 9). Refined UVs follow the linear face-varying rule.",
            common);
        parser.positional("INPUT", &input, "container made by limn-tables (the mesh needs UVs)")
            .notes("Example:\n  limn-classify spot.obj | limn-tables -d 3 | limn-seams |"
                   " limn-render --displace d.png -o spot.png\n");
        if (!parser.parse(ac, av)) return 0;

        ContainerOutput out(common.output, common.depfile, input);
        Warnings warnings;
        Container container = loadOrClassify(input, warnings);
        cli::printWarnings(warnings, displayName(input));
        try {
            Mesh mesh = loadMesh(container);
            const Chunk* tb = container.find(kTablesChunk);
            if (!tb) throwBadInput("the container has no subdivision tables (TBLS); run limn-tables first");
            Tables tables = decodeTablesChunk(*tb, &mesh);
            Seams seams = computeSeams(mesh, tables, seamsSourceHash(container));
            cli::info(std::to_string(seams.elements.size()) + " elements, " +
                      std::to_string(seams.uvs.size()) + " auxiliary UVs");
            container.set(encodeSeamsChunk(seams));
        } catch (Error& e) {
            e.setFile(displayName(input));
            throw;
        }
        out.commit(container, {input});
        return 0;
    });
}
