// The closeness-distance metric (paper 004, section 3.2, eq. (2); math.md B.4): for every edge, the
// distance between its odd vertex and that vertex's limit position, taken in the mesh refined
// uniformly once. There an interior odd vertex is regular (valence 6), so its limit is
//     L(o) = o/2 + (a' + b' + o_1 + o_2 + o_3 + o_4)/12
// (a', b': the even positions of the edge's ends; o_1..o_4: the odd vertices of the other edges of
// its two triangles), and an odd vertex on a sharp edge has the crease limit L(o) = (a' + 4o + b')/6.
#pragma once

#include "loop/level.h"

#include <glm/vec3.hpp>

#include <vector>

namespace limn::loop {

enum class Metric {
    Full,   // |o − L(o)|: the paper's metric
    Normal, // the part of o − L(o) off the surface: along the mean of the two face normals for an
            // interior edge, perpendicular to the edge for a sharp one (math.md B.4, "optional fix")
    Chord,  // |(a + b)/2 − L(o)|: the gap between the unsplit edge's midpoint and the limit surface
            // there, i.e. the error the edge leaves if it is not split (limn's variant)
};

// L(o_e) for every edge: the limit positions of the odd vertices (formulas above). `even` and `odd`
// are evenPositions() and oddPositions() of the same level. These are also the limit positions of
// the odd vertices of the uniformly refined mesh, so no topology of that mesh is needed.
std::vector<glm::dvec3> oddLimitPositions(const Level& level, const std::vector<glm::dvec3>& even,
                                          const std::vector<glm::dvec3>& odd);

// d(e) for every edge of the level, unnormalized.
std::vector<double> edgeDistances(const Level& level, const std::vector<glm::dvec3>& even,
                                  const std::vector<glm::dvec3>& odd, Metric metric);

} // namespace limn::loop
