// The blending surface on generated and real meshes (math.md A.11 checks ), and
// agreement with the Python prototype of math.md (../shared/docs/checks/blend.py).
#include "base/error.h"
#include "blend/blend_chunk.h"
#include "blend/blend_surface.h"
#include "blend/quadrangulate.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

using namespace limn;
using namespace limn::blend;
using namespace limn::blendtest;

namespace {

struct PrototypeSample {
    uint32_t face;
    double u, v;
    double position[3], normal[3];
};
struct PrototypeCase {
    const char *mesh, *chart, *weights;
    std::vector<PrototypeSample> samples;
};
#include "prototype_reference.inc"

BlendSurface build(const Mesh& m, WeightKind w = WeightKind::Cubic,
                   ChartType c = ChartType::Conformal) {
    return buildBlendSurface(m, topologyOf(m), {w, c});
}

} // namespace

// Agreement with the prototype at 21 samples per case (positions and normals it printed), and at
// 3 samples on spot as limn quadrangulates it: face 241, on a horn, is one where the quadratic
// local surfaces fold over (its normal points into the cow), in the prototype as here.
TEST(Surface, AgreesWithPythonPrototype) {
    for (const PrototypeCase* pc : {&kProto_disk_conformal_cubic, &kProto_disk_conformal_quintic,
                                    &kProto_ball_conformal_cubic, &kProto_ball_charmap_quintic,
                                    &kProto_spot_conformal_cubic}) {
        Mesh m = std::string(pc->mesh) == "spot"
                     ? quadrangulated(loadModel("quad/spot_control_mesh.obj"))
                     : loadTestData(std::string("proto_") + pc->mesh + ".obj");
        BlendSurface s = build(m, std::string(pc->weights) == "quintic" ? WeightKind::Quintic : WeightKind::Cubic,
                               std::string(pc->chart) == "charmap" ? ChartType::CharacteristicMap
                                                                   : ChartType::Conformal);
        for (const auto& ps : pc->samples) {
            auto got = evaluateBlendSurface(s, ps.face, ps.u, ps.v);
            glm::dvec3 p(ps.position[0], ps.position[1], ps.position[2]);
            glm::dvec3 n(ps.normal[0], ps.normal[1], ps.normal[2]);
            EXPECT_LT(glm::length(got.position - p), 1e-11)
                << pc->mesh << " " << pc->chart << " face " << ps.face << " (" << ps.u << "," << ps.v << ")";
            EXPECT_LT(glm::length(got.normal - n), 1e-9)
                << pc->mesh << " " << pc->chart << " face " << ps.face << " (" << ps.u << "," << ps.v << ")";
        }
    }
}

// A-9, by hand: on a regular grid every local surface is the biquadratic Lagrange interpolant of
// its vertex's 3×3 neighbourhood, and at a face centre all four weights are h(½)² = ¼. With the
// 1D Lagrange weights at offset ½ from the middle node (−1/8, 3/4, 3/8):
//     S(½,½) = ¼ Σ_corners Σ_ab l_a l_b P(corner + (a,b)).
TEST(Surface, FaceCentreOfRegularGridByHand) {
    Mesh m = grid(3, [](double x, double y) { return std::sin(1.3 * x) * std::cos(0.7 * y) + 0.1 * x * x * y; });
    const uint32_t centreFace = 4; // the middle one of the 3×3 faces: corners (1,1) (2,1) (2,2) (1,2)
    auto P = [&](int i, int j) { return m.positions[i * 4 + j]; };
    auto lag = [](int node, double sign) { // l_node(½·sign), nodes −1, 0, 1
        const double w[3] = {-0.125, 0.75, 0.375};
        return w[sign > 0 ? node + 1 : 1 - node];
    };
    glm::dvec3 expect(0.0);
    const int corners[4][2] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
    for (auto [ci, cj] : corners) {
        double sx = ci == 1 ? 1 : -1, sy = cj == 1 ? 1 : -1; // direction of the face centre
        for (int a = -1; a <= 1; ++a)
            for (int b = -1; b <= 1; ++b) expect += 0.25 * lag(a, sx) * lag(b, sy) * P(ci + a, cj + b);
    }
    for (WeightKind w : {WeightKind::Cubic, WeightKind::Quintic}) {
        auto got = evaluateBlendSurface(build(m, w), centreFace, 0.5, 0.5);
        EXPECT_LT(glm::length(got.position - expect), 1e-13);
    }
}

