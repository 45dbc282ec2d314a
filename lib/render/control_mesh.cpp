#include "render/control_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace limn::render {

std::vector<uint32_t> ptexFaceBase(const Mesh& mesh) {
    std::vector<uint32_t> base(mesh.faceCount());
    uint32_t next = 0;
    for (size_t f = 0; f < mesh.faceCount(); ++f) {
        base[f] = next;
        next += mesh.faceSize(f) == 4 ? 1 : mesh.faceSize(f);
    }
    return base;
}

std::vector<uint32_t> textureWords(const FloatImage* img) {
    if (!img) return {1, 1, 0xFFFFFFFFu};
    std::vector<uint32_t> w{img->width, img->height};
    for (size_t i = 0; i < size_t(img->width) * img->height; ++i) {
        uint32_t c = 0;
        for (uint32_t k = 0; k < 3; ++k) {
            // Grey (1 channel) and grey + alpha (2) are grey in R, G and B: channel 1 of a
            // two-channel image is its alpha, not a colour.
            const uint32_t source = img->channels < 3 ? 0 : k;
            float v = img->values[i * img->channels + source];
            c |= uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)) << (8 * k);
        }
        w.push_back(c | 0xFF000000u);
    }
    return w;
}

ControlMeshDraw prepareControlMesh(const Mesh& mesh) {
    ControlMeshDraw d;
    d.hasUVs = mesh.hasUVs();
    d.controlPoints.reserve(mesh.vertexCount());
    for (const auto& p : mesh.positions)
        d.controlPoints.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y),
                                     static_cast<float>(p.z), 1.0f);
    d.faceOffsets = mesh.faceOffsets;
    d.faceVertices = mesh.faceVertices;
    if (d.hasUVs)
        for (const auto& uv : mesh.uvs)
            d.uvs.emplace_back(static_cast<float>(uv.x), static_cast<float>(uv.y));
    else
        d.uvs.emplace_back(0.0f, 0.0f);

    std::vector<uint8_t> hole(mesh.faceCount(), 0);
    for (uint32_t f : mesh.tags.holes) hole[f] = 1;
    const auto ptex = ptexFaceBase(mesh);

    std::vector<std::pair<uint32_t, uint32_t>> edges;
    std::vector<uint8_t> used(mesh.vertexCount(), 0);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        if (hole[f]) continue;
        ++d.drawnFaces;
        auto verts = mesh.face(f);
        const uint32_t first = static_cast<uint32_t>(d.corners.size());
        for (size_t i = 0; i < verts.size(); ++i) {
            GpuCorner c;
            c.vertex = verts[i];
            c.face = f;
            c.uv = d.hasUVs ? mesh.faceUVs(f)[i] : 0;
            c.ptex = ptex[f];
            d.corners.push_back(c);
            used[verts[i]] = 1;
            uint32_t a = verts[i], b = verts[(i + 1) % verts.size()];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
        // Fan from corner 0: (0, i, i+1) keeps the face's orientation.
        for (uint32_t i = 1; i + 1 < verts.size(); ++i) {
            d.triangles.push_back(first);
            d.triangles.push_back(first + i);
            d.triangles.push_back(first + i + 1);
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [a, b] : edges) {
        d.edges.push_back(a);
        d.edges.push_back(b);
    }

    const bool any = d.drawnFaces > 0;
    std::vector<glm::dvec3> drawn;
    for (size_t v = 0; v < mesh.vertexCount(); ++v)
        if (!any || used[v]) drawn.push_back(mesh.positions[v]);
    if (!drawn.empty()) d.bounds = boundsOf(drawn);
    return d;
}

} // namespace limn::render
