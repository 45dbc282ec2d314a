// A test model (under tests/data) and its feature-adaptive or uniform tables, built in process
// the way limn-classify | limn-tables builds them, for tests that drive lib/render directly.
#pragma once

#include "mesh/import.h"
#include "subdiv/tables.h"
#include "test_support.h"
#include "topology/features.h"

#include "render/camera.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>

namespace limn::test {

struct ModelTables {
    Mesh mesh;
    Tables tables;
};

// Tables of `mesh` built in process (feature-adaptive, or uniform).
inline ModelTables buildMeshTables(Mesh mesh, int depth, bool uniform = false) {
    Warnings w;
    ModelTables b;
    b.mesh = std::move(mesh);
    TablesOptions o;
    o.depth = depth;
    o.uniform = uniform;
    b.tables = buildTables(b.mesh, resolveSchemeOptions(b.mesh.tags, {}), o, w);
    return b;
}

inline ModelTables buildModelTables(const std::string& model, int depth, bool uniform = false) {
    Warnings w;
    return buildMeshTables(importMeshFile(modelPath(model).string(), w), depth, uniform);
}

// The paper's demo layout (issue 11): a UV sphere of 16 segments x 16 rings (242 vertices) of
// radius r at the origin, triangle fans at the poles, faces outward.
inline Mesh paperSphere(double r) {
    Mesh m;
    const int S = 16, R = 16;
    m.positions.push_back({0, r, 0});
    for (int i = 1; i < R; ++i)
        for (int j = 0; j < S; ++j) {
            const double th = M_PI * i / R, ph = 2 * M_PI * j / S;
            m.positions.push_back({r * std::sin(th) * std::cos(ph), r * std::cos(th), -r * std::sin(th) * std::sin(ph)});
        }
    m.positions.push_back({0, -r, 0});
    auto idx = [&](int i, int j) { return uint32_t(1 + (i - 1) * S + (j % S)); };
    auto face = [&](std::initializer_list<uint32_t> v) { m.addFace(std::span<const uint32_t>(v.begin(), v.size())); };
    for (int j = 0; j < S; ++j) face({0, idx(1, j), idx(1, j + 1)});
    for (int i = 1; i + 1 < R; ++i)
        for (int j = 0; j < S; ++j) face({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)});
    const uint32_t last = uint32_t(m.positions.size() - 1);
    for (int j = 0; j < S; ++j) face({idx(R - 1, j), last, idx(R - 1, j + 1)});
    return m;
}

// A view from azimuth/elevation (degrees) at `distance` bounding radii from the control points'
// box centre, looking at it; distance 0 keeps the default framing.
inline void orbitView(render::ViewSpec& view, const Mesh& mesh, double azimuth, double elevation, double distance) {
    view.azimuthDeg = azimuth, view.elevationDeg = elevation;
    if (distance <= 0) return;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::dvec3 c = 0.5 * (lo + hi);
    const double R = 0.5 * glm::length(hi - lo), az = glm::radians(azimuth), el = glm::radians(elevation);
    view.target = c;
    view.eye = c + distance * R * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
}

} // namespace limn::test
