#include "blend/blend_surface.h"

#include "base/error.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace limn::blend {

void requireManifold(const Mesh& mesh, const Topology& topo) {
    (void)mesh;
    for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
        if (!topo.edgeIsNonManifold(e)) continue;
        auto [a, b] = topo.edgeVertices(e);
        std::string name = "edge (" + std::to_string(a) + "," + std::to_string(b) + ")";
        if (topo.edgeFaceCount(e) > 2)
            throwBadInput(name + " is non-manifold: " + std::to_string(topo.edgeFaceCount(e)) +
                          " faces share it; blending surfaces need a 2-manifold mesh");
        throwBadInput(name + " is used in the same direction by both of its faces: the mesh is "
                             "not consistently oriented");
    }
    for (uint32_t v = 0; v < topo.vertexCount(); ++v)
        if (topo.vertexIsNonManifold(v))
            throwBadInput("vertex " + std::to_string(v) +
                          " is non-manifold: several separate fans of faces meet there");
}

void requireQuads(const Mesh& mesh) {
    for (size_t f = 0; f < mesh.faceCount(); ++f)
        if (mesh.faceSize(f) != 4)
            throwBadInput("face " + std::to_string(f) + " has " +
                          std::to_string(mesh.faceSize(f)) +
                          " corners; blending surfaces need a quad mesh");
}

BlendSurface buildBlendSurface(const Mesh& mesh, const Topology& topo, const BlendOptions& options) {
    requireManifold(mesh, topo);
    requireQuads(mesh);
    BlendSurface s;
    s.weights = options.weights;
    s.chartType = options.chart;
    const uint32_t V = topo.vertexCount(), F = topo.faceCount();
    s.faces.resize(F);
    for (uint32_t f = 0; f < F; ++f) {
        auto vs = mesh.face(f);
        s.faces[f].vertex = {vs[0], vs[1], vs[2], vs[3]};
        s.faces[f].ring = {kNone, kNone, kNone, kNone};
    }
    s.vertices.resize(V);
    LocalSurfaceFitter fitter;
    std::vector<uint32_t> ring;
    std::vector<glm::dvec3> points;
    for (uint32_t v = 0; v < V; ++v) {
        BlendVertex& bv = s.vertices[v];
        bv.coef = {};
        bv.coef[0] = mesh.positions[v];
        topo.vertexRing(v, ring); // counter-clockwise; boundary fans start at the boundary (A.2)
        if (ring.empty()) {       // used by no face: never evaluated
            bv.chart = Chart{0, VertexKind::Interior, 0, 0, 0};
            continue;
        }
        const uint32_t k = static_cast<uint32_t>(ring.size());
        VertexKind kind = !topo.vertexIsBoundary(v) ? VertexKind::Interior
                          : k == 1                  ? VertexKind::Corner
                                                    : VertexKind::Boundary;
        bv.chart = makeChart(k, kind, options.chart);
        points.clear();
        for (uint32_t j = 0; j < k; ++j) {
            uint32_t h = ring[j];
            s.faces[topo.face(h)].ring[topo.cornerIndex(h)] = j;
            points.push_back(mesh.positions[topo.vertex(topo.next(h))]);             // e_j
            points.push_back(mesh.positions[topo.vertex(topo.next(topo.next(h)))]);  // d_j
        }
        if (kind != VertexKind::Interior)
            points.push_back(mesh.positions[topo.vertex(topo.prev(ring.back()))]); // c_{i−1}
        bv.coef = fitter.fit(bv.chart, mesh.positions[v], points);
    }
    return s;
}

std::array<double, 4> cornerWeights(WeightKind kind, double u, double v) {
    std::array<double, 4> w{};
    for (uint32_t i = 0; i < 4; ++i) {
        glm::dvec2 st = cornerFromFace(i, u, v);
        w[i] = hermiteStep(kind, st.x).h * hermiteStep(kind, st.y).h;
    }
    return w;
}

SurfaceSample evaluateBlendSurface(const BlendSurface& surface, uint32_t face, double u, double v) {
    const BlendFace& bf = surface.faces[face];
    glm::dvec3 S(0.0), Du(0.0), Dv(0.0);
    double W = 0, dWu = 0, dWv = 0;
    int atVertex = -1;
    for (uint32_t i = 0; i < 4; ++i) {
        const BlendVertex& bv = surface.vertices[bf.vertex[i]];
        glm::dvec2 st = cornerFromFace(i, u, v);
        Mat2 Ji = cornerJacobian(i);
        // w = h(s)h(t) (E3); its gradient in (u,v) is the row (h'(s)h(t), h(s)h'(t)) · J_i.
        StepValue hs = hermiteStep(surface.weights, st.x), ht = hermiteStep(surface.weights, st.y);
        double w = hs.h * ht.h;
        double ws = hs.dh * ht.h, wt = hs.h * ht.dh;
        double wu = ws * Ji.m00 + wt * Ji.m10, wv = ws * Ji.m01 + wt * Ji.m11;
        LocalValue L;
        if (std::hypot(st.x, st.y) < kVertexEpsilon) {
            atVertex = static_cast<int>(i);
            L = evaluateLocalSurface(bv.coef, {0, 0});
            L.dx = L.dy = glm::dvec3(0.0); // χ has no derivative at the vertex; see below
        } else {
            ChartValue z = chartMap(bv.chart, bf.ring[i], st.x, st.y);
            L = evaluateLocalSurface(bv.coef, z.z);
            Mat2 K = z.jacobian * Ji; // ∂(x,y)/∂(u,v)
            glm::dvec3 Lu = L.dx * K.m00 + L.dy * K.m10, Lv = L.dx * K.m01 + L.dy * K.m11;
            L.dx = Lu;
            L.dy = Lv;
        }
        S += w * L.value;
        W += w;
        dWu += wu;
        dWv += wv;
        Du += wu * L.value + w * L.dx;
        Dv += wv * L.value + w * L.dy;
    }
    // E1's normalization and the quotient rule; a no-op when W == 1 (A.4), kept as a guard.
    S /= W;
    Du = (Du - dWu * S) / W;
    Dv = (Dv - dWv * S) / W;
    glm::dvec3 n;
    if (atVertex >= 0) {
        // The true limit at the vertex (A.6): the other weights vanish with their gradients.
        const Coefficients& c = surface.vertices[bf.vertex[atVertex]].coef;
        n = glm::cross(c[coefficientIndex(1, 0)], c[coefficientIndex(0, 1)]);
    } else {
        n = glm::cross(Du, Dv);
    }
    double len = glm::length(n);
    n = len > 0 && std::isfinite(len) ? n / len : glm::dvec3(0.0);
    return {S, Du, Dv, n};
}

} // namespace limn::blend
