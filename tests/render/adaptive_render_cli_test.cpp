// View-adaptive tessellation, run as users run it (limn-classify | limn-tables | limn-render
// --mesh-out, --max-error 0 --edge-pixels 4: segments of about 4 px) in close-up views where the
// edge rates run from 1 to 32 and more:
// - every drawn vertex lies on OpenSubdiv's limit surface at its (ptex, u, v), normals compared
//   with their sign;
// - welded by exact position, every edge of a closed input is used by exactly two triangles in
//   opposite directions (so the two sides of every edge drew the same points: equal rates, no
//   T-junction, no crack); on open inputs every unpaired edge lies on the mesh boundary;
// - drawn edges seen on screen are about --edge-pixels long (tolerance below).
// The options, displacement and error messages: adaptive_options_cli_test.cpp; images:
// adaptive_image_cli_test.cpp.
// Expected values come from OpenSubdiv, from the mesh file and from the camera the tool reports;
// never from limn's tessellation.
#include "drawn_ply.h"
#include "mesh/import.h"
#include "model_tables.h"
#include "osd_oracle.h"
#include "image/srgb_image.h"
#include "subdiv/tables.h"
#include "adaptive_cli_support.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace limn;
using namespace limn::test;

namespace {

struct Case {
    std::string model; // under the test models, or "sphere" (generated, the paper's demo layout)
    int depth;
    bool closed;
    // The camera looks at control vertex 0 from outside: from the box centre's side away
    // (plus `direction`), `distance` half diagonals away.
    glm::dvec3 direction;
    double distance;
    bool spansRates = false; // the view gives level-0 patches both rate <= 2 and >= 32
};
void PrintTo(const Case& c, std::ostream* os) {
    *os << c.model << " depth " << c.depth << " distance " << c.distance;
}
std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model.substr(info.param.model.find_last_of('/') + 1);
    s = s.substr(0, s.find('.'));
    return s + "_d" + std::to_string(info.param.depth);
}

std::string modelFile(const Case& c, const ScratchDir& dir) {
    if (c.model == "prism7") return writePrism(dir / "prism7.obj", 7);
    return c.model == "sphere" ? writeSphere(dir / "sphere.obj") : modelPath(c.model).string();
}

// Base edges of the mesh with one face (holes count as no face): the boundary of the drawn
// surface. Ptex numbering (OpenSubdiv): a quad one face, an n-gon n sub-faces.
struct BoundaryInfo {
    std::set<std::pair<uint32_t, uint32_t>> edges;
    std::set<uint32_t> vertices;
    struct PtexFace {
        uint32_t face;
        int sub;
    };
    std::vector<PtexFace> ptex;
};
BoundaryInfo boundaryOf(const Mesh& m) {
    BoundaryInfo b;
    std::set<uint32_t> holes(m.tags.holes.begin(), m.tags.holes.end());
    std::map<std::pair<uint32_t, uint32_t>, int> count;
    for (uint32_t f = 0; f + 1 < m.faceOffsets.size(); ++f) {
        const uint32_t first = m.faceOffsets[f], n = m.faceOffsets[f + 1] - first;
        if (n == 4) b.ptex.push_back({f, -1});
        else
            for (uint32_t k = 0; k < n; ++k) b.ptex.push_back({f, int(k)});
        if (holes.count(f)) continue;
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t a = m.faceVertices[first + k], c = m.faceVertices[first + (k + 1) % n];
            ++count[{std::min(a, c), std::max(a, c)}];
        }
    }
    for (const auto& [e, n] : count)
        if (n == 1) b.edges.insert(e), b.vertices.insert(e.first), b.vertices.insert(e.second);
    return b;
}

