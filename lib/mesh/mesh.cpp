#include "mesh/mesh.h"

#include "base/cli.h"
#include "base/error.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace limn {

namespace {

// What float arithmetic on the GPU carries with room for squared lengths (3.4e38 and 1.2e-38).
constexpr double kMaxCoordinate = 1e18;
constexpr double kMinExtent = 1e-18;

} // namespace

MeshBox boundingBox(const Mesh& mesh) {
    MeshBox box;
    if (mesh.positions.empty()) return box;
    box.lo = box.hi = mesh.positions[0];
    for (const auto& p : mesh.positions) box.lo = glm::min(box.lo, p), box.hi = glm::max(box.hi, p);
    return box;
}

double MeshBox::diagonal() const { return glm::length(hi - lo); }

void validateMesh(const Mesh& m) {
    const size_t V = m.vertexCount();
    if (m.faceOffsets.empty() || m.faceOffsets.front() != 0 ||
        m.faceOffsets.back() != m.faceVertices.size())
        throwBadInput("face offsets are inconsistent with the corner list");
    if (V == 0) throwBadInput("the mesh has no vertices");
    if (m.faceCount() == 0) throwBadInput("the mesh has no faces");
    for (size_t v = 0; v < V; ++v) {
        const auto& p = m.positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throwBadInput("vertex " + std::to_string(v) + " has a non-finite position (NaN or Inf)");
        // The GPU computes in float and squares lengths (normals, projections): beyond 1e18 a
        // square overflows float's 3.4e38.
        if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinate)
            throwBadInput("vertex " + std::to_string(v) + " lies " +
                          cli::shortNumber(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)})) +
                          " from the origin, beyond the 1e18 that the GPU's float arithmetic "
                          "carries; scale the mesh down");
    }
    // A mesh whose extent float cannot resolve (1e-300) would render as a point or not at all.
    const auto [lo, hi] = boundingBox(m);
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double magnitude = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z),
                                       std::abs(hi.x), std::abs(hi.y), std::abs(hi.z)});
    if (extent < kMinExtent || (magnitude > 0 && extent < magnitude * 1e-6))
        throwBadInput("the mesh spans " + cli::shortNumber(extent) + " (at " + cli::shortNumber(magnitude) +
                      " from the origin); the GPU's float "
                      "arithmetic cannot resolve it: scale it up or move it to the origin");
    for (size_t f = 0; f < m.faceCount(); ++f) {
        if (m.faceOffsets[f + 1] < m.faceOffsets[f])
            throwBadInput("face offsets are not increasing at face " + std::to_string(f));
        auto face = m.face(f);
        if (face.size() < 3)
            throwBadInput("face " + std::to_string(f) + " has " + std::to_string(face.size()) +
                          " vertices; a face needs at least 3");
        auto degenerate = [&](uint32_t v) {
            throwBadInput("face " + std::to_string(f) + " is degenerate: it uses vertex " +
                          std::to_string(v) + " twice");
        };
        for (size_t i = 0; i < face.size(); ++i) {
            if (face[i] >= V)
                throwBadInput("face " + std::to_string(f) + " refers to vertex " +
                              std::to_string(face[i]) + " but there are only " +
                              std::to_string(V));
            if (face.size() <= 32)
                for (size_t j = 0; j < i; ++j)
                    if (face[j] == face[i]) degenerate(face[i]);
        }
        // A hostile 100k-gon must not cost 10^10 comparisons.
        if (face.size() > 32) {
            std::vector<uint32_t> sorted(face.begin(), face.end());
            std::sort(sorted.begin(), sorted.end());
            if (auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end())
                degenerate(*it);
        }
    }
    if (!m.uvIndices.empty()) {
        if (m.uvIndices.size() != m.faceVertices.size())
            throwBadInput("UV index count " + std::to_string(m.uvIndices.size()) +
                          " differs from the corner count " + std::to_string(m.cornerCount()));
        for (size_t c = 0; c < m.uvIndices.size(); ++c)
            if (m.uvIndices[c] >= m.uvs.size())
                throwBadInput("corner " + std::to_string(c) + " refers to UV " +
                              std::to_string(m.uvIndices[c]) + " but there are only " +
                              std::to_string(m.uvs.size()));
        for (size_t i = 0; i < m.uvs.size(); ++i) {
            if (!std::isfinite(m.uvs[i].x) || !std::isfinite(m.uvs[i].y))
                throwBadInput("UV " + std::to_string(i) + " is not finite (NaN or Inf)");
            // Same limit as positions: a UV of 1e39 is finite here but infinite in the GPU's float,
            // and the displaced surface would be NaN.
            const double far = std::max(std::abs(double(m.uvs[i].x)), std::abs(double(m.uvs[i].y)));
            if (far > kMaxCoordinate)
                throwBadInput("UV " + std::to_string(i) + " is " + cli::shortNumber(far) +
                              " from the origin, beyond the 1e18 that the GPU's float arithmetic carries");
        }
    }
    auto checkSharpness = [](float s, const std::string& what) {
        if (!std::isfinite(s) || s < 0)
            throwBadInput(what + " has sharpness " + std::to_string(s) +
                          "; it must be finite and >= 0");
    };
    for (size_t i = 0; i < m.tags.creases.size(); ++i) {
        const auto& c = m.tags.creases[i];
        std::string what = "crease tag " + std::to_string(i) + " (" + std::to_string(c.v0) + "," +
                           std::to_string(c.v1) + ")";
        if (c.v0 >= V || c.v1 >= V) throwBadInput(what + " refers to a vertex out of range");
        if (c.v0 == c.v1) throwBadInput(what + " joins a vertex to itself");
        checkSharpness(c.sharpness, what);
    }
    for (size_t i = 0; i < m.tags.corners.size(); ++i) {
        const auto& c = m.tags.corners[i];
        std::string what = "corner tag " + std::to_string(i) + " (vertex " +
                           std::to_string(c.vertex) + ")";
        if (c.vertex >= V) throwBadInput(what + " refers to a vertex out of range");
        checkSharpness(c.sharpness, what);
    }
    for (size_t i = 0; i < m.tags.holes.size(); ++i)
        if (m.tags.holes[i] >= m.faceCount())
            throwBadInput("hole tag " + std::to_string(i) + " refers to face " +
                          std::to_string(m.tags.holes[i]) + " but there are only " +
                          std::to_string(m.faceCount()));
    auto checkEnum = [](std::optional<uint8_t> v, uint8_t max, const char* what) {
        if (v && *v > max)
            throwBadInput(std::string(what) + " value " + std::to_string(*v) + " is out of range");
    };
    auto raw = [](const auto& o) -> std::optional<uint8_t> {
        if (!o) return std::nullopt;
        return static_cast<uint8_t>(*o);
    };
    checkEnum(raw(m.tags.boundary), 2, "boundary rule");
    checkEnum(raw(m.tags.fvar), 5, "face-varying rule");
    checkEnum(raw(m.tags.creaseMethod), 1, "crease method");
    checkEnum(raw(m.tags.triangles), 1, "triangle subdivision");
}

} // namespace limn
