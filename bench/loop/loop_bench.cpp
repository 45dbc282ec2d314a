// Reproduces the paper's comparison (paper 004, section 4: uniform level 2 against adaptive with a
// bound) on the shared triangle meshes, as error-versus-vertex-count curves (math.md B.8):
// uniform levels 0-3 and epsilon sweeps of each metric variant, with the distance to the limit
// surface of the control mesh; then the vertex saving at equal error against uniform level 2, and
// the time per level next to OpenMesh's Uniform::LoopT.
// Output: JSON lines on stdout, a readable table on stderr.
//   loop_bench [--models DIR] [--mesh NAME]... [--quick]   (--quick: one mesh, one variant)
#include "base/json.h"
#include "loop/adaptive.h"
#include "loop/measure.h"
#include "loop/rules.h"
#include "mesh/import.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace limn;
using namespace limn::loop;

namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Point {
    double epsilon = 0;
    uint32_t vertices = 0;
    double max = 0, rms = 0;
};

struct Variant {
    const char* name;
    Positions positions;
    Normalization normalization;
    Metric metric;
    EvenUpdate even;
    std::vector<double> epsilons;
};

void emit(const JsonWriter& j) { std::printf("%s\n", j.str().c_str()); }

// log(err) interpolated linearly in log(V) along a curve sorted by V; extrapolated at the ends.
double interpolateError(const std::vector<Point>& curve, double v, bool useMax) {
    auto err = [&](const Point& p) { return std::log(useMax ? p.max : p.rms); };
    size_t i = 1;
    while (i + 1 < curve.size() && curve[i].vertices < v) ++i;
    double x0 = std::log(curve[i - 1].vertices), x1 = std::log(curve[i].vertices);
    double t = (std::log(v) - x0) / (x1 - x0);
    return std::exp(err(curve[i - 1]) + t * (err(curve[i]) - err(curve[i - 1])));
}

// The smallest vertex count at which the curve (sorted by V) first reaches `target`, interpolated
// log-log between the two runs around the crossing; 0 if it never does.
double verticesAtError(const std::vector<Point>& curve, double target, bool useMax) {
    auto err = [&](const Point& p) { return useMax ? p.max : p.rms; };
    for (size_t i = 0; i < curve.size(); ++i) {
        if (err(curve[i]) > target) continue;
        if (i == 0) return curve[0].vertices;
        double y0 = std::log(err(curve[i - 1])), y1 = std::log(err(curve[i]));
        double t = (std::log(target) - y0) / (y1 - y0);
        return std::exp(std::log(curve[i - 1].vertices) +
                        t * (std::log(curve[i].vertices) - std::log(curve[i - 1].vertices)));
    }
    return 0;
}

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

OMesh toOpenMesh(const TriMesh& m) {
    OMesh om;
    std::vector<OMesh::VertexHandle> vh;
    for (const auto& p : m.positions) vh.push_back(om.add_vertex(OMesh::Point(p.x, p.y, p.z)));
    for (const Tri& t : m.triangles) om.add_face(vh[t[0]], vh[t[1]], vh[t[2]]);
    return om;
}

// Seconds for each level step, the best of `repeats` runs (the machine is shared): OpenMesh's
// uniform LoopT, limn's uniform Loop, and limn's adaptive Loop at its defaults in both position
// modes (for those, the time of a run to level l minus the run to level l-1, since the exact mode
// is not a sequence of independent steps).
void timeLevels(const std::string& name, const TriMesh& control, int repeats) {
    std::fprintf(stderr, "\nTime per level on %s (%u vertices, %u triangles), seconds, best of %d:\n",
                 name.c_str(), control.vertexCount(), control.triangleCount(), repeats);
    std::fprintf(stderr, "  level  OpenMesh LoopT  limn uniform  limn adaptive exact (V)  limn adaptive paper (V)\n");
    auto best = [&](auto&& work) {
        double t = 1e300;
        for (int r = 0; r < repeats; ++r) {
            auto t0 = std::chrono::steady_clock::now();
            work();
            t = std::min(t, seconds(t0));
        }
        return t;
    };
    double exactBefore = 0, paperBefore = 0;
    for (int l = 1; l <= 3; ++l) {
        OMesh om = toOpenMesh(control);
        AdaptiveOptions uo;
        uo.uniform = true;
        uo.levels = l - 1;
        TriMesh before = subdivide(control, uo).mesh;
        for (int k = 1; k < l; ++k) {
            OpenMesh::Subdivider::Uniform::LoopT<OMesh> loop;
            loop.attach(om);
            loop(1);
            loop.detach();
        }
        size_t omVertices = 0;
        double tOm = best([&] {
            OMesh copy = om;
            OpenMesh::Subdivider::Uniform::LoopT<OMesh> loop;
            loop.attach(copy);
            loop(1);
            loop.detach();
            omVertices = copy.n_vertices();
        });
        uo.levels = 1;
        uint32_t uniformVertices = 0;
        double tUni = best([&] { uniformVertices = subdivide(before, uo).mesh.vertexCount(); });
        AdaptiveOptions exact, paper;
        exact.levels = paper.levels = l;
        paper.positions = Positions::Paper;
        uint32_t ve = 0, vp = 0;
        double tExact = best([&] { ve = subdivide(control, exact).mesh.vertexCount(); });
        double tPaper = best([&] { vp = subdivide(control, paper).mesh.vertexCount(); });
        JsonWriter j;
        j.beginObject().field("bench", "loop_time").field("mesh", name).field("level", l);
        j.field("openmesh_s", tOm).field("openmesh_vertices", static_cast<uint64_t>(omVertices));
        j.field("limn_uniform_s", tUni).field("limn_uniform_vertices", uniformVertices);
        j.field("limn_exact_s", tExact - exactBefore).field("limn_exact_total_s", tExact);
        j.field("limn_exact_vertices", ve);
        j.field("limn_paper_s", tPaper - paperBefore).field("limn_paper_total_s", tPaper);
        j.field("limn_paper_vertices", vp).endObject();
        emit(j);
        std::fprintf(stderr, "  %5d  %14.3f  %12.3f  %14.3f (%7u)  %14.3f (%7u)\n", l, tOm, tUni,
                     tExact - exactBefore, ve, tPaper - paperBefore, vp);
        exactBefore = tExact;
        paperBefore = tPaper;
    }
}

} // namespace