// a regular grid whose heights are a biquadratic is reproduced exactly on faces with four
// interior corners.
TEST(Surface, RegularGridReproducesBiquadratic) {
    auto f = [](double x, double y) { return 0.3 - 0.2 * x + 0.1 * y + 0.05 * x * x - 0.07 * x * y + 0.02 * x * x * y * y - 0.03 * y * y; };
    Mesh m = grid(6, f);
    BlendSurface s = build(m, WeightKind::Quintic, ChartType::CharacteristicMap);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(0, 1);
    double err = 0;
    for (uint32_t face = 0; face < m.faceCount(); ++face) {
        glm::dvec3 c0 = m.positions[m.face(face)[0]];
        if (c0.x < 1 || c0.y < 1 || c0.x > 4 || c0.y > 4) continue; // a corner on the boundary
        for (int n = 0; n < 20; ++n) {
            double u = U(rng), v = U(rng);
            glm::dvec3 p = evaluateBlendSurface(s, face, u, v).position;
            err = std::max(err, glm::length(p - glm::dvec3(c0.x + u, c0.y + v, f(c0.x + u, c0.y + v))));
        }
    }
    EXPECT_LT(err, 1e-12);
}

// a planar control mesh (moved rigidly off z = 0) with extraordinary vertices of valence 3
// to 8 and boundary vertices with k = 1, 2, 3 gives a planar surface with the plane's normal.
TEST(Surface, PlanarMeshGivesPlanarSurface) {
    std::vector<Mesh> meshes;
    for (int n = 3; n <= 8; ++n) meshes.push_back(quadrangulated(fanDisk(n)));
    Mesh disk = loadTestData("proto_disk.obj"); // valences 3..6, boundary k = 1, 2
    for (auto& p : disk.positions) p.z = 0;
    meshes.push_back(disk);
    const glm::dvec3 n0 = rigidNormal();
    for (const Mesh& flat : meshes) {
        Mesh m = rigidlyMoved(flat);
        const double d0 = glm::dot(m.positions[0], n0), diag = bboxDiagonal(m);
        for (WeightKind w : {WeightKind::Cubic, WeightKind::Quintic}) {
            BlendSurface s = build(m, w);
            double dist = 0, angle = 0;
            for (uint32_t f = 0; f < m.faceCount(); ++f)
                for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
                    for (double v : {0.0, 0.31, 0.5, 0.91, 1.0}) {
                        auto p = evaluateBlendSurface(s, f, u, v);
                        dist = std::max(dist, std::abs(glm::dot(p.position, n0) - d0));
                        angle = std::max(angle, angleDegrees(p.normal, n0));
                    }
            EXPECT_LT(dist, 1e-13 * diag) << m.vertexCount() << " vertices";
            EXPECT_LT(angle, 1e-6) << m.vertexCount() << " vertices";
        }
    }
}

namespace {

struct RealCase {
    std::string name;
    Mesh mesh;
};

std::vector<RealCase> realMeshes() {
    std::vector<RealCase> out;
    out.push_back({"spot (quadrangulated)", quadrangulated(loadModel("quad/spot_control_mesh.obj"))});
    out.push_back({"spot after 2 Catmull-Clark steps", loadModel("quad/spot_quadrangulated.obj")});
    out.push_back({"blub (quadrangulated)", quadrangulated(loadModel("quad/blub_control_mesh.obj"))});
    out.push_back({"osd torus", loadModel("quad/osd_catmark_torus.obj")});
    out.push_back({"generated torus 12x7", torus(12, 7, 2.0, 0.6)});
    out.push_back({"osd toroidal tet (valence 6, genus 3)", loadModel("quad/osd_catmark_toroidal_tet.obj")});
    out.push_back({"osd cube (valence 3)", loadModel("quad/osd_catmark_cube.obj")});
    out.push_back({"osd xord boundary", loadModel("quad/osd_catmark_xord_boundary.obj")});
    out.push_back({"proto ball", loadTestData("proto_ball.obj")});
    for (int n = 3; n <= 8; ++n)
        out.push_back({"bipyramid " + std::to_string(n) + " (valence " + std::to_string(n) + ")",
                       quadrangulated(bipyramid(n))});
    return out;
}

} // namespace