// Whether a drawn point (ptex, u, v) lies on the mesh boundary.
bool onBoundary(const Mesh& m, const BoundaryInfo& b, const PlyVertex& v) {
    const auto& pf = b.ptex.at(size_t(v.ptex));
    const uint32_t first = m.faceOffsets[pf.face], n = m.faceOffsets[pf.face + 1] - first;
    auto vert = [&](uint32_t k) { return m.faceVertices[first + (k % n)]; };
    auto edge = [&](uint32_t k0, uint32_t k1) {
        uint32_t a = vert(k0), c = vert(k1);
        return b.edges.count({std::min(a, c), std::max(a, c)}) != 0;
    };
    const float u = v.uv[0], w = v.uv[1];
    const bool u0 = u == 0, u1 = u == 1, w0 = w == 0, w1 = w == 1;
    if (pf.sub < 0) {
        if ((u0 || u1) && (w0 || w1)) return b.vertices.count(vert(u0 ? (w0 ? 0 : 3) : (w0 ? 1 : 2))) != 0;
        return (w0 && edge(0, 1)) || (u1 && edge(1, 2)) || (w1 && edge(2, 3)) || (u0 && edge(3, 0));
    }
    const uint32_t k = uint32_t(pf.sub);
    if (u0 && w0) return b.vertices.count(vert(k)) != 0;
    return (w0 && !u1 && edge(k, k + 1)) || (u0 && !w1 && edge(k + n - 1, k)) ||
           (w0 && u1 && edge(k, k + 1)) || (u0 && w1 && edge(k + n - 1, k));
}

// The largest distance, in pixels of the view, between a drawn triangle's centroid and the
// limit surface at its interpolated (ptex, u, v) (1b. below). Measured over these cases: at most
// 0.69 px in patches and 0.51 px in irregular faces; with bilinear irregular faces (tables with
// --irregular-levels 0) 3.9 px (prism7), 13.4 px (smoothtris0 d2) and 23.8 px (d1).
constexpr double kCentroidPixels = 1.0;

class AdaptiveRender : public ::testing::TestWithParam<Case> {};

