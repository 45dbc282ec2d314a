// View-adaptive tessellation, run as users run it (limn-classify | limn-tables | limn-render
// --mesh-out, --max-error 0 --edge-pixels 4: segments of about 4 px) in close-up views where the
// edge rates run from 1 to 32 and more:
// - every drawn vertex lies on OpenSubdiv's limit surface at its (ptex, u, v), normals compared
//   with their sign;
// - welded by exact position, every edge of a closed input is used by exactly two triangles in
//   opposite directions (so the two sides of every edge drew the same points: equal rates, no
//   T-junction, no crack); on open inputs every unpaired edge lies on the mesh boundary;
// - drawn edges seen on screen are about --edge-pixels long (tolerance below);
// - images: the adaptive image differs from the fixed grids' (--edge-pixels 0) in at most 0.5%
//   of the covered pixels by more than 8/255, and is the same bytes twice;
// - the default error-driven rates (--max-error): the image against --edge-pixels 1, welded
//   closed.
// Expected values come from OpenSubdiv, from the mesh file and from the camera the tool reports;
// never from limn's tessellation.
#include "drawn_ply.h"
#include "mesh/import.h"
#include "model_tables.h"
#include "osd_oracle.h"
#include "image/srgb_image.h"
#include "subdiv/tables.h"
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

// The paper's demo sphere (model_tables.h's paperSphere) of radius 5, as an OBJ file.
std::string writeSphere(const std::filesystem::path& path) {
    const Mesh m = paperSphere(5);
    std::ofstream o(path);
    char line[128];
    for (const glm::dvec3& p : m.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
        o << line;
    }
    for (size_t f = 0; f < m.faceCount(); ++f) {
        o << "f";
        for (uint32_t v : m.face(f)) o << " " << v + 1;
        o << "\n";
    }
    return path.string();
}

// A closed prism whose two caps are n-gons (n = 7, twisted and bulged so that nothing is flat):
// every cap vertex has valence 3 and each cap's centre, after the first level, valence n.
std::string writePrism(const std::filesystem::path& path, int n) {
    std::ofstream o(path);
    char line[128];
    for (int ring = 0; ring < 2; ++ring)
        for (int k = 0; k < n; ++k) {
            const double a = 2 * M_PI * (k + 0.3 * ring) / n, r = 1 + 0.2 * std::cos(3 * a);
            std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", r * std::cos(a), r * std::sin(a), ring ? 1.3 : -0.4 * r);
            o << line;
        }
    o << "f";
    for (int k = n; k-- > 0;) o << " " << k + 1;
    o << "\nf";
    for (int k = 0; k < n; ++k) o << " " << n + k + 1;
    o << "\n";
    for (int k = 0; k < n; ++k)
        o << "f " << k + 1 << " " << (k + 1) % n + 1 << " " << n + (k + 1) % n + 1 << " " << n + k + 1 << "\n";
    return path.string();
}

std::string modelFile(const Case& c, const ScratchDir& dir) {
    if (c.model == "prism7") return writePrism(dir / "prism7.obj", 7);
    return c.model == "sphere" ? writeSphere(dir / "sphere.obj") : modelPath(c.model).string();
}

std::string prepare(const std::string& obj, int depth, const ScratchDir& dir, std::vector<std::string> classify = {}) {
    const std::string limn = (dir / "in.limn").string();
    classify.insert(classify.begin(), {tool("limn-classify").string(), obj, "-o", limn});
    auto r = run(classify);
    if (r.exitCode != 0) throw std::runtime_error(r.err);
    r = run({tool("limn-tables").string(), limn, "-q", "-o", limn, "--depth", std::to_string(depth)});
    if (r.exitCode != 0) throw std::runtime_error(r.err);
    return limn;
}

std::string triple(const glm::dvec3& v) {
    char s[128];
    std::snprintf(s, sizeof s, "%.9g,%.9g,%.9g", v.x, v.y, v.z);
    return s;
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
};

INSTANTIATE_TEST_SUITE_P(Shared, AdaptiveRender, ::testing::ValuesIn(kCases), caseName);