// on real and generated meshes, both weight kinds, conformal and characteristic
// charts: the surface interpolates the control vertices, positions and normals agree across every
// shared edge (≤ 1e-6 of the bounding-box diagonal, < 0.5°), and normals near every vertex
// converge to the vertex normal c_10 × c_01.
TEST(Surface, RealMeshesInterpolateAndAreContinuous) {
    for (const RealCase& rc : realMeshes()) {
        const Mesh& m = rc.mesh;
        Topology topo = topologyOf(m);
        const double diag = bboxDiagonal(m);
        for (auto [w, c] : {std::pair{WeightKind::Cubic, ChartType::Conformal},
                            std::pair{WeightKind::Quintic, ChartType::CharacteristicMap}}) {
            BlendSurface s = build(m, w, c);
            EXPECT_LE(maxInterpolationError(s, m), 1e-14 * diag) << rc.name;
            Continuity cont = edgeContinuity(s, topo, 5);
            EXPECT_GT(cont.edges, 0u);
            EXPECT_LE(cont.positionJump, 1e-6 * diag) << rc.name;
            EXPECT_LT(cont.normalJump, 0.5) << rc.name;
            // What double precision actually gives (math.md A.11: 9e-16, 2e-6°).
            EXPECT_LE(cont.positionJump, 1e-13 * diag) << rc.name;
            EXPECT_LT(cont.normalJump, 1e-4) << rc.name;
            EXPECT_LT(maxVertexNormalAngle(s, topo, 1e-7), 0.5) << rc.name;
        }
    }
}

// near an extraordinary vertex the normal converges to the vertex normal like distance^q.
TEST(Surface, NormalsConvergeAtExtraordinaryVertices) {
    for (int n : {3, 5, 8}) {
        Mesh m = quadrangulated(bipyramid(n));
        Topology topo = topologyOf(m);
        BlendSurface s = build(m);
        // q = 4/n, so 4 decades closer shrink the angle by at least 10^(4·4/8)/… ≥ 10×.
        double far = maxVertexNormalAngle(s, topo, 1e-3), near = maxVertexNormalAngle(s, topo, 1e-7);
        EXPECT_LT(near, 0.1 * far) << n;
        EXPECT_LT(near, 0.5) << n;
    }
}

// analytic derivatives against central differences, away from the vertices.
TEST(Surface, AnalyticDerivativesMatchCentralDifferences) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> U(0.01, 0.99);
    for (const RealCase& rc : realMeshes()) {
        const Mesh& m = rc.mesh;
        for (auto [w, c] : {std::pair{WeightKind::Cubic, ChartType::Conformal},
                            std::pair{WeightKind::Quintic, ChartType::Isodistance}}) {
            BlendSurface s = build(m, w, c);
            double worst = 0;
            for (int n = 0; n < 60; ++n) {
                uint32_t f = static_cast<uint32_t>(rng() % m.faceCount());
                double u = U(rng), v = U(rng), e = 1e-6;
                auto p = evaluateBlendSurface(s, f, u, v);
                auto fu = (evaluateBlendSurface(s, f, u + e, v).position - evaluateBlendSurface(s, f, u - e, v).position) / (2 * e);
                auto fv = (evaluateBlendSurface(s, f, u, v + e).position - evaluateBlendSurface(s, f, u, v - e).position) / (2 * e);
                double scale = 1 + glm::length(p.du) + glm::length(p.dv);
                worst = std::max({worst, glm::length(fu - p.du) / scale, glm::length(fv - p.dv) / scale});
            }
            EXPECT_LT(worst, 1e-7) << rc.name;
        }
    }
}

// The surface's normals point the way the control faces do (meshes are counter-clockwise seen
// from outside): at every face centre the normal and the face's Newell normal agree. Spot after
// one linear step is the exception this construction has: on the horns the one-ring of a vertex
// wraps so far around that its biquadratic folds over (34 of 732 face centres flip, the Python
// prototype agrees, see AgreesWithPythonPrototype); two Catmull-Clark steps first remove them.
TEST(Surface, NormalsFaceOutward) {
    for (const RealCase& rc : realMeshes()) {
        const Mesh& m = rc.mesh;
        BlendSurface s = build(m);
        size_t flipped = 0;
        for (uint32_t f = 0; f < m.faceCount(); ++f) {
            auto vs = m.face(f);
            glm::dvec3 newell(0.0);
            for (size_t i = 0; i < 4; ++i)
                newell += glm::cross(m.positions[vs[i]], m.positions[vs[(i + 1) % 4]]);
            flipped += glm::dot(evaluateBlendSurface(s, f, 0.5, 0.5).normal, newell) <= 0;
        }
        EXPECT_EQ(flipped, rc.name == "spot (quadrangulated)" ? 34u : 0u) << rc.name;
    }
}

