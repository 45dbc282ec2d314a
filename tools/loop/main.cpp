// limn-loop: adaptive Loop subdivision driven by the distance of new vertices to their limit
// positions (paper 004, Jeong & Kim; math.md B). Reads a triangle mesh, writes OBJ, PLY or OFF.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "base/json.h"
#include "loop/adaptive.h"
#include "loop/measure.h"
#include "mesh/import.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

using namespace limn;

namespace {

constexpr double kLoopBytesPerTriangle = 128; // peak memory per triangle of all levels


double parseEpsilon(const std::string& text) {
    double value = 0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value))
        throw Error(ErrorKind::Usage, "--epsilon: '" + text + "' is not a number (see --help)");
    if (value < 0 || value > 1e300)
        throw Error(ErrorKind::Usage, "--epsilon: " + text + " is out of range 0 to 1e300 (see --help)");
    return value;
}

void writeStats(const loop::TriMesh& input, const loop::AdaptiveResult& result,
                const loop::Measurement* m) {
    JsonWriter j;
    j.beginObject();
    j.key("input").beginObject();
    j.field("vertices", input.vertexCount()).field("faces", input.triangleCount());
    j.endObject();
    j.key("levels").beginArray();
    for (const auto& l : result.levels) {
        j.beginObject();
        j.field("level", l.level).field("edges", l.edges).field("split", l.splitEdges);
        j.field("vertices", l.vertices).field("faces", l.faces);
        j.endObject();
    }
    j.endArray();
    j.key("output").beginObject();
    j.field("vertices", result.mesh.vertexCount()).field("faces", result.mesh.triangleCount());
    j.endObject();
    if (m) {
        auto side = [&](const char* name, const loop::OneSided& s) {
            j.key(name).beginObject();
            j.field("max", s.max).field("rms", s.rms).field("samples", s.samples);
            j.endObject();
        };
        j.key("measure").beginObject();
        j.field("reference_level", m->referenceLevel).field("reference_faces", m->referenceFaces);
        j.field("diagonal", m->diagonal).field("max", m->max).field("rms", m->rms);
        side("to_limit", m->toLimit);
        side("from_limit", m->fromLimit);
        j.endObject();
    }
    j.endObject();
    std::fprintf(stderr, "%s\n", j.str().c_str());
}

} // namespace