// Displacement (paper 000, 4.5) on the view-adaptive tessellation, close up: every drawn vertex
// of a regular patch moved from OpenSubdiv's limit point along OpenSubdiv's limit normal (the
// offset's component across the normal within 1e-5 of the diagonal, its length within the map's
// range); welded closed with the seam fix, and open without it (the UV-noise map differs across
// UV seams, so each side's own samples crack the surface: the check can fail).
TEST(AdaptiveDisplacement, AlongTheNormalClosedWithSeamFixOpenWithout) {
    ScratchDir dir;
    const std::string obj = modelPath("quad/spot_control_mesh.obj").string();
    const std::string limn = prepare(obj, 3, dir), map = (dir / "h.png").string();
    auto r = run({tool("limn-seams").string(), limn, "-o", limn});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run({tool("limn-heightmap").string(), limn, "--kind", "uv", "-o", map});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Warnings w;
    Mesh mesh = importMeshFile(obj, w);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo), scale = 0.03 * diag;
    const glm::dvec3 target = mesh.positions[0];
    const glm::dvec3 eye = target + glm::normalize(target - 0.5 * (lo + hi)) * (0.4 * diag);
    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    TablesOptions to;
    to.depth = 3;
    Tables t = buildTables(mesh, so, to, w);
    std::map<uint32_t, std::vector<std::array<double, 3>>> patches; // ptex -> u0, v0, size
    std::map<uint32_t, int> irregular;
    for (const Patch& p : t.patches) patches[p.ptex].push_back({p.u0, p.v0, p.size});
    for (const IrregularFace& q : t.irregular) ++irregular[q.ptex];
    OsdLimitSurface osd(mesh, so, 5);
    for (bool fix : {true, false}) {
        SCOPED_TRACE(fix ? "seam fix" : "no seam fix");
        const std::string ply = (dir / "d.ply").string();
        std::vector<std::string> args = {tool("limn-render").string(), limn, "--size", "320x240", "--validate",
                                         "--eye", triple(eye), "--target", triple(target), "--displace", map,
                                         "--displace-scale", std::to_string(scale), "--displace-mid", "0.5",
                                         "--mesh-out", ply, "-o", (dir / "d.png").string()};
        if (!fix) args.push_back("--no-seam-fix");
        r = run(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Drawn drawn = parsePly(readFile(ply));
        double across = 0, longest = 0;
        size_t compared = 0;
        for (const PlyVertex& v : drawn.vertices) {
            if (irregular.count(uint32_t(v.ptex))) continue; // only ptex faces of regular patches
            glm::dvec3 ref, refN;
            ASSERT_TRUE(osd.evaluate(v.ptex, v.uv[0], v.uv[1], ref, refN));
            const glm::dvec3 d = glm::dvec3(v.p[0], v.p[1], v.p[2]) - ref;
            across = std::max(across, glm::length(d - glm::dot(d, refN) * refN) / diag);
            longest = std::max(longest, glm::length(d));
            ++compared;
        }
        EXPECT_GT(compared, drawn.vertices.size() / 10);
        EXPECT_LE(across, 1e-5) << "displaced off the limit normal";
        EXPECT_LE(longest, 0.5 * scale * 1.0001) << "more than scale * |sample - mid|";
        EXPECT_GT(longest, 0.05 * scale) << "not displaced";
        const WeldedEdges welded = weldedEdges(drawn);
        EXPECT_EQ(welded.over, 0u);
        if (fix) {
            EXPECT_EQ(welded.open, 0u) << "open edges with the seam fix";
        } else {
            EXPECT_GT(welded.open, 0u) << "no cracks without the seam fix: the test shows nothing";
        }
        std::printf("%s: %zu vertices, %zu triangles, open edges %zu, across %.2e diag, longest %.3f of scale\n",
                    fix ? "fix" : "nofix", drawn.vertices.size(), drawn.triangles.size(), welded.open, across,
                    longest / scale);
    }
}

