// Exact limit points for the corners of the faces left irregular at the last level.
//
// The closed-form masks of limit_masks.h are exact only where the vertex's rule holds for every
// further level and is one the formulas cover. These are not:
//  - semi-sharp features (0 < s < 10) at the vertex that have not decayed by the last level N:
//    the limit is neither the smooth nor the crease one. A crease of sharpness s uses the sharp
//    rules for ceil(s) more levels and is smooth after that ([DKT98]; Sdc::Crease), so these
//    vertices are refined locally (their faces; with Chaikin creasing also the one-ring of those,
//    as the isolation of tables.h does) until every incident edge and the vertex itself are smooth or infinitely
//    sharp; the masks of that level are then exact, and the stencils of the extra levels are
//    composed into them so the rows read level-N vertices only (the one-ring of a vertex at level
//    N + j depends only on its one-ring at level N, so the support does not grow).
//  - darts and valence-2 vertices: their local subdivision matrix S (one-ring to one-ring, built
//    from the level's own Sdc stencils one level further) is not the one the smooth formulas are
//    eigenvectors of (a dart's sharp edge uses the midpoint rule; HKD93's tangent masks degenerate
//    at valence 2). The limit position is S's left eigenvector for eigenvalue 1, a dart's tangent
//    plane the left invariant subspace of its next two eigenvalues (Halstead et al. 1993,
//    section 4), found by power and subspace iteration from the closed forms, which also fix the
//    orientation. Valence 2 has eigenvalues 1/4, 1/4, -1/4: no tangent plane; its normal stays
//    flagged approximate.
//  - corners whose sector has more than one face, and cone points (a corner on a ring no two
//    sharp edges cut): the surface has no tangent plane, so each face drawn through the vertex
//    gets its own limit point whose normal is the one approached along that face's diagonal.
//    Where S has a Jordan block there, that normal converges like 1/level and stays flagged
//    approximate (as at smooth corners).
// Limit points of the other vertices are limit_masks.h's, unchanged.
#pragma once

#include "subdiv/level.h"
#include "subdiv/limit_masks.h"

#include <cstdint>
#include <vector>

namespace limn {

// The limit points of one level-N vertex: one per sector (of the level where its masks are
// exact), as stencils over level-N vertices, and the sector of each face around it at level N.
struct VertexLimits {
    std::vector<LimitMasks> sectors;
    std::vector<uint32_t> ringFaces;  // level-N faces around the vertex
    std::vector<uint8_t> ringSector;  // the sector of each of those faces
};

// Limit points of the given level-N vertices (all faces around them quads). `drawn` marks the
// level-N faces drawn through their corners' limit points (where a vertex has one point per face,
// only those get one). `ptexBase` as for refineLevel. Deterministic.
std::vector<VertexLimits> exactVertexLimits(const Level& levelN, const std::vector<uint32_t>& vertices,
                                            const std::vector<uint8_t>& drawn,
                                            const SchemeOptions& options,
                                            const std::vector<uint32_t>& ptexBase);

} // namespace limn
