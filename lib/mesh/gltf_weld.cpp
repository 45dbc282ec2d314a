// gltf::Welder: glTF primitives welded into one limn Mesh (gltf_parts.h): node transforms and
// morph targets applied, strips and fans as glTF 2.0 (3.7.2.1) defines their triangles, mirrored
// instances turned right side out (3.7.4), and FB_ngon_encoding's polygons rebuilt.
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>

namespace limn::gltf {

uint32_t Welder::weldPosition(const glm::dvec3& p) {
    auto [it, inserted] = positionIndex.try_emplace({p.x, p.y, p.z},
                                                     static_cast<uint32_t>(mesh.positions.size()));
    if (inserted) mesh.positions.push_back(p);
    return it->second;
}
uint32_t Welder::weldUV(const glm::dvec2& uv) {
    auto [it, inserted] = uvIndex.try_emplace({uv.x, uv.y}, static_cast<uint32_t>(mesh.uvs.size()));
    if (inserted) mesh.uvs.push_back(uv);
    return it->second;
}

void Welder::addPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                          const Prepass& pre, std::pair<int, int> key, const std::vector<double>& weights,
                          const glm::dmat4& transform, const std::string& what) {
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        ++skippedPrimitives;
        return;
    }
    if (prim.material >= 0) {
        if (material < 0) material = prim.material;
        else if (prim.material != material) otherMaterials = true;
    }
    const PrimitiveData d = primitiveData(model, prim, pre, key, weights, what);
    std::vector<uint32_t> welded(d.positions.size());
    for (size_t i = 0; i < d.positions.size(); ++i) {
        const glm::dvec3 q(transform * glm::dvec4(d.positions[i], 1.0));
        // A NaN would also break the welding map's ordering; refuse it like Inf.
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
            throwBadInput(what + " POSITION " + std::to_string(i) +
                          " is not finite (NaN or Inf), after the node transforms and morph targets");
        welded[i] = weldPosition(q);
    }
    std::vector<uint32_t> uvs(d.texcoords.size());
    for (size_t i = 0; i < d.texcoords.size(); ++i) {
        const double u = d.texcoords[i].x, v = d.texcoords[i].y;
        if (!std::isfinite(u) || !std::isfinite(v))
            throwBadInput(what + " TEXCOORD_0 " + std::to_string(i) + " is not finite");
        uvs[i] = weldUV({u, 1.0 - v});
    }
    (d.texcoords.empty() ? anyWithoutUV : anyUV) = true;
    std::vector<uint32_t> corners = d.indices;
    if (d.hasIndices) {
        for (uint32_t c : corners)
            if (c >= d.positions.size())
                throwBadInput(what + " index " + std::to_string(c) + " is past the " +
                              std::to_string(d.positions.size()) + " vertices");
    } else {
        corners.resize(d.positions.size());
        for (size_t i = 0; i < corners.size(); ++i) corners[i] = static_cast<uint32_t>(i);
    }
    // Strips and fans as the triangles glTF 2.0 (3.7.2.1) defines: strip triangle i is
    // {v_i, v_i+(1+i%2), v_i+(2-i%2)}, fan triangle i is {v_i+1, v_i+2, v_0}.
    if (mode != TINYGLTF_MODE_TRIANGLES) {
        std::vector<uint32_t> list;
        for (size_t i = 0; i + 2 < corners.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                list.insert(list.end(), {corners[i], corners[i + 1 + i % 2], corners[i + 2 - i % 2]});
            else
                list.insert(list.end(), {corners[i + 1], corners[i + 2], corners[0]});
        }
        corners = std::move(list);
    }
    if (corners.size() % 3) throwBadInput(what + " index count is not a multiple of 3");
    // A transform with a negative determinant mirrors the mesh: glTF 2.0 (3.7.4) reverses the
    // winding, so that the instance stays right side out.
    const bool mirror = glm::determinant(glm::dmat3(transform)) < 0;
    if (mirror) ++mirrored;
    const bool ngon = rebuildNgons && mode == TINYGLTF_MODE_TRIANGLES && prim.extensions.count("FB_ngon_encoding");
    std::vector<uint32_t> polygon, polygonUVs;
    auto emit = [&] { // the polygon in `polygon` (glTF indices), welded
        std::vector<uint32_t> face, faceUV;
        for (uint32_t c : polygon) {
            face.push_back(welded[c]);
            faceUV.push_back(uvs.empty() ? ~0u : uvs[c]);
        }
        if (mirror) {
            std::reverse(face.begin() + 1, face.end());
            std::reverse(faceUV.begin() + 1, faceUV.end());
        }
        std::vector<uint32_t> sorted = face;
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
            ++degenerate; // collapsed by welding or degenerate in the file
            return;
        }
        if (face.size() > 3) ++ngons;
        mesh.addFace(face);
        mesh.uvIndices.insert(mesh.uvIndices.end(), faceUV.begin(), faceUV.end());
    };
    for (size_t t = 0; t < corners.size(); t += 3) {
        const uint32_t a = corners[t], b = corners[t + 1], c = corners[t + 2];
        // FB_ngon_encoding: the triangles of one polygon are consecutive and share their first
        // index, as a fan (a, b, c), (a, c, d), ...; a triangle that does not continue the
        // fan starts a new polygon.
        if (ngon && !polygon.empty() && polygon.front() == a && polygon.back() == b) {
            polygon.push_back(c);
            continue;
        }
        if (!polygon.empty()) emit();
        polygon = {a, b, c};
    }
    if (!polygon.empty()) emit();
}

} // namespace limn::gltf