// --mesh-out flags the vertices drawn where the surface is approximate (bilinear within 2^-K of
// an extraordinary corner, docs/irregular.md): with K = 2 tables (the default --tess 64 lands
// vertices there) every vertex off OpenSubdiv's limit by more than 1e-5 of the diagonal is
// flagged and every unflagged one is on it; with the default K = 6 nothing is, and the PLY keeps
// its layout without the property.
TEST(AdaptiveCli, MeshOutFlagsTheApproximateVertices) {
    ScratchDir dir;
    const std::string obj = modelPath("osd/catmark/catmark_smoothtris0.obj").string(), limn = (dir / "c.limn").string();
    ASSERT_EQ(run({tool("limn-classify").string(), obj, "-o", limn}).exitCode, 0);
    Warnings w;
    const Mesh mesh = importMeshFile(obj, w);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    OsdLimitSurface osd(mesh, resolveSchemeOptions(mesh.tags, {}), 10);
    for (const char* K : {"2", "6"}) {
        SCOPED_TRACE(std::string("--irregular-levels ") + K);
        const std::string tables = (dir / "t.limn").string(), ply = (dir / "m.ply").string();
        auto r = run({tool("limn-tables").string(), limn, "-q", "--depth", "2", "--irregular-levels", K, "-o", tables});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = run({tool("limn-render").string(), tables, "-q", "--size", "160x120", "--mesh-out", ply, "-o",
                 (dir / "i.png").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Drawn drawn = parsePly(readFile(ply));
        size_t flagged = 0, off = 0, offUnflagged = 0;
        for (const PlyVertex& v : drawn.vertices) {
            glm::dvec3 ref, refN;
            ASSERT_TRUE(osd.evaluate(v.ptex, v.uv[0], v.uv[1], ref, refN));
            const bool isOff = glm::length(glm::dvec3(v.p[0], v.p[1], v.p[2]) - ref) / diag > 1e-5;
            flagged += v.approximate, off += isOff, offUnflagged += isOff && !v.approximate;
        }
        EXPECT_EQ(offUnflagged, 0u);
        if (std::string(K) == "2") {
            EXPECT_TRUE(drawn.hasApproximate);
            EXPECT_GT(off, 20u);
            EXPECT_GE(flagged, off);
            EXPECT_LE(flagged, off + off / 10) << "flagged vertices that are on the limit";
        } else {
            EXPECT_FALSE(drawn.hasApproximate);
            EXPECT_EQ(off, 0u);
        }
        std::printf("K %s: %zu vertices, %zu off the limit, %zu flagged approximate\n", K,
                    drawn.vertices.size(), off, flagged);
    }
}

// --tess that is not a power of two used to crash the fixed grids ("vector::_M_range_insert");
// both modes now render and stay welded closed.
TEST(AdaptiveCli, TessNotAPowerOfTwoInBothModes) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/spot_control_mesh.obj").string(), 3, dir);
    for (const char* tess : {"3", "5", "6", "7", "12"})
        for (const char* ep : {"4", "0"}) {
            SCOPED_TRACE(std::string("--tess ") + tess + " --edge-pixels " + ep);
            const std::string ply = (dir / "t.ply").string();
            auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--tess", tess,
                          "--edge-pixels", ep, "--mesh-out", ply, "-o", (dir / "t.png").string()});
            ASSERT_EQ(r.exitCode, 0) << r.err;
            const WeldedEdges welded = weldedEdges(parsePly(readFile(ply)));
            EXPECT_EQ(welded.open, 0u);
            EXPECT_EQ(welded.over, 0u);
        }
}

// Rates far above the default in a close view (--tess 1024, half-pixel segments): every element
// writes all its triangles (lavapipe ends a shader invocation's loops after 65,535 iterations in
// all, which once left most of a big element unwritten: holes, and --mesh-out triangles of one
// repeated vertex), so the surface is welded closed with no triangle collapsed; or, where one
// element's sides alone need more, the render is refused (exit 1, nothing written). cube_creases1 has single-crease patches (graded segments).
TEST(AdaptiveCli, HighRatesWriteEveryTriangle) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("osd/catmark/catmark_cube_creases1.obj").string(), 3, dir);
    const std::string ply = (dir / "t.ply").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "400x300", "--view", "30,40", "--tess", "1024",
                  "--edge-pixels", "0.25", "--mesh-out", ply});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Drawn d = parsePly(readFile(ply));
    EXPECT_GT(d.triangles.size(), 1000000u) << "not a high-rate view";
    const WeldedEdges welded = weldedEdges(d);
    EXPECT_EQ(welded.collapsed, 0u);
    EXPECT_EQ(welded.open, 0u);
    EXPECT_EQ(welded.over, 0u);
    // The same view with smooth UVs spends more loop iterations per vertex (fvar_eval.glsl).
    const std::string spot = prepare(modelPath("quad/spot_control_mesh.obj").string(), 4, dir, {"--fvar", "none"});
    r = run({tool("limn-render").string(), spot, "--size", "400x300", "--eye", "0.3,0.4,0.9", "--target", "0,0.2,0",
             "--tess", "128", "--edge-pixels", "0.25", "--shade", "uv", "--mesh-out", ply});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const WeldedEdges smooth = weldedEdges(parsePly(readFile(ply)));
    EXPECT_EQ(smooth.collapsed, 0u);
    EXPECT_EQ(smooth.open, 0u);
    EXPECT_EQ(smooth.over, 0u);
}