// What the GPU will see: coefficients rounded to f32 through BLND move the surface by a few f32
// ulps of the model size.
TEST(Surface, Float32CoefficientsStayClose) {
    Mesh m = quadrangulated(loadModel("quad/spot_control_mesh.obj"));
    BlendSurface s = build(m);
    BlendSurface f32 = decodeBlendChunk(encodeBlendChunk(s, 0)).surface;
    double worst = 0, angle = 0;
    for (uint32_t f = 0; f < m.faceCount(); ++f)
        for (double u : {0.1, 0.5, 0.9})
            for (double v : {0.2, 0.6}) {
                auto a = evaluateBlendSurface(s, f, u, v), b = evaluateBlendSurface(f32, f, u, v);
                worst = std::max(worst, glm::length(a.position - b.position));
                angle = std::max(angle, angleDegrees(a.normal, b.normal));
            }
    EXPECT_LT(worst, 1e-6 * bboxDiagonal(m));
    EXPECT_LT(angle, 1e-2);
}

TEST(Surface, RefusesNonQuadAndNonManifold) {
    Mesh tri = fanDisk(5);
    try {
        build(tri);
        FAIL();
    } catch (const limn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("face 0 has 3 corners"), std::string::npos) << e.what();
    }
    // Three quads sharing the edge (0,1).
    Mesh fin;
    fin.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, -1, 0}, {0, -1, 0}, {1, 0, 1}, {0, 0, 1}};
    fin.addFace(std::vector<uint32_t>{0, 1, 2, 3});
    fin.addFace(std::vector<uint32_t>{1, 0, 5, 4});
    fin.addFace(std::vector<uint32_t>{0, 1, 6, 7});
    try {
        build(fin);
        FAIL();
    } catch (const limn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("edge (0,1)"), std::string::npos) << e.what();
    }
    // Two quads touching at vertex 0 only (a bow tie).
    Mesh bow;
    bow.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {0, -1, 0}};
    bow.addFace(std::vector<uint32_t>{0, 1, 2, 3});
    bow.addFace(std::vector<uint32_t>{0, 4, 5, 6});
    try {
        build(bow);
        FAIL();
    } catch (const limn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 0 is non-manifold"), std::string::npos) << e.what();
    }
}

// A.0: the linear step keeps positions and UVs on the straight-line interpolation and gives the
// counts of the construction: V + E + F vertices, one quad per corner.
TEST(Quadrangulate, CountsPositionsAndUVs) {
    Mesh m = loadModel("quad/spot_control_mesh.obj");
    Topology topo = topologyOf(m);
    Mesh q = quadrangulateLinear(m, topo);
    EXPECT_EQ(q.vertexCount(), m.vertexCount() + topo.edgeCount() + m.faceCount());
    EXPECT_EQ(q.faceCount(), m.cornerCount());
    EXPECT_TRUE(isQuadMesh(q));
    validateMesh(q);
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        auto vs = m.face(f);
        auto uvs = m.faceUVs(f);
        glm::dvec3 centre(0.0);
        glm::dvec2 centreUV(0.0);
        for (size_t i = 0; i < vs.size(); ++i) {
            centre += m.positions[vs[i]];
            centreUV += m.uvs[uvs[i]];
        }
        centre /= double(vs.size());
        centreUV /= double(vs.size());
        for (size_t i = 0; i < vs.size(); ++i) {
            uint32_t child = m.faceOffsets[f] + static_cast<uint32_t>(i);
            auto cq = q.face(child);
            auto cu = q.faceUVs(child);
            size_t n = vs.size();
            EXPECT_EQ(cq[0], vs[i]);
            EXPECT_EQ(q.positions[cq[1]], (m.positions[vs[i]] + m.positions[vs[(i + 1) % n]]) * 0.5);
            EXPECT_LT(glm::length(q.positions[cq[2]] - centre), 1e-15);
            EXPECT_EQ(q.positions[cq[3]], (m.positions[vs[(i + n - 1) % n]] + m.positions[vs[i]]) * 0.5);
            EXPECT_EQ(q.uvs[cu[0]], m.uvs[uvs[i]]);
            EXPECT_EQ(q.uvs[cu[1]], (m.uvs[uvs[i]] + m.uvs[uvs[(i + 1) % n]]) * 0.5);
            EXPECT_LT(glm::length(q.uvs[cu[2]] - centreUV), 1e-15);
        }
    }
    // Manifold and consistently oriented, as the input.
    Topology qt = topologyOf(q);
    EXPECT_EQ(qt.nonManifoldEdgeCount(), 0u);
    EXPECT_EQ(qt.boundaryEdgeCount(), 0u);
}