TEST_P(AdaptiveRender, OnTheLimitSurfaceWatertightAndSizedByTheView) {
    const Case& c = GetParam();
    ScratchDir dir;
    const std::string obj = modelFile(c, dir);
    const std::string limn = prepare(obj, c.depth, dir), ply = (dir / "drawn.ply").string();
    const uint32_t W = 320, H = 240;
    const double P = 4, fov = 35;
    Warnings w;
    Mesh mesh = importMeshFile(obj, w);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    const glm::dvec3 target = mesh.positions[0];
    const glm::dvec3 away = glm::normalize(target - 0.5 * (lo + hi)) + c.direction;
    const glm::dvec3 eye = target + glm::normalize(away) * (c.distance * diag / 2);
    // The length rule (--max-error 0), which part 3 measures; the error-driven rates are welded
    // by AdaptiveErrorRates.
    auto r = run({tool("limn-render").string(), limn, "--size", "320x240", "--validate", "--eye",
                  triple(eye), "--target", triple(target), "--eval", "compute", "--mesh-out", ply,
                  "--max-error", "0", "--edge-pixels", "4", "-o", (dir / "image.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Drawn drawn = parsePly(readFile(ply));

    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    TablesOptions to;
    to.depth = c.depth;
    Tables t = buildTables(mesh, so, to, w);

    // 1. On the limit surface, every drawn vertex: the irregular faces too, drawn on their
    // sub-patches (docs/irregular.md; at the default --tess 64 no vertex falls within 2^-6 of an
    // extraordinary corner, where they would be bilinear).
    struct Dom {
        double u0, v0, size;
        bool patch;
    };
    std::map<uint32_t, std::vector<Dom>> domains;
    for (const Patch& p : t.patches) domains[p.ptex].push_back({p.u0, p.v0, p.size, true});
    for (const IrregularFace& q : t.irregular) domains[q.ptex].push_back({q.u0, q.v0, q.size, false});
    // Isolation 10: OpenSubdiv's patches are the limit surface only where its isolation has
    // outlasted the sharpness of semi-sharp creases (catmark_hole_test2: 7.5).
    OsdLimitSurface osd(mesh, so, 10);
    const std::vector<uint8_t> smooth = smoothCorners(mesh, so);
    double worstP = 0, worstN = 0;
    size_t compared = 0;
    for (const PlyVertex& v : drawn.vertices) {
        bool any = false;
        for (const Dom& d : domains[uint32_t(v.ptex)])
            if (v.uv[0] >= d.u0 && v.uv[0] <= d.u0 + d.size && v.uv[1] >= d.v0 && v.uv[1] <= d.v0 + d.size)
                any = true;
        ASSERT_TRUE(any) << "a drawn vertex outside every element of its ptex face";
        glm::dvec3 ref, refN;
        ASSERT_TRUE(osd.evaluate(v.ptex, v.uv[0], v.uv[1], ref, refN));
        glm::dvec3 got(v.p[0], v.p[1], v.p[2]), gotN(v.n[0], v.n[1], v.n[2]);
        worstP = std::max(worstP, glm::length(got - ref) / diag);
        // Smooth corners' normals converge like 1/level: OpenSubdiv's end caps freeze them.
        const int bv = baseVertexAt(mesh, uint32_t(v.ptex), v.uv[0], v.uv[1]);
        if (!(bv >= 0 && smooth[size_t(bv)]))
            worstN = std::max(worstN, std::acos(std::clamp(glm::dot(glm::normalize(gotN), refN), -1.0, 1.0)) * 180 / M_PI);
        ++compared;
    }
    EXPECT_EQ(compared, drawn.vertices.size());
    EXPECT_LE(worstP, 1e-5) << compared << " vertices compared";
    EXPECT_LE(worstN, 0.5) << "degrees, with sign";

    // 1b. Between drawn vertices: each drawn triangle's centroid, labelled with the interpolated
    // (ptex, u, v), against OpenSubdiv's limit there, in pixels of this view (the camera of 3.
    // below). That is the flatness of the triangles: their edges are about --edge-pixels long
    // on screen (3.), so a centroid is off by about L^2 / 8R for a surface bending with radius R
    // pixels; it must hold inside the irregular faces, drawn on their sub-patches, as inside
    // patches (bilinear irregular faces were up to 1.9e-2 of the diagonal off: pixels here).
    const glm::dmat4 vp = glm::perspective(glm::radians(fov), double(W) / H, 0.01, 1000.0) *
                          glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
    auto toScreen = [&](const glm::dvec3& p, glm::dvec2& s) {
        const glm::dvec4 q = vp * glm::dvec4(p, 1.0);
        s = glm::dvec2(q.x / q.w * W / 2, q.y / q.w * H / 2);
        return q.w > 0 && std::abs(q.x) <= q.w && std::abs(q.y) <= q.w;
    };
    double worstInside[2] = {0, 0}; // pixels: in patches, in irregular faces
    size_t centroids[2] = {0, 0}, mixedPtex = 0;
    for (const auto& tri : drawn.triangles) {
        const PlyVertex &a = drawn.vertices[size_t(tri[0])], &b = drawn.vertices[size_t(tri[1])],
                        &e = drawn.vertices[size_t(tri[2])];
        if (a.ptex != b.ptex || a.ptex != e.ptex) {
            ++mixedPtex; // a shared point labelled with a neighbour's ptex face
            continue;
        }
        const double u = (double(a.uv[0]) + b.uv[0] + e.uv[0]) / 3, v = (double(a.uv[1]) + b.uv[1] + e.uv[1]) / 3;
        const glm::dvec3 got = (glm::dvec3(a.p[0], a.p[1], a.p[2]) + glm::dvec3(b.p[0], b.p[1], b.p[2]) +
                                glm::dvec3(e.p[0], e.p[1], e.p[2])) / 3.0;
        glm::dvec3 ref, refN;
        ASSERT_TRUE(osd.evaluate(a.ptex, u, v, ref, refN));
        // Triangles wholly on screen and facing the eye (on closed surfaces: back faces are
        // culled and kept in --mesh-out at their smallest rate), as in 3.
        glm::dvec2 sg, sr, s[3];
        bool shown = toScreen(got, sg) && toScreen(ref, sr);
        for (int k = 0; k < 3 && shown; ++k) {
            const float* q = drawn.vertices[size_t(tri[k])].p;
            shown = toScreen(glm::dvec3(q[0], q[1], q[2]), s[k]);
        }
        const glm::dvec2 e1 = s[1] - s[0], e2 = s[2] - s[0];
        const double area = e1.x * e2.y - e1.y * e2.x;
        if (!shown || (c.closed ? area <= 0 : area == 0)) continue;
        int kind = 0;
        for (const Dom& d : domains[uint32_t(a.ptex)])
            if (!d.patch && u >= d.u0 && u <= d.u0 + d.size && v >= d.v0 && v <= d.v0 + d.size) kind = 1;
        worstInside[kind] = std::max(worstInside[kind], glm::length(sg - sr));
        ++centroids[kind];
    }
    EXPECT_GT(centroids[0] + centroids[1], 300u) << mixedPtex << " triangles across ptex faces";
    EXPECT_LE(worstInside[0], kCentroidPixels) << centroids[0] << " triangle centroids in patches";
    EXPECT_LE(worstInside[1], kCentroidPixels) << centroids[1] << " triangle centroids in irregular faces";

    // 2. Welded by exact position: each directed edge once, its reverse once (closed), or
    // unpaired only on the mesh boundary.
    std::map<std::array<float, 3>, int> weld;
    std::vector<int> id(drawn.vertices.size());
    for (size_t i = 0; i < drawn.vertices.size(); ++i) {
        const float* p = drawn.vertices[i].p;
        id[i] = weld.try_emplace({p[0], p[1], p[2]}, int(weld.size())).first->second;
    }
    std::map<std::pair<int, int>, std::pair<int, int>> directed; // -> uses, a drawn triangle corner
    size_t collapsed = 0;
    for (size_t f = 0; f < drawn.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            int a = id[drawn.triangles[f][k]], b = id[drawn.triangles[f][(k + 1) % 3]];
            if (a == b) {
                ++collapsed;
                continue;
            }
            auto& e = directed[{a, b}];
            ++e.first;
            e.second = drawn.triangles[f][k];
        }
    EXPECT_EQ(collapsed, 0u);
    size_t twice = 0, unpaired = 0, unpairedInside = 0;
    const BoundaryInfo boundary = boundaryOf(mesh);
    for (const auto& [e, use] : directed) {
        if (use.first > 1) ++twice;
        if (directed.count({e.second, e.first})) continue;
        ++unpaired;
        // Both ends on the mesh boundary (the end we kept a drawn index for, and the other).
        const PlyVertex& a = drawn.vertices[size_t(use.second)];
        bool ok = onBoundary(mesh, boundary, a);
        if (!ok) ++unpairedInside;
    }
    EXPECT_EQ(twice, 0u) << "directed edges used by more than one triangle";
    if (c.closed) {
        EXPECT_EQ(unpaired, 0u) << "open edges after welding by exact position";
    } else {
        EXPECT_GT(unpaired, 0u);
        EXPECT_EQ(unpairedInside, 0u) << "unpaired edges away from the mesh boundary (cracks)";
    }

    // 3. Sized by the view: project the drawn edges with the camera given (35 degrees, Y up). Of
    // the edges of triangles wholly on screen (front-facing ones on closed surfaces, whose back
    // faces are culled and kept in --mesh-out at their smallest rate), 99% must be at most
    // 2.5 P long and none longer than 8 P (a rate is ceil(length / P) of the piece's three-point
    // polyline, the parameter spacing is uniform rather than by arc length, interior grid
    // diagonals are sqrt(2) longer and zipper strips join sides to a ring at their own spacing).
    // And the rates vary: some ptex side carries >= 32 segments.
    std::vector<double> lengths;
    for (const auto& tri : drawn.triangles) {
        glm::dvec2 s[3];
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) {
            const float* p = drawn.vertices[size_t(tri[k])].p;
            glm::dvec4 q = vp * glm::dvec4(p[0], p[1], p[2], 1.0);
            inside = q.w > 0 && std::abs(q.x) <= q.w && std::abs(q.y) <= q.w;
            s[k] = glm::dvec2(q.x / q.w * W / 2, q.y / q.w * H / 2);
        }
        if (!inside) continue;
        const glm::dvec2 e1 = s[1] - s[0], e2 = s[2] - s[0];
        const double area = e1.x * e2.y - e1.y * e2.x;
        if (c.closed ? area <= 0 : area == 0) continue; // facing away, or edge-on
        for (int k = 0; k < 3; ++k) lengths.push_back(glm::length(s[(k + 1) % 3] - s[k]));
    }
    ASSERT_GT(lengths.size(), 300u);
    std::sort(lengths.begin(), lengths.end());
    const double p50 = lengths[lengths.size() / 2], p99 = lengths[lengths.size() * 99 / 100];
    EXPECT_LE(p99, 2.5 * P) << "median " << p50 << ", max " << lengths.back();
    EXPECT_LE(lengths.back(), 8 * P) << "median " << p50 << ", p99 " << p99;
    // Rates vary: an element has, strictly inside its domain, no point (flat: the corners' quad,
    // or two triangles), one centre point (interior rates <= 2), or the (mu-1)(mv-1) points of a
    // grid with interior rates mu along u and mv along v, at mu - 1 distinct u and mv - 1
    // distinct v. (Culled elements are kept at their smallest rate: a large rate is a drawn one.)
    std::map<int, std::vector<const PlyVertex*>> byPtex;
    for (const PlyVertex& v : drawn.vertices) byPtex[v.ptex].push_back(&v);
    size_t most = 0, least = SIZE_MAX;
    for (const auto& [ptex, doms] : domains)
        for (const Dom& d : doms) {
            std::set<float> us, vs;
            for (const PlyVertex* v : byPtex[int(ptex)])
                if (v->uv[0] > d.u0 && v->uv[0] < d.u0 + d.size && v->uv[1] > d.v0 && v->uv[1] < d.v0 + d.size)
                    us.insert(v->uv[0]), vs.insert(v->uv[1]);
            const size_t rate = us.empty() ? 1 : 1 + std::max(us.size(), vs.size());
            most = std::max(most, rate);
            least = std::min(least, us.size());
        }
    const int mostRate = int(most);
    if (c.spansRates) {
        EXPECT_GE(mostRate, 32) << "no element with 32 segments: not a close-up";
        EXPECT_LE(least, 1u) << "no element at the smallest rate";
    }
    std::printf("%s d%d: %zu vertices, %zu triangles, edge px median %.2f p99 %.2f max %.2f, most "
                "interior rate of an element %d, worst %.2e diag %.3f deg, centroids %.3f px "
                "(%zu in patches) %.3f px (%zu in irregular faces)\n",
                c.model.c_str(), c.depth, drawn.vertices.size(), drawn.triangles.size(), p50, p99,
                lengths.back(), mostRate, worstP, worstN, worstInside[0], centroids[0], worstInside[1], centroids[1]);
}

const Case kCases[] = {
    {"quad/spot_control_mesh.obj", 1, true, {0.2, 0.3, 1}, 0.6, true},
    {"quad/spot_control_mesh.obj", 6, true, {-1, 0.5, 0.5}, 0.8, true},
    {"quad/blub_control_mesh.obj", 4, true, {1, 0.4, 0.6}, 0.9},
    {"osd/catmark/catmark_nonquads.obj", 2, false, {0.3, 1, 0.4}, 0.5},
    {"osd/catmark/catmark_hole_test2.obj", 3, false, {0.4, 1, 0.6}, 0.7},
    {"osd/catmark/catmark_single_crease.obj", 3, false, {0.3, 1, 0.5}, 0.7},
    {"osd/catmark/catmark_torus_creases0.obj", 3, true, {0.5, 1, 0.2}, 0.8},
    {"quad/osd_catmark_xord_boundary.obj", 5, false, {0.1, 1, 0.3}, 0.6},
    {"osd/catmark/catmark_cubes_semisharp.obj", 3, true, {0.6, 0.5, 1}, 0.7},
    {"sphere", 6, true, {0, -0.5, 1}, 0.25, true},
    // Every vertex extraordinary, two per face at depth 1, poles of valence 20, n-gons.
    {"osd/catmark/catmark_smoothtris0.obj", 2, true, {0.3, 0.2, 1}, 0.6},
    {"osd/catmark/catmark_smoothtris0.obj", 1, true, {0.3, 0.2, 1}, 0.6},
    {"tri/osd_loop_tetrahedron.obj", 2, true, {0.2, 1, 0.4}, 2.0},
    {"prism7", 3, true, {0.4, 0.3, 1}, 0.6},
    {"osd/catmark/catmark_car.obj", 3, false, {0.2, 0.6, 1}, 0.7},
    // Faces around boundary vertices on their configurations' bases (smooth boundary vertices of
    // 2 to 4 faces; edge-only smooth corners and boundary vertices of 3 faces).
    {"tri/cube_no_bottom.obj", 2, false, {0.3, -0.6, 0.5}, 0.7},
    {"osd/catmark/catmark_edgeonly.obj", 2, false, {0.3, 0.4, 1}, 0.7},
    // And in sectors between infinitely sharp creases.
    {"osd/catmark/catmark_cubes_infsharp.obj", 2, true, {0.3, 0.5, 1}, 0.8},
};

INSTANTIATE_TEST_SUITE_P(Shared, AdaptiveRender, ::testing::ValuesIn(kCases), caseName);

} // namespace
