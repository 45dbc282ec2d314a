// limn-render on blending surfaces, run as users run it (limn-classify | limn-blend | limn-render
// --mesh-out), on the machine's Vulkan device with validation on. The expected values come from
// lib/blend's CPU evaluator (f64, written independently of the GLSL), fed the f32 coefficients of
// the very BLND chunk the tool rendered, so the comparison measures the GPU's arithmetic alone.
#include "blend/blend_chunk.h"
#include "blend/blend_surface.h"
#include "container/container.h"
#include "drawn_ply.h"
#include "mesh/mesh_chunks.h"
#include "mesh/obj.h"
#include "image/srgb_image.h"
#include "test_meshes.h"
#include "test_support.h"
#include "topology/topology.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <sstream>

using namespace limn;
using namespace limn::test;

namespace {

// A shared model ("quad/spot_control_mesh.obj") or a generated one ("bipyramid:5", "fan:6").
std::string inputObj(const ScratchDir& dir, const std::string& model) {
    auto colon = model.find(':');
    if (colon == std::string::npos) return modelPath(model).string();
    int n = std::stoi(model.substr(colon + 1));
    Mesh m = model.rfind("bipyramid", 0) == 0 ? blendtest::bipyramid(n) : blendtest::fanDisk(n);
    auto path = dir / "generated.obj";
    writeFile(path, writeObj(m));
    return path.string();
}

// classify | blend ARGS -> in.limn
std::string makeBlendContainer(const ScratchDir& dir, const std::string& model,
                               const std::vector<std::string>& blendArgs) {
    const std::string limn = (dir / "in.limn").string();
    auto r = run({tool("limn-classify").string(), inputObj(dir, model), "-o", limn});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> args = {tool("limn-blend").string(), limn, "-q", "-o", limn};
    args.insert(args.end(), blendArgs.begin(), blendArgs.end());
    r = run(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return limn;
}

struct Loaded {
    Mesh mesh;
    blend::BlendSurface surface;
};
Loaded load(const std::string& limn) {
    auto bytes = readBytes(limn);
    Container c = parseContainer(bytes);
    Loaded l;
    l.mesh = loadMesh(c);
    l.surface = blend::loadBlendSurface(c, l.mesh);
    return l;
}

glm::dvec3 position(const PlyVertex& v) {
    return {v.p[0], v.p[1], v.p[2]};
}
glm::dvec3 normal(const PlyVertex& v) {
    return {v.n[0], v.n[1], v.n[2]};
}

// The same surface point seen from the face across the edge (A.1): face f's edge c runs
// c_c -> c_{c+1} at fraction τ, the twin runs back at 1 − τ. Returns false off edges, at corners
// and on the boundary.
bool acrossEdge(const Topology& topo, uint32_t f, double u, double v, uint32_t& g, double& gu,
                double& gv) {
    const bool onU = u == 0 || u == 1, onV = v == 0 || v == 1;
    if (onU == onV) return false; // interior or corner
    uint32_t c;
    double tau;
    if (v == 0)
        c = 0, tau = u;
    else if (u == 1)
        c = 1, tau = v;
    else if (v == 1)
        c = 2, tau = 1 - u;
    else
        c = 3, tau = 1 - v;
    uint32_t t = topo.twin(topo.faceHalfedge(f) + c);
    if (t == kNone) return false;
    g = topo.face(t);
    glm::dvec2 uv = blend::faceFromCorner(topo.cornerIndex(t), 1 - tau, 0);
    gu = uv.x, gv = uv.y;
    return true;
}

// How much f32 rounding can turn the unit normal normalize(S_u × S_v): the blend sums face-sized
// terms (relative to the face's first corner, blend_eval.glsl), so relative errors of about ε·ℓ
// in S_u and S_v, ℓ the face's size, turn the normal by about
//     κ·ε,  κ = ℓ·(1/|S_u| + 1/|S_v|) / sin∠(S_u, S_v).
// At a vertex the normal is c_10 × c_01 (A.6), so κ takes those. κ is large where a derivative
// nearly vanishes or the two nearly align: the folds on coarse thin features (docs/blend.md).
double normalCondition(const Loaded& in, uint32_t f, double u, double v,
                       const blend::SurfaceSample& ref) {
    auto corners = in.mesh.face(f);
    double ell = 0;
    for (uint32_t k = 1; k < 4; ++k)
        ell = std::max(ell,
                       glm::length(in.mesh.positions[corners[k]] - in.mesh.positions[corners[0]]));
    glm::dvec3 a = ref.du, b = ref.dv;
    if ((u == 0 || u == 1) && (v == 0 || v == 1)) {
        const uint32_t corner = u == 0 ? (v == 0 ? 0 : 3) : (v == 0 ? 1 : 2);
        const auto& coef = in.surface.vertices[corners[corner]].coef;
        a = coef[blend::coefficientIndex(1, 0)];
        b = coef[blend::coefficientIndex(0, 1)];
    }
    const double sinAngle = glm::length(glm::cross(a, b)) / (glm::length(a) * glm::length(b));
    return ell * (1 / glm::length(a) + 1 / glm::length(b)) / sinAngle;
}
// The normal must match to 1e-5 where it is well conditioned (κ ≤ 2: derivatives of the face's
// size, at a good angle), and to 1e-5·κ/2 beyond. Measured on lavapipe over every case below: at
// most 45·2⁻²⁴·κ ≈ 2.7e-6·κ, above 1e-5 at 207 of spot's 187,394 points (all κ > 6).
double normalTolerance(double kappa) {
    return 1e-5 * std::max(1.0, kappa / 2);
}

struct Stats {
    double position = 0, normal = 0, worstRatio = 0, acrossPosition = 0, acrossNormal = 0;
    size_t over = 0, across = 0;
};

struct Case {
    std::string name, model;
    std::vector<std::string> blendArgs;
    int grid = 16;
    std::string eval = "compute";
    bool closed = true;
};

class BlendRender : public ::testing::TestWithParam<Case> {};

TEST_P(BlendRender, MeshOutIsTheCpuSurfaceWatertightAndContinuous) {
    const Case& c = GetParam();
    ScratchDir dir;
    const std::string limn = makeBlendContainer(dir, c.model, c.blendArgs);
    const std::string ply = (dir / "drawn.ply").string();
    auto r = run({tool("limn-render").string(), limn, "--size", "64x48", "--validate", "-v",
                  "--grid", std::to_string(c.grid), "--eval", c.eval, "--mesh-out", ply, "-o",
                  (dir / "image.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("validation: 0 errors"), std::string::npos) << r.err;
    const Drawn drawn = parsePly(readFile(ply));
    const Loaded in = load(limn);
    const Topology topo = blendtest::topologyOf(in.mesh);
    const double diag = blendtest::bboxDiagonal(in.mesh);
    const size_t K = size_t(c.grid), F = in.mesh.faceCount();

    // One vertex per surface point: mesh vertices, (K−1) per edge, (K−1)² per face.
    EXPECT_EQ(drawn.vertices.size(),
              in.mesh.vertexCount() + topo.edgeCount() * (K - 1) + F * (K - 1) * (K - 1));
    EXPECT_EQ(drawn.triangles.size(), F * K * K * 2);

    // Positions and normals: the CPU evaluator at the vertex's own (ptex = face, u, v).
    Stats st;
    for (const PlyVertex& v : drawn.vertices) {
        ASSERT_GE(v.ptex, 0);
        ASSERT_LT(size_t(v.ptex), F);
        const uint32_t f = uint32_t(v.ptex);
        // (u, v) are grid parameters i/K exactly as f32 holds them.
        for (float x : v.uv) EXPECT_EQ(x, float(std::lround(double(x) * double(K))) / float(K));
        auto ref = blend::evaluateBlendSurface(in.surface, f, v.uv[0], v.uv[1]);
        st.position = std::max(st.position, glm::length(position(v) - ref.position) / diag);
        const double e = glm::length(normal(v) - ref.normal);
        const double kappa = normalCondition(in, f, v.uv[0], v.uv[1], ref);
        st.normal = std::max(st.normal, e);
        st.worstRatio = std::max(st.worstRatio, e / (0x1p-24 * kappa));
        st.over += e > 1e-5;
        EXPECT_LE(e, normalTolerance(kappa))
            << "face " << f << " (" << v.uv[0] << ", " << v.uv[1] << "), condition " << kappa;
        // Continuity across shared edges: with one owner a shared point has one normal, so the
        // drawn normal is compared with the CPU surface evaluated from the *other* face.
        uint32_t g;
        double gu, gv;
        if (acrossEdge(topo, f, v.uv[0], v.uv[1], g, gu, gv)) {
            auto other = blend::evaluateBlendSurface(in.surface, g, gu, gv);
            st.acrossPosition =
                std::max(st.acrossPosition, glm::length(position(v) - other.position) / diag);
            st.acrossNormal =
                std::max(st.acrossNormal, blendtest::angleDegrees(normal(v), other.normal));
            ++st.across;
        }
    }
    EXPECT_LE(st.position, 1e-5) << "position error / bbox diagonal";
    if (K > 1) {
        EXPECT_GT(st.across, 0u);
    }
    EXPECT_LE(st.acrossPosition, 1e-5);
    EXPECT_LE(st.acrossNormal, 0.5) << "degrees between the drawn normal and the other face's";
    std::cout << c.name << ": position error " << st.position << " of the diagonal; normal error "
              << st.normal << ", above 1e-5 at " << st.over << " of " << drawn.vertices.size()
              << " points, error <= " << st.worstRatio << " * 2^-24 * condition; across "
              << st.across << " edge points " << st.acrossNormal << " deg\n";

    // Watertight: weld by exact position; every edge of a closed surface has two triangles.
    std::map<std::array<float, 3>, int> weld;
    std::vector<int> id(drawn.vertices.size());
    for (size_t i = 0; i < drawn.vertices.size(); ++i)
        id[i] = weld.try_emplace(
                        {drawn.vertices[i].p[0], drawn.vertices[i].p[1], drawn.vertices[i].p[2]},
                        int(weld.size()))
                    .first->second;
    EXPECT_EQ(weld.size(), drawn.vertices.size()) << "two surface points at the same position";
    std::map<std::pair<int, int>, int> edgeUse;
    for (const auto& tri : drawn.triangles)
        for (int k = 0; k < 3; ++k) {
            ASSERT_LT(size_t(tri[k]), drawn.vertices.size());
            int a = id[tri[k]], b = id[tri[(k + 1) % 3]];
            ASSERT_NE(a, b) << "a triangle collapsed when welded";
            ++edgeUse[{std::min(a, b), std::max(a, b)}];
        }
    size_t open = 0, over = 0;
    for (const auto& [e, n] : edgeUse) open += n == 1, over += n > 2;
    EXPECT_EQ(over, 0u);
    if (c.closed) {
        EXPECT_EQ(open, 0u) << "open edges after welding by exact position";
    } else {
        EXPECT_EQ(open, topo.boundaryEdgeCount() * K);
    }
}

const Case kCases[] = {
    {"spot", "quad/spot_control_mesh.obj", {"--quadrangulate"}},
    {"spot_vertex_stage", "quad/spot_control_mesh.obj", {"--quadrangulate"}, 5, "vertex"},
    {"spot_cc2_quintic_characteristic",
     "quad/spot_quadrangulated.obj",
     {"--weights", "quintic", "--chart", "characteristic"},
     4},
    {"blub", "quad/blub_control_mesh.obj", {"--quadrangulate"}, 8},
    {"torus", "quad/osd_catmark_torus.obj", {}, 16},
    {"torus_grid1", "quad/osd_catmark_torus.obj", {}, 1},
    {"cube_isodistance", "quad/osd_catmark_cube.obj", {"--chart", "isodistance"}, 7},
    {"xord_boundary", "quad/osd_catmark_xord_boundary.obj", {}, 8, "compute", false},
    {"bipyramid3", "bipyramid:3", {"--quadrangulate"}, 6},
    {"bipyramid5", "bipyramid:5", {"--quadrangulate"}, 6},
    {"bipyramid6", "bipyramid:6", {"--quadrangulate", "--weights", "quintic"}, 6},
    {"bipyramid7", "bipyramid:7", {"--quadrangulate", "--chart", "characteristic"}, 6},
    {"bipyramid8", "bipyramid:8", {"--quadrangulate"}, 6},
    {"fan7_boundary", "fan:7", {"--quadrangulate"}, 6, "compute", false},
};

INSTANTIATE_TEST_SUITE_P(Meshes, BlendRender, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

} // namespace
