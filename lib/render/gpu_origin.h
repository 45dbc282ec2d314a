// The GPU's coordinates: the model's minus an origin in the middle of the control points' box.
// Float carries 24 bits of a coordinate, so a small face far from the origin loses its small
// differences (the rook sits 3.4 from the origin with a diagonal of 0.87: its normals were up to
// 0.44 degrees off in float, where limn's double evaluation is OpenSubdiv's to the last digit; a
// model 300 units out drew thousands of vertices 3e-5 of its diagonal off). Relative to the box's
// middle the coordinates are at most half the diagonal. The renderer uploads control points, eye
// and view-projection in these coordinates and adds the origin back to what --mesh-out reads;
// the web runtime (web/src/renderer.mjs) does the same with the same expressions, so both upload
// the same bits. Only the subdivision surface uses it: the control mesh is drawn flat at its own
// points, which --mesh-out gives back exactly (a point shifted and shifted back is not always the
// point in float), and the blending surface's draw reads what limn-blend fitted in the model's.
#pragma once

#include "mesh/mesh.h"

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace limn::render {

inline glm::dvec3 renderOrigin(const Mesh& mesh) {
    if (mesh.positions.empty()) return glm::dvec3(0.0);
    glm::dvec3 lo = mesh.positions[0], hi = mesh.positions[0];
    for (const glm::dvec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return (lo + hi) * 0.5;
}

// viewProjection * translate(origin): the view-projection of the GPU's coordinates, written out
// term by term in the order web/src/renderer.mjs's `translated` uses, so both round the same
// doubles to float.
inline glm::dmat4 translatedViewProjection(glm::dmat4 vp, const glm::dvec3& origin) {
    for (int r = 0; r < 4; ++r)
        vp[3][r] = ((vp[3][r] + vp[0][r] * origin.x) + vp[1][r] * origin.y) + vp[2][r] * origin.z;
    return vp;
}

} // namespace limn::render
