// limn-heightmap: generates the height maps the displacement examples and tests use: 3D noise
// baked into a mesh's UV layout (continuous across its seams), or 2D noise in UV space.
#include "bake/heightmap.h"
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "mesh/import.h"
#include "image/texture_image.h"

using namespace limn;

int main(int argc, char** argv) {
    return cli::run("limn-heightmap", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-", kind = "surface";
        int size = 1024, octaves = 4, seed = 1, padding = 4;
        double frequency = 6;
        cli::Parser parser(
            "limn-heightmap", "[options] [INPUT|-] -o MAP.png",
            "Writes a 16-bit grayscale PNG height map for limn-render --displace.\n"
            "  surface: 3D noise at the surface point each texel maps to (through the mesh's UV\n"
            "           charts), continuous across UV seams: the realistic case.\n"
            "  uv:      2D noise in UV space, unrelated across seams: the stress case for the seam\n"
            "           fix. INPUT is not read (and may be left out).",
            common);
        parser.positional("INPUT", &input, "mesh with UVs (any format limn reads, or .limn)")
            .choice("--kind", &kind, {"surface", "uv"}, "which field to bake")
            .integer("--size", "N", &size, 16, 8192, "width and height in texels")
            .real("--frequency", "F", &frequency, 0.01, 1000, "noise cycles across the bounding box (or UV square)")
            .integer("--octaves", "N", &octaves, 1, 12, "fBm octaves")
            .integer("--seed", "S", &seed, 0, 1 << 30, "noise seed")
            .integer("--padding", "P", &padding, 0, 64, "texels a surface map extends past each UV island");
        if (!parser.parse(ac, av)) return 0;
        const bool needsMesh = kind != "uv";
        std::vector<std::string> inputs =
            needsMesh ? std::vector<std::string>{input} : std::vector<std::string>{};
        refuseOverwritingInputs(common.output, inputs);
        requireOutputExtension(common.output, ".png", "PNG");
        OutputFile out(common.output, OutputFile::Kind::Binary); // refused on a terminal
        Depfile depfile(common.depfile, {common.output}, inputs);
        Mesh mesh;
        if (needsMesh) {
            Warnings warnings;
            mesh = importMeshFile(input, warnings, &inputs);
            cli::printWarnings(warnings, displayName(input));
        }
        HeightmapOptions o;
        o.kind = kind == "uv" ? HeightmapKind::Uv : HeightmapKind::Surface;
        o.size = uint32_t(size);
        o.frequency = frequency;
        o.octaves = octaves;
        o.seed = uint32_t(seed);
        o.padding = uint32_t(padding);
        std::vector<float> values;
        try {
            values = bakeHeightmap(mesh, o);
        } catch (Error& e) {
            e.setFile(displayName(input));
            throw;
        }
        out.write(encodeGray16Png(o.size, o.size, values));
        depfile.setRule(common.output, inputs);
        depfile.prepare(); // a depfile that cannot be written fails the run before the output lands
        out.commit();
        depfile.commit();
        return 0;
    });
}