int main(int argc, char** argv) {
    return cli::run("limn-loop", argc, argv, [](int ac, char** av) {
        cli::Common common;
        std::string input = "-", normalize = "bbox", metric = "full", even = "split", positions = "exact",
                    boundary;
        std::optional<double> epsilon;
        loop::AdaptiveOptions options;
        bool triangulate = false, stats = false, measure = false;
        int measureLevel = 0, measureSamples = 200000;
        uint64_t maxMemory = cli::defaultMemoryBudget();
        cli::Parser parser(
            "limn-loop", "[options] [INPUT|-] [-o OUTPUT|-]",
            "Adaptive Loop subdivision (Jeong & Kim): at each level every edge whose new vertex\n"
            "lies at a normalized distance d >= E from its limit position is split; triangles are\n"
            "retriangulated by their number of split edges, so the mesh stays conforming.",
            common);
        parser.positional("INPUT", &input, "triangle mesh: .obj, .gltf, .glb, .ply, .off or .limn")
            .custom("--max-memory", "SIZE",
                    [&](const std::string& v) { maxMemory = cli::parseByteSize("--max-memory", v); },
                    cli::formatBytes(maxMemory) + ", half of this machine's memory",
                    "refuse runs estimated to need more (512M, 8G, ...), from the triangle count before "
                    "any refinement: the uniform levels bound adaptive ones too")
            .integer("--levels", "L", &options.levels, 0, 8, "subdivision levels")
            .custom("--epsilon", "E", [&](const std::string& v) { epsilon = parseEpsilon(v); },
                    "2e-05 with bbox, 0.0025 with edge",
                    "split an edge when its normalized distance d >= E (0 to 1e300; 0 splits every edge)")
            .choice("--normalize", &normalize, {"bbox", "edge"},
                    "d divided by the control mesh's bounding-box diagonal, or by the edge's length")
            .choice("--metric", &metric, {"full", "normal", "chord"},
                    "d = |o - L(o)| (paper); its normal part; or |(a+b)/2 - L(o)| (gap left unsplit)")
            .choice("--positions", &positions, {"exact", "paper"},
                    "vertices on the input's uniform Loop hierarchy, or Loop's rules re-applied (paper)")
            .choice("--even", &even, {"split", "all"},
                    "vertices move to their even position only at a split edge, or all vertices")
            .flag("--uniform", &options.uniform, "split every edge: plain Loop subdivision")
            .flag("--triangulate", &triangulate, "split polygons into triangle fans instead of refusing them")
            .choice("--boundary", &boundary, {"none", "edge", "edge-corner"},
                    "boundary rule [default: the mesh's interpolateboundary tag, else edge]")
            .flag("--stats", &stats, "print per-level counts as one JSON line on stderr")
            .flag("--measure", &measure,
                  "with --stats: distance of the result to the input's limit surface")
            .integer("--measure-level", "R", &measureLevel, 0, 8,
                     "reference level for --measure; 0 picks levels+2, fewer above 5M triangles")
            .integer("--measure-samples", "N", &measureSamples, 1000, 100000000,
                     "samples per direction for --measure")
            .exitCodes("Exit codes:\n"
                       "  0  success\n"
                       "  1  bad input (polygon without --triangulate, non-manifold edge or vertex,\n"
                       "     semi-sharp crease or corner, hole tag, unreadable file) or failed output\n"
                       "  2  usage error\n")
            .notes("Output format by the extension of -o: .obj (with UVs and tags), .ply, .off;\n"
                   "standard output gets OBJ. UVs are interpolated linearly. Infinitely sharp creases\n"
                   "and corners (sharpness >= 10) and the boundary rules are supported; semi-sharp\n"
                   "ones, holes and non-manifold meshes are refused. A level that splits no edge ends\n"
                   "the refinement. --stats prints {input, levels: [{level, edges, split, vertices,\n"
                   "faces}], output[, measure]}; --measure adds the distance to the input's limit\n"
                   "surface relative to its bounding-box diagonal (max and RMS, both directions).\n"
                   "Examples:\n"
                   "  limn-loop --levels 2 cat.obj -o cat2.obj\n"
                   "  limn-loop --uniform --levels 3 --stats --measure spot.obj -o spot3.ply\n");
        if (!parser.parse(ac, av)) return 0;
        if (measure && !stats) throw Error(ErrorKind::Usage, "--measure needs --stats (see --help)");
        options.normalization = normalize == "edge" ? loop::Normalization::EdgeLength
                                                    : loop::Normalization::BoundingBox;
        options.epsilon = epsilon.value_or(normalize == "edge" ? 0.0025 : 2e-5);
        options.metric = metric == "normal"  ? loop::Metric::Normal
                         : metric == "chord" ? loop::Metric::Chord
                                             : loop::Metric::Full;
        options.positions = positions == "paper" ? loop::Positions::Paper : loop::Positions::Exact;
        options.evenUpdate = even == "all" ? loop::EvenUpdate::All : loop::EvenUpdate::Split;
        loop::ImportOptions importOptions;
        importOptions.triangulate = triangulate;
        if (boundary == "none") importOptions.boundary = BoundaryRule::None;
        if (boundary == "edge") importOptions.boundary = BoundaryRule::EdgeOnly;
        if (boundary == "edge-corner") importOptions.boundary = BoundaryRule::EdgeAndCorner;

        checkExportPath(common.output);
        refuseOverwritingInputs(common.output, {input});
        OutputFile out(common.output, OutputFile::Kind::Text);
        Depfile depfile(common.depfile, {common.output}, {input});
        const std::string inputName = displayName(input);
        Warnings warnings;
        std::vector<std::string> inputs = {input}; // and a .gltf's buffers and images
        Mesh mesh = importMeshFile(input, warnings, &inputs);
        loop::TriMesh control;
        try {
            control = loop::fromMesh(mesh, importOptions, warnings);
        } catch (Error& e) {
            e.setFile(inputName);
            throw;
        }
        cli::printWarnings(warnings, inputName);
        // Every level keeps the one before (the hierarchy), and uniform refinement quadruples the
        // triangles: all levels together hold F (4^(L+1) - 1) / 3. Measured peak: about 110 bytes
        // per triangle of the last level (a 1,280-triangle sphere, 5 uniform levels).
        {
            const double F = double(control.triangleCount());
            const double triangles = F * (std::pow(4.0, options.levels + 1) - 1) / 3;
            const double need = triangles * kLoopBytesPerTriangle;
            if (need > double(maxMemory))
                throw Error(ErrorKind::BadInput,
                            std::to_string(options.levels) + " levels need about " +
                                cli::formatBytes(uint64_t(std::min(need, 1e18))) +
                                " of memory (" + std::to_string(uint64_t(std::min(triangles, 1e18))) +
                                " triangles at most), more than --max-memory " +
                                cli::formatBytes(maxMemory) +
                                "; use fewer --levels or raise --max-memory",
                            "")
                    .setFile(inputName);
        }

        loop::AdaptiveResult result = loop::subdivide(control, options);
        for (const auto& l : result.levels)
            cli::info("level " + std::to_string(l.level) + ": split " +
                      std::to_string(l.splitEdges) + " of " + std::to_string(l.edges) +
                      " edges; " + std::to_string(l.vertices) + " vertices, " +
                      std::to_string(l.faces) + " faces");
        loop::Measurement measurement;
        if (measure) {
            loop::MeasureOptions mo;
            mo.referenceLevel = measureLevel > 0 ? measureLevel
                                                 : loop::defaultReferenceLevel(control, options.levels);
            mo.maxSamples = static_cast<uint64_t>(measureSamples);
            measurement = loop::LimitReference(control, mo).measure(result.mesh);
        }

        out.write(exportMesh(loop::toMesh(result.mesh, mesh.tags), common.output));
        depfile.setRule(common.output, inputs);
        depfile.prepare(); // a depfile that cannot be written fails the run before the output lands
        out.commit();
        depfile.commit();
        if (stats) writeStats(control, result, measure ? &measurement : nullptr);
        return 0;
    });
}
