// limn-trim: writes a trim atlas for limn-render --trim (paper 001, 4.3; math.md A.8): one square
// tile per face of the container's mesh, white where the blending surface is kept, black where it
// is cut. The layout is lib/render/trim.h's; the pattern is a round hole per face and whole faces
// removed, enough to show trimming and to test it.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "container/container.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "image/srgb_image.h"
#include "blend/trim.h"

#include <sstream>

using namespace limn;

namespace {

std::vector<uint32_t> faceList(const std::string& value) {
    std::vector<uint32_t> out;
    std::istringstream in(value);
    for (std::string item; std::getline(in, item, ',');) {
        size_t used = 0;
        unsigned long f = 0;
        try {
            f = std::stoul(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || item[0] == '-' || f > 0xFFFFFFFEul)
            throw Error(ErrorKind::Usage, "--remove: '" + item + "' is not a face index");
        out.push_back(static_cast<uint32_t>(f));
    }
    return out;
}

} // namespace

int main(int argc, char** argv) {
    return cli::run("limn-trim", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-", removed;
        int tile = 32, every = 1;
        double hole = 0.3;
        cli::Parser parser(
            "limn-trim", "[options] [INPUT|-] [-o OUTPUT.png|-]",
            "Writes a trim atlas for limn-render --trim: one square tile of R x R texels per face "
            "of\n"
            "the container's mesh, in face order, ceil(sqrt(F)) tiles to a row; inside a tile u "
            "runs\n"
            "right and v up. White (255) keeps the surface, black (0) cuts it. One grey channel.",
            common);
        parser
            .positional("INPUT", &input, ".limn container (the faces of its MESH), or a mesh file")
            .integer("--tile", "R", &tile, 1, 4096, "texels per tile side")
            .real("--hole", "RADIUS", &hole, 0, 1,
                  "radius of a round hole at each face's centre, in face parameters (0: none)")
            .integer("--every", "N", &every, 1, 1 << 30, "holes only in faces f with f mod N = 0")
            .text("--remove", "F,F,...", &removed, "faces cut away whole")
            .notes("Faces past the mesh's last face in the atlas are black. The layout is in\n"
                   "docs/blend.md (Trimming). Example:\n"
                   "  limn-trim blub.limn --hole 0.35 -o holes.png\n"
                   "  limn-render blub.limn --trim holes.png -o blub.png\n")
            .exitCodes("Exit codes:\n"
                       "  0  success\n"
                       "  1  bad input\n"
                       "  2  usage error (including binary output to a terminal)\n");
        if (!parser.parse(ac, av)) return 0;
        blend::TrimPattern pattern;
        pattern.tile = static_cast<uint32_t>(tile);
        pattern.holeRadius = hole;
        pattern.every = static_cast<uint32_t>(every);
        if (!removed.empty()) pattern.removed = faceList(removed);

        refuseOverwritingInputs(common.output, {input});
        requireOutputExtension(common.output, ".png", "PNG");
        OutputFile out(common.output, OutputFile::Kind::Binary);
        Depfile depfile(common.depfile, {common.output}, {input});
        auto bytes = readInput(input);
        size_t faces = 0;
        std::vector<std::string> inputs = {input}; // and a .gltf's buffers and images
        try {
            Warnings warnings;
            Mesh mesh = loadOrImportMesh(input, bytes, warnings, &inputs);
            cli::printWarnings(warnings, displayName(input));
            faces = mesh.faceCount();
            for (uint32_t f : pattern.removed)
                if (f >= faces)
                    throwBadInput("--remove: face " + std::to_string(f) +
                                  " does not exist (the mesh has " + std::to_string(faces) +
                                  " faces)");
        } catch (Error& e) {
            e.setFile(displayName(input));
            throw;
        }
        blend::TrimLayout l = blend::trimAtlasLayout(static_cast<uint32_t>(faces), pattern.tile);
        if (uint64_t(l.width()) * l.height() > (uint64_t(1) << 28))
            throw Error(ErrorKind::Usage,
                        "--tile " + std::to_string(tile) + " makes the atlas too large");
        cli::info(std::to_string(faces) + " faces: " + std::to_string(l.tilesX) + "x" +
                  std::to_string(l.tilesY) + " tiles of " + std::to_string(tile) + "x" +
                  std::to_string(tile));
        Image atlas = blend::makeTrimAtlas(static_cast<uint32_t>(faces), pattern);
        out.write(encodePng(atlas));
        depfile.setRule(common.output, inputs);
        depfile.prepare(); // a depfile that cannot be written fails the run before the output lands
        out.commit();
        depfile.commit();
        return 0;
    });
}
