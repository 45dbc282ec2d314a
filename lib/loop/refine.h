// One step of adaptive Loop refinement (paper 004, section 3.3.3; math.md B.5–B.7): split the
// marked edges at their odd vertices, update the even vertices, and retriangulate every triangle
// by its number of split edges. Decisions are per edge, so both triangles at an edge agree and
// the result is conforming (no T-junctions) by construction.
#pragma once

#include "loop/level.h"

#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace limn::loop {

// Which old vertices move to their even position (math.md B.7).
enum class EvenUpdate {
    All,   // (a) every vertex, as uniform Loop does
    Split, // (b) only vertices with at least one split edge; the others keep their position
};

struct Refinement {
    // Vertices: the old ones first (same indices), then one odd vertex per split edge, in edge
    // order. Triangles keep their orientation.
    TriMesh mesh;
    // For each odd vertex (index vertexCount_old + i): the ends of the edge it splits.
    std::vector<VertexPair> oddParents;
};

// `split` has one flag per edge of the level; `even`/`odd` are evenPositions()/oddPositions().
Refinement refine(const Level& level, std::span<const uint8_t> split, EvenUpdate update,
                  const std::vector<glm::dvec3>& even, const std::vector<glm::dvec3>& odd);

// Appends the retriangulation of one triangle (math.md B.6; paper 004, Fig. 4) to `out`:
// `corner` its counter-clockwise corners, `mid[i]` the vertex splitting edge (corner i, corner i+1)
// or kNone. Two split edges: the corner between them is cut off and the remaining quad is split by
// the diagonal whose two triangles have the larger minimum compactness on positions `P` (ties: the
// diagonal from the corner opposite the cut-off one). With `uvCorner`/`uvMid`, the UV triangles too.
void appendTemplate(const Tri& corner, const Tri& mid, const std::vector<glm::dvec3>& P,
                    TriMesh& out, const Tri* uvCorner = nullptr, const Tri* uvMid = nullptr);

// Compactness 4√3·A/(l0² + l1² + l2²) of a triangle (paper 004, eq. (3)): 1 for an equilateral
// triangle, towards 0 for slivers, 0 for a degenerate one.
double compactness(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

} // namespace limn::loop
