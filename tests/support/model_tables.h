// A test model (under tests/data) and its feature-adaptive or uniform tables, built in process
// the way limn-classify | limn-tables builds them, for tests that drive lib/render directly.
#pragma once

#include "mesh/import.h"
#include "paper_sphere.h"
#include "subdiv/tables.h"
#include "test_support.h"
#include "topology/features.h"

#include "render/camera.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
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
