#include "test_meshes.h"

#include "blend/chart.h"
#include "blend/quadrangulate.h"
#include "mesh/import.h"
#include "test_support.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace limn::blendtest {

namespace {
const double pi = std::numbers::pi;
void add(Mesh& m, std::initializer_list<uint32_t> f) {
    std::vector<uint32_t> v(f);
    m.addFace(v);
}
} // namespace

Mesh bipyramid(int n) {
    Mesh m;
    for (int i = 0; i < n; ++i)
        m.positions.push_back({std::cos(2 * pi * i / n), std::sin(2 * pi * i / n), 0.1 * (i % 2)});
    const uint32_t top = n, bottom = n + 1;
    m.positions.push_back({0, 0, 1.3});
    m.positions.push_back({0.05, 0, -1.1});
    for (int i = 0; i < n; ++i) {
        uint32_t a = i, b = (i + 1) % n;
        add(m, {a, b, top});
        add(m, {b, a, bottom});
    }
    return m;
}

Mesh fanDisk(int n) {
    Mesh m;
    m.positions.push_back({0.02, -0.03, 0});
    for (int i = 0; i < n; ++i) {
        double r = 1 + 0.1 * std::sin(3.0 * i);
        m.positions.push_back({r * std::cos(2 * pi * i / n), r * std::sin(2 * pi * i / n), 0});
    }
    for (int i = 0; i < n; ++i) add(m, {0, uint32_t(1 + i), uint32_t(1 + (i + 1) % n)});
    return m;
}

Mesh torus(int nu, int nv, double R, double r) {
    Mesh m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            double a = 2 * pi * i / nu, b = 2 * pi * j / nv;
            m.positions.push_back({(R + r * std::cos(b)) * std::cos(a),
                                   (R + r * std::cos(b)) * std::sin(a), r * std::sin(b)});
        }
    auto id = [&](int i, int j) { return uint32_t((i % nu) * nv + (j % nv)); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) add(m, {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    return m;
}

Mesh grid(int n, double (*height)(double, double)) {
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) m.positions.push_back({double(i), double(j), height(i, j)});
    auto id = [&](int i, int j) { return uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) add(m, {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    return m;
}

Mesh loadModel(const std::string& relative) {
    Warnings w;
    return importMeshFile(test::modelPath(relative).string(), w);
}

Mesh loadTestData(const std::string& name) {
    Warnings w;
    return importMeshFile(std::string(LIMN_BLEND_TEST_DATA) + "/" + name, w);
}

Mesh quadrangulated(const Mesh& mesh) { return blend::quadrangulateLinear(mesh, topologyOf(mesh)); }

namespace {
// Rotation by 0.7 rad about (1,2,2)/3 (Rodrigues), then a translation.
glm::dvec3 rotate(const glm::dvec3& p) {
    glm::dvec3 k(1.0 / 3, 2.0 / 3, 2.0 / 3);
    double c = std::cos(0.7), s = std::sin(0.7);
    return p * c + glm::cross(k, p) * s + k * glm::dot(k, p) * (1 - c);
}
} // namespace

Mesh rigidlyMoved(const Mesh& mesh) {
    Mesh m = mesh;
    for (auto& p : m.positions) p = rotate(p) + glm::dvec3(0.3, -1.2, 2.0);
    return m;
}
glm::dvec3 rigidNormal() { return rotate({0, 0, 1}); }

Topology topologyOf(const Mesh& m) {
    return Topology(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
}

double bboxDiagonal(const Mesh& m) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return glm::length(hi - lo);
}

double angleDegrees(const glm::dvec3& a, const glm::dvec3& b) {
    // atan2 form: accurate for tiny angles, where acos of a dot product is not.
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180 / pi;
}

Continuity edgeContinuity(const blend::BlendSurface& s, const Topology& topo, int samples) {
    Continuity c;
    for (uint32_t h = 0; h < topo.halfedgeCount(); ++h) {
        uint32_t t = topo.twin(h);
        if (t == kNone || t < h) continue;
        ++c.edges;
        for (int n = 0; n < samples; ++n) {
            double tau = (n + 0.5) / samples;
            // In face(h) the edge a→b is the s-edge of corner a: (s,t) = (τ, 0); in face(t) it is
            // the s-edge of corner b running back: (1 − τ, 0)  (A.1).
            glm::dvec2 uv1 = blend::faceFromCorner(topo.cornerIndex(h), tau, 0);
            glm::dvec2 uv2 = blend::faceFromCorner(topo.cornerIndex(t), 1 - tau, 0);
            auto a = blend::evaluateBlendSurface(s, topo.face(h), uv1.x, uv1.y);
            auto b = blend::evaluateBlendSurface(s, topo.face(t), uv2.x, uv2.y);
            c.positionJump = std::max(c.positionJump, glm::length(a.position - b.position));
            c.normalJump = std::max(c.normalJump, angleDegrees(a.normal, b.normal));
        }
    }
    return c;
}

double maxInterpolationError(const blend::BlendSurface& s, const Mesh& mesh) {
    double err = 0;
    const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (uint32_t i = 0; i < 4; ++i) {
            auto p = blend::evaluateBlendSurface(s, f, corners[i][0], corners[i][1]);
            err = std::max(err, glm::length(p.position - mesh.positions[mesh.face(f)[i]]));
        }
    return err;
}

double maxVertexNormalAngle(const blend::BlendSurface& s, const Topology& topo, double d) {
    double worst = 0;
    for (uint32_t h = 0; h < topo.halfedgeCount(); ++h) {
        uint32_t f = topo.face(h), i = topo.cornerIndex(h);
        glm::dvec2 at = blend::faceFromCorner(i, 0, 0), near = blend::faceFromCorner(i, d, d);
        auto n0 = blend::evaluateBlendSurface(s, f, at.x, at.y).normal;
        auto n1 = blend::evaluateBlendSurface(s, f, near.x, near.y).normal;
        worst = std::max(worst, angleDegrees(n0, n1));
    }
    return worst;
}

} // namespace limn::blendtest