int main(int argc, char** argv) {
    std::string models = std::string(LIMN_TEST_DATA_DIR) + "/tri";
    bool quick = false;
    std::vector<std::string> only;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--models") && i + 1 < argc) models = argv[++i];
        else if (!std::strcmp(argv[i], "--quick")) quick = true;
        else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) only.push_back(argv[++i]);
        else {
            std::fprintf(stderr, "usage: loop_bench [--models DIR] [--mesh NAME]... [--quick]\n");
            return 2;
        }
    }
    std::vector<std::string> meshes = {"cat_lowres", "spot_triangulated", "goathead", "penguin",
                                       "plane_holes"};
    if (quick) meshes = {"goathead"};
    if (!only.empty()) meshes = only;
    std::vector<double> bboxEps = {5e-6, 1e-5, 2e-5, 4e-5, 8e-5, 1.6e-4};
    std::vector<double> edgeEps = {0.00125, 0.0025, 0.005, 0.01, 0.02};
    std::vector<double> chordEps = {1e-5, 2e-5, 4e-5, 8e-5, 1.6e-4, 3.2e-4};
    if (quick) bboxEps = {5e-6, 2e-5, 8e-5};
    // "paper:" re-applies Loop's masks to the adaptive mesh (the paper, math.md B.7); "exact:" keeps
    // every vertex on the uniform hierarchy (limn's default). Then metric / normalization / even rule.
    std::vector<Variant> variants = {
        {"paper:full/bbox/even-split", Positions::Paper, Normalization::BoundingBox, Metric::Full, EvenUpdate::Split, bboxEps},
        {"paper:full/bbox/even-all", Positions::Paper, Normalization::BoundingBox, Metric::Full, EvenUpdate::All, bboxEps},
        {"paper:normal/bbox/even-split", Positions::Paper, Normalization::BoundingBox, Metric::Normal, EvenUpdate::Split, bboxEps},
        {"exact:full/bbox/even-split", Positions::Exact, Normalization::BoundingBox, Metric::Full, EvenUpdate::Split, bboxEps},
        {"exact:full/bbox/even-all", Positions::Exact, Normalization::BoundingBox, Metric::Full, EvenUpdate::All, bboxEps},
        {"exact:normal/bbox/even-split", Positions::Exact, Normalization::BoundingBox, Metric::Normal, EvenUpdate::Split, bboxEps},
        {"exact:full/edge/even-split", Positions::Exact, Normalization::EdgeLength, Metric::Full, EvenUpdate::Split, edgeEps},
        {"exact:chord/bbox/even-split", Positions::Exact, Normalization::BoundingBox, Metric::Chord, EvenUpdate::Split, chordEps},
    };
    if (quick) variants.resize(1);
    const int levels = 2;

    std::string table;
    char line[512];
    for (const std::string& name : meshes) {
        Warnings w;
        auto t0 = std::chrono::steady_clock::now();
        TriMesh control = fromMesh(importMeshFile(models + "/" + name + ".obj", w), {}, w);
        MeasureOptions mo;
        mo.referenceLevel = defaultReferenceLevel(control, levels);
        mo.maxSamples = 100000;
        LimitReference reference(control, mo);
        std::fprintf(stderr, "%s: reference level %d (%u triangles) in %.1f s\n", name.c_str(),
                     mo.referenceLevel, reference.mesh().triangleCount(), seconds(t0));

        auto run = [&](const char* method, const char* variant, const AdaptiveOptions& o, int lv) {
            AdaptiveResult r = subdivide(control, o);
            Measurement m = reference.measure(r.mesh);
            JsonWriter j;
            j.beginObject().field("bench", "loop").field("mesh", name).field("method", method);
            if (variant) j.field("variant", variant).field("epsilon", o.epsilon);
            j.field("levels", lv).field("vertices", r.mesh.vertexCount());
            j.field("faces", r.mesh.triangleCount()).field("max", m.max).field("rms", m.rms);
            j.field("max_to_limit", m.toLimit.max).field("max_from_limit", m.fromLimit.max);
            j.field("reference_level", m.referenceLevel).endObject();
            emit(j);
            return Point{o.epsilon, r.mesh.vertexCount(), m.max, m.rms};
        };
        std::vector<Point> uniform;
        for (int l = 0; l <= 3; ++l) {
            AdaptiveOptions o;
            o.uniform = true;
            o.levels = l;
            uniform.push_back(run("uniform", nullptr, o, l));
        }
        const Point& u2 = uniform[2];
        std::snprintf(line, sizeof line, "\n%s (V0 %u): uniform L1 %u / %.2e / %.2e, L2 %u / %.2e / %.2e, L3 %u / %.2e / %.2e  (V / max / rms)\n",
                      name.c_str(), uniform[0].vertices, uniform[1].vertices, uniform[1].max, uniform[1].rms,
                      u2.vertices, u2.max, u2.rms, uniform[3].vertices, uniform[3].max, uniform[3].rms);
        table += line;
        table += "  variant                      saving@L2max saving@L2rms  V@1.3xmax (saving)  below uniform curve\n";
        for (const Variant& var : variants) {
            std::vector<Point> curve;
            for (double eps : var.epsilons) {
                AdaptiveOptions o;
                o.levels = levels;
                o.epsilon = eps;
                o.normalization = var.normalization;
                o.metric = var.metric;
                o.evenUpdate = var.even;
                o.positions = var.positions;
                curve.push_back(run("adaptive", var.name, o, levels));
            }
            std::sort(curve.begin(), curve.end(),
                      [](const Point& a, const Point& b) { return a.vertices < b.vertices; });
            double vMax = verticesAtError(curve, u2.max, true);
            double vRms = verticesAtError(curve, u2.rms, false);
            double v13 = verticesAtError(curve, 1.3 * u2.max, true);
            int below = 0, belowRms = 0, compared = 0;
            for (const Point& p : curve) {
                if (p.vertices <= uniform[0].vertices || p.vertices >= uniform[3].vertices) continue;
                ++compared;
                if (p.max < interpolateError(uniform, p.vertices, true)) ++below;
                if (p.rms < interpolateError(uniform, p.vertices, false)) ++belowRms;
            }
            // -100% means the curve never reaches that error below the uniform level-2 count.
            auto saving = [&](double v) { return v > 0 ? 1.0 - v / u2.vertices : -1.0; };
            JsonWriter j;
            j.beginObject().field("bench", "loop_summary").field("mesh", name).field("variant", var.name);
            j.field("uniform2_vertices", u2.vertices).field("uniform2_max", u2.max).field("uniform2_rms", u2.rms);
            j.field("vertices_at_uniform2_max", vMax).field("saving_at_uniform2_max", saving(vMax));
            j.field("vertices_at_uniform2_rms", vRms).field("saving_at_uniform2_rms", saving(vRms));
            j.field("vertices_at_1.3x_uniform2_max", v13).field("saving_at_1.3x_uniform2_max", saving(v13));
            j.field("points_below_uniform_max", below).field("points_below_uniform_rms", belowRms);
            j.field("points_compared", compared).endObject();
            emit(j);
            std::snprintf(line, sizeof line, "  %-28s %11.0f%% %11.0f%%  %8.0f (%4.0f%%)  %d/%d max, %d/%d rms\n",
                          var.name, 100 * saving(vMax), 100 * saving(vRms), v13, 100 * saving(v13), below,
                          compared, belowRms, compared);
            table += line;
            for (const Point& p : curve) {
                std::snprintf(line, sizeof line, "      eps %-8g V %7u  max %.2e (%.2fx L2)  rms %.2e (%.2fx L2)\n",
                              p.epsilon, p.vertices, p.max, p.max / u2.max, p.rms, p.rms / u2.rms);
                table += line;
            }
        }
        std::fprintf(stderr, "%s: done in %.1f s\n", name.c_str(), seconds(t0));
    }
    std::fprintf(stderr, "%s", table.c_str());

    Warnings w;
    std::string largest = quick ? "goathead" : "plane_holes";
    TriMesh control = fromMesh(importMeshFile(models + "/" + largest + ".obj", w), {}, w);
    timeLevels(largest, control, quick ? 1 : 3);
    return 0;
}