// The same promise where the elements are few and large: a flat 3x3 grid at depth 1 seen from
// above with every side at --tess segments (--edge-pixels 0.001). Up to --tess 1536 every
// element is written whole; past that, on lavapipe, its loop limit ends an element's emit early
// (the emit pass's budget in adaptive_counts.comp is an estimate; at 2048 and 4096 it once left
// 15-50% of the triangles unwritten, as (0, 0, 0), with exit 0). Whatever the device, each
// render is whole (no collapsed triangle) or refused with what to do and nothing written.
TEST(AdaptiveCli, LargeElementsAtHighRatesAreWholeOrRefused) {
    ScratchDir dir;
    std::string obj;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            const int a = y * 4 + x + 1;
            obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 5) + " " +
                   std::to_string(a + 4) + "\n";
        }
    writeFile(dir / "grid.obj", obj);
    const std::string limn = prepare((dir / "grid.obj").string(), 1, dir);
    const std::string ply = (dir / "g.ply").string();
    for (const char* tess : {"1536", "2048", "4096"}) {
        SCOPED_TRACE(tess);
        auto r = run({tool("limn-render").string(), limn, "--eye", "1.5,1.5,3", "--target", "1.5,1.5,0", "--size",
                      "320x240", "--edge-pixels", "0.001", "--tess", tess, "--mesh-out", ply});
        if (r.exitCode == 0) {
            const Drawn d = parsePly(readFile(ply));
            EXPECT_GT(d.triangles.size(), 100000u) << "not a high-rate view";
            EXPECT_EQ(weldedEdges(d).collapsed, 0u) << "triangles left unwritten";
            std::filesystem::remove(ply);
        } else {
            EXPECT_EQ(r.exitCode, 1) << r.err;
            EXPECT_NE(r.err.find("lower --tess"), std::string::npos) << r.err;
            // (--tess above 2^6 is also told that it can draw irregular faces' corners bilinear.)
            std::string other;
            for (size_t at = 0, end; at < r.err.size(); at = end + 1) {
                end = std::min(r.err.find('\n', at), r.err.size());
                const std::string line = r.err.substr(at, end - at);
                if (line.find("--irregular-levels") == std::string::npos) other += line + "\n";
            }
            EXPECT_EQ(other.find("warning"), std::string::npos) << "the error alone, not a warning too: " << r.err;
            EXPECT_FALSE(std::filesystem::exists(ply));
        }
        if (std::string(tess) == "1536") {
            EXPECT_EQ(r.exitCode, 0) << r.err;
        }
    }
}

// A view whose tessellation needs more than the per-frame buffers hold (a sub-pixel
// --edge-pixels) once wrote an image with holes and exit 0, with only a warning: it is refused
// like --mesh-out, and a sequence removes the frames it wrote.
TEST(AdaptiveCli, AViewOverItsBuffersWritesNothing) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/spot_control_mesh.obj").string(), 3, dir);
    const std::string png = (dir / "s.png").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--view", "150,20", "--edge-pixels", "0.001",
                  "-q", "-o", png});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("more than its buffers hold"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing written: raise --max-error or --edge-pixels, or lower --tess"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--edge-pixels", "0.001", "--turntable", "2",
             "-o", (dir / "t_%d.png").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "t_0.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "t_1.png"));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--view", "150,20", "--edge-pixels", "0.001",
             "--bench", "1"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(r.out, "") << "no benchmark JSON for a frame with parts left out";
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--view", "150,20", "-o", png});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// limn-tables accepts --depth 16; the view-adaptive pieces pack depth 15 at most (edge_pieces.cpp),
// so the default mode refuses such tables saying what to do, and the fixed grids render them.
TEST(AdaptiveCli, DepthSixteenTablesRefusedWithWhatToDo) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/osd_catmark_cube.obj").string(), 16, dir);
    const std::string png = (dir / "c.png").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "-o", png});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("these have depth 16"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--depth 15 or less"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--edge-pixels 0"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--edge-pixels", "0", "-o", png});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// catmark_car at depth 6: its fixed grids (64 segments per side of its level-0 patches: about
// 12.9 M triangles, 147.7 MiB of indices)
// are refused before any work with what to do; the view-adaptive default renders it.
TEST(AdaptiveCli, CarAtDepthSixFixedRefusedAdaptiveRenders) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("osd/catmark/catmark_car.obj").string(), 6, dir);
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--edge-pixels", "0", "-o",
                  (dir / "fixed.png").string()});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("128 MiB"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--edge-pixels"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "fixed.png"));
    r = run({tool("limn-render").string(), limn, "--size", "64x48", "--validate", "-o", (dir / "va.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// --wire-triangles draws the edges of the triangles drawn: with view-adaptive tessellation its
// line pixels follow the rates the view chose (a close-up of spot's flank: a quarter of the
// segment length gives over twice the line pixels, lines being 1 px wide and merging where
// dense), with the fixed grids it draws their triangles. Normal shading: no surface pixel has
// the wire's grey (18, 18, 18: an encoded normal is never (-0.86, -0.86, -0.86)). One sample per
// pixel, so a line pixel is exactly the wire colour.
TEST(AdaptiveCli, WireTrianglesFollowTheRates) {
    ScratchDir dir;
    const std::string limn = prepare(modelPath("quad/spot_control_mesh.obj").string(), 3, dir);
    auto wirePixels = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args = {tool("limn-render").string(), limn, "--validate", "--samples", "1",
                                         "--shade", "normal", "--size", "320x240", "--eye", "0.2,0.4,-1.3",
                                         "--target", "0,0.2,-0.3", "--max-error", "0", "-o", (dir / name).string()};
        args.insert(args.end(), extra.begin(), extra.end());
        auto r = run(args);
        if (r.exitCode != 0) throw std::runtime_error(r.err);
        const auto img = render::decodePng(readBytes(dir / name));
        size_t n = 0;
        for (size_t i = 0; i + 2 < img.pixels.size(); i += img.channels)
            n += img.pixels[i] == 18 && img.pixels[i + 1] == 18 && img.pixels[i + 2] == 18;
        return n;
    };
    const size_t none = wirePixels("none.png", {});
    const size_t fine = wirePixels("p8.png", {"--wire-triangles", "--edge-pixels", "8"});
    const size_t coarse = wirePixels("p32.png", {"--wire-triangles", "--edge-pixels", "32"});
    const size_t fixed = wirePixels("fixed.png", {"--wire-triangles", "--edge-pixels", "0"});
    std::printf("wire pixels: none %zu, P=8 %zu, P=32 %zu, fixed %zu\n", none, fine, coarse, fixed);
    EXPECT_EQ(none, 0u);
    EXPECT_GT(coarse, 3000u);
    EXPECT_GT(double(fine), 1.8 * double(coarse));
    EXPECT_GT(fixed, 3000u);
    EXPECT_EQ(readBytes(dir / "p8.png"), (wirePixels("again.png", {"--wire-triangles", "--edge-pixels", "8"}),
                                          readBytes(dir / "again.png")));

    auto r = run({tool("limn-render").string(), limn, "--wire", "--wire-triangles", "-o", (dir / "x.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("choose one"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    const std::string control = (dir / "control.limn").string();
    r = run({tool("limn-classify").string(), modelPath("quad/spot_control_mesh.obj").string(), "-o", control});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = run({tool("limn-render").string(), control, "--wire-triangles", "-o", (dir / "x.png").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("limn-tables"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// Default view-adaptive images against the fixed grids of today (--edge-pixels 0): at most 0.5%
// of the pixels covered in either differ by more than 8/255 in a channel; and the same bytes
// when rendered twice.
struct ImageCase {
    std::string model;
    int depth;
    std::vector<std::string> fixedExtra; // options for the fixed-grid render
    std::vector<std::string> view; // options for both renders: the view, --sample-shading
    double allowed = 0.005; // fraction of covered pixels that may differ
    // Also against a finer view-adaptive render (--edge-pixels 1): the default image must be at
    // least as close to it as the fixed grids' (within 0.1% of the covered pixels).
    bool fineReference = false;
};

// Pixels covered in either image (not the background colour of a's corner pixel, background in
// every view here), and of those, how many differ by more than 8/255 in a channel.
std::pair<size_t, size_t> coveredAndDiffering(const render::Image& a, const render::Image& b) {
    const uint8_t* bg = a.pixels.data();
    size_t covered = 0, differ = 0;
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i) {
        const uint8_t *p = &a.pixels[i * a.channels], *q = &b.pixels[i * b.channels];
        if (std::equal(p, p + 3, bg) && std::equal(q, q + 3, bg)) continue;
        ++covered;
        int d = 0;
        for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(p[k]) - int(q[k])));
        differ += d > 8;
    }
    return {covered, differ};
}

class AdaptiveImage : public ::testing::TestWithParam<ImageCase> {};

TEST_P(AdaptiveImage, CloseToTheFixedGridsAndDeterministic) {
    const ImageCase& c = GetParam();
    ScratchDir dir;
    const std::string obj = c.model == "sphere" ? writeSphere(dir / "sphere.obj") : modelPath(c.model).string();
    const std::string limn = prepare(obj, c.depth, dir);
    auto render = [&](const std::string& name, std::vector<std::string> extra) {
        // The default image (4 samples): a silhouette pixel differs by more than 8/255 where
        // the two outlines cover a different number of its samples, which the chord criterion
        // of adaptive_rates.comp keeps rare.
        std::vector<std::string> args = {tool("limn-render").string(), limn, "--validate", "-o",
                                         (dir / name).string()};
        args.insert(args.end(), c.view.begin(), c.view.end());
        args.insert(args.end(), extra.begin(), extra.end());
        auto r = run(args);
        if (r.exitCode != 0) throw std::runtime_error(r.err);
        return render::decodePng(readBytes(dir / name));
    };
    std::vector<std::string> fixed = {"--edge-pixels", "0"};
    fixed.insert(fixed.end(), c.fixedExtra.begin(), c.fixedExtra.end());
    const auto a = render("adaptive.png", {}), b = render("fixed.png", fixed);
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    const auto [covered, differ] = coveredAndDiffering(a, b);
    ASSERT_GT(covered, 10000u);
    EXPECT_LE(double(differ), c.allowed * double(covered)) << differ << " of " << covered;
    std::printf("%s d%d: %zu of %zu covered pixels differ by > 8/255\n", c.model.c_str(), c.depth, differ, covered);
    if (c.fineReference) {
        const auto fine = render("fine.png", {"--edge-pixels", "1"});
        const auto [coveredA, adaptiveOff] = coveredAndDiffering(a, fine);
        const auto [coveredF, fixedOff] = coveredAndDiffering(b, fine);
        EXPECT_LE(double(adaptiveOff), double(fixedOff) + 0.001 * double(coveredF))
            << "the default view-adaptive image is further from the --edge-pixels 1 image than the fixed grids'";
        std::printf("%s d%d against --edge-pixels 1: view-adaptive %zu of %zu pixels differ, fixed grids %zu of %zu\n",
                    c.model.c_str(), c.depth, adaptiveOff, coveredA, fixedOff, coveredF);
    }
    const auto again = render("again.png", {});
    EXPECT_EQ(readBytes(dir / "adaptive.png"), readBytes(dir / "again.png"));
}

const ImageCase kImages[] = {
    {"quad/spot_control_mesh.obj", 6, {}, {}},
    // Depth 5: the fixed grids of depth 6 need --tess 32, which would cap the single-crease
    // patches along the car's semi-sharp creases (levels 0-1) below the depth's own density;
    // at depth 5 every patch gets its full 2^(5-l) segments, 32 for level 0 as before. Its 314
    // creases of sharpness 6 are single-crease patches, whose surface bends within 2^-6 of the
    // crease: the fixed grids' even segments (a 32nd of the patch) and the view-adaptive ones,
    // graded towards the crease (the first about a quarter pixel), draw that bend differently,
    // in a line along the creases: 0.98% of the covered pixels differ (0.25% before crease
    // patches, when both drew the same level-5 quads there). Neither is the surface: against
    // --edge-pixels 1 (graded to a hundredth of a pixel) the default image is 0.73% off and
    // the fixed grids 0.76%, which the fine-reference check pins.
    {"osd/catmark/catmark_car.obj", 5, {}, {}, 0.015, true},
    // The same with --sample-shading: each of the 4 samples shaded where it lies averages the
    // bend instead of picking it up or missing it at the pixel centre, and the two tessellations
    // agree within the 0.5% (0.34%).
    {"osd/catmark/catmark_car.obj", 5, {}, {"--sample-shading"}, 0.005},
    {"sphere", 6, {}, {"--size", "1280x720", "--eye", "0,12,22", "--target", "0,0,0"}},
};

std::string imageName(const ::testing::TestParamInfo<ImageCase>& param) {
    std::string s = param.param.model.substr(param.param.model.find_last_of('/') + 1);
    s = s.substr(0, s.find('.'));
    const auto& v = param.param.view;
    return std::find(v.begin(), v.end(), "--sample-shading") != v.end() ? s + "_sample_shading" : s;
}

INSTANTIATE_TEST_SUITE_P(Shared, AdaptiveImage, ::testing::ValuesIn(kImages), imageName);

} // namespace

// Back faces dropped by the rasterizer (a closed surface seen from outside, view-adaptive) change
// no pixel: the same image, byte for byte, as with --back-faces, which draws every back face in a
// key colour (and so turns the culling off). Faces wound the other way round (negative volume)
// take the other cull mode; seen from outside they are all back faces, so --back-faces would key
// everything: their image is instead compared with the mesh as wound, which a wrong choice
// (showing the inside, and holes where whole patches facing away are skipped) would not match.
std::string writeReversed(const std::filesystem::path& from, const std::filesystem::path& to) {
    std::ifstream in(from);
    std::ofstream out(to);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("f ", 0) == 0) {
            std::istringstream words(line.substr(2));
            std::vector<std::string> corners;
            for (std::string w; words >> w;) corners.push_back(w);
            std::reverse(corners.begin(), corners.end());
            line = "f";
            for (const std::string& c : corners) line += " " + c;
        }
        out << line << "\n";
    }
    return to.string();
}

struct CullCase {
    std::string name, model;
    int depth;
    bool reversed;
    std::vector<std::string> view;
};

class AdaptiveBackFaces : public ::testing::TestWithParam<CullCase> {};

TEST_P(AdaptiveBackFaces, CullingThemChangesNoPixel) {
    const CullCase& c = GetParam();
    ScratchDir dir;
    std::string obj = c.model == "sphere" ? writeSphere(dir / "sphere.obj") : modelPath(c.model).string();
    const std::string limn = prepare(obj, c.depth, dir);
    ScratchDir reversedDir;
    const std::string reversed =
        c.reversed ? prepare(writeReversed(obj, reversedDir / "reversed.obj"), c.depth, reversedDir) : "";
    auto render = [&](const std::string& name, std::vector<std::string> extra, const std::string& in = "") {
        // One sample per pixel: with MSAA a silhouette sample may see a back face that no
        // pixel centre sees, and the key colour would blend in there.
        std::vector<std::string> args = {tool("limn-render").string(), in.empty() ? limn : in, "--size", "320x240",
                                         "--validate", "--samples", "1", "-o", (dir / name).string()};
        args.insert(args.end(), c.view.begin(), c.view.end());
        args.insert(args.end(), extra.begin(), extra.end());
        auto r = run(args);
        if (r.exitCode != 0) throw std::runtime_error(r.err);
        return readBytes(dir / name);
    };
    const auto culled = render("culled.png", {});
    const auto keyed = render("keyed.png", {"--back-faces", "1,0,0"});
    EXPECT_EQ(culled, keyed);
    if (c.reversed) {
        // The same surface, its triangles wound the other way and split a little differently.
        const auto a = render::decodePng(render("reversed.png", {}, reversed)), b = render::decodePng(culled);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        const auto [covered, differ] = coveredAndDiffering(a, b);
        EXPECT_GT(covered, 2000u);
        EXPECT_LE(double(differ), 0.005 * double(covered)) << differ << " of " << covered;
    }
    // And the image is not empty or all key colour: it has the surface's grey shades.
    const auto img = render::decodePng(culled);
    size_t grey = 0;
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
        const uint8_t* p = &img.pixels[i * img.channels];
        grey += p[0] == p[1] && p[1] == p[2] && p[0] != 51;
    }
    EXPECT_GT(grey, size_t(img.width) * img.height / 20);
}

const CullCase kCullCases[] = {
    {"sphere_d6", "sphere", 6, false, {"--eye", "0,12,22", "--target", "0,0,0"}},
    {"spot_d3", "quad/spot_control_mesh.obj", 3, false, {}},
    {"spot_and_reversed_d3", "quad/spot_control_mesh.obj", 3, true, {"--view", "200,-30"}},
    {"car_d2", "osd/catmark/catmark_car.obj", 2, false, {"--view", "120,35"}},
};

INSTANTIATE_TEST_SUITE_P(Shared, AdaptiveBackFaces, ::testing::ValuesIn(kCullCases),
                         [](const ::testing::TestParamInfo<CullCase>& p) { return p.param.name; });

// The error-driven rates (--max-error, docs/adaptive.md): the default image against the same
// view drawn with segments of at most a pixel (--edge-pixels 1, whose chords are within a few
// hundredths of a pixel of the surface: the reference), at most `allowed` of the covered pixels
// off by more than 8/255; the default image the same bytes twice (spot); welded, the drawn mesh
// closed (closed inputs). Measured: spot 0.44%, quad_sphere 0.26%, displaced 0.85%, the
// icosphere 0.03%, the car 0.90% at 640x480 and 0.53% at 1280x960.
namespace {
struct ErrorCase {
    std::string name;
    std::string model;       // under the test models; "quad_sphere": limn-examples'
    std::vector<std::string> args; // both renders: size, displacement
    double allowed = 0.005;
    bool displaced = false;  // a surface height map (limn-heightmap --kind surface) on it
    bool closed = true;      // the drawn mesh, welded by exact position, is closed
    bool twice = false;      // render the default image twice: the same bytes
};

// Directed edges of the drawn mesh welded by exact position: used more than once, and without
// their reverse (a crack, or an open boundary).
std::pair<size_t, size_t> weldedEdgeFaults(const Drawn& drawn) {
    std::map<std::array<float, 3>, int> weld;
    std::vector<int> id(drawn.vertices.size());
    for (size_t i = 0; i < drawn.vertices.size(); ++i) {
        const float* p = drawn.vertices[i].p;
        id[i] = weld.try_emplace({p[0], p[1], p[2]}, int(weld.size())).first->second;
    }
    std::map<std::pair<int, int>, int> uses;
    for (const auto& t : drawn.triangles)
        for (int k = 0; k < 3; ++k) ++uses[{id[t[k]], id[t[(k + 1) % 3]]}];
    size_t twice = 0, unpaired = 0;
    for (const auto& [e, n] : uses) {
        twice += n > 1;
        unpaired += !uses.count({e.second, e.first});
    }
    return {twice, unpaired};
}

class AdaptiveErrorRates : public ::testing::TestWithParam<ErrorCase> {};
} // namespace

TEST_P(AdaptiveErrorRates, CloseToOnePixelSegments) {
    const ErrorCase& c = GetParam();
    ScratchDir dir;
    std::string obj;
    if (c.model == "quad_sphere") {
        auto r = run({tool("limn-examples").string(), "--only", "quad_sphere", "-o", dir.path().string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        obj = (dir / "quad_sphere.obj").string();
    } else {
        obj = modelPath(c.model).string();
    }
    const std::string limn = prepare(obj, 3, dir);
    std::vector<std::string> args = c.args;
    if (c.displaced) {
        const std::string map = (dir / "bumps.png").string();
        auto r = run({tool("limn-seams").string(), limn, "-o", limn});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = run({tool("limn-heightmap").string(), "--kind", "surface", limn, "-o", map});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        args.insert(args.end(), {"--displace", map, "--displace-scale", "0.2", "--displace-mid", "0.5"});
    }
    auto render = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> argv = {tool("limn-render").string(), limn, "-o", (dir / name).string()};
        argv.insert(argv.end(), args.begin(), args.end());
        argv.insert(argv.end(), extra.begin(), extra.end());
        auto r = run(argv);
        if (r.exitCode != 0) throw std::runtime_error(r.err);
        return render::decodePng(readBytes(dir / name));
    };
    const auto a = render("default.png", {}), fine = render("fine.png", {"--edge-pixels", "1"});
    const auto [covered, differ] = coveredAndDiffering(a, fine);
    ASSERT_GT(covered, 10000u);
    EXPECT_LE(double(differ), c.allowed * double(covered)) << differ << " of " << covered;
    std::printf("%s: %zu of %zu covered pixels differ from --edge-pixels 1 by > 8/255\n", c.name.c_str(), differ,
                covered);
    if (c.twice) {
        render("again.png", {});
        EXPECT_EQ(readBytes(dir / "default.png"), readBytes(dir / "again.png"));
    }
    if (!c.closed) return;
    // The two sides of every edge drew the same points: welded, the drawn mesh is closed.
    std::vector<std::string> argv = {tool("limn-render").string(), limn, "--mesh-out", (dir / "drawn.ply").string()};
    argv.insert(argv.end(), args.begin(), args.end());
    auto r = run(argv);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto [twice, unpaired] = weldedEdgeFaults(parsePly(readFile((dir / "drawn.ply").string())));
    EXPECT_EQ(twice, 0u);
    EXPECT_EQ(unpaired, 0u);
}

const ErrorCase kErrorCases[] = {
    {"spot", "quad/spot_control_mesh.obj", {"--size", "640x480"}, 0.005, false, true, true},
    {"quad_sphere", "quad_sphere", {"--size", "640x480"}},
    // Displaced: both draw the map's bumps at segments of 2 pixels where its texels are denser
    // (the texel bound's cap), the reference at 1: 0.85% off, and 0.83% with the rule before
    // the error estimate (--max-error 0 --edge-pixels 4). 1%: no worse than that.
    {"quad_sphere_displaced", "quad_sphere", {"--size", "640x480"}, 0.01, true},
    {"icosphere_triangles", "tri/sphere.obj", {"--size", "640x480"}},
    // The car's semi-sharp creases bend within a pixel: 1%.
    {"car", "osd/catmark/catmark_car.obj", {"--size", "640x480"}, 0.01, false, false},
    {"car_1280", "osd/catmark/catmark_car.obj", {"--size", "1280x960"}, 0.01, false, false},
};

INSTANTIATE_TEST_SUITE_P(Shared, AdaptiveErrorRates, ::testing::ValuesIn(kErrorCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& p) { return p.param.name; });
