// A CPU evaluator of the tables: the same arithmetic the GPU passes do, in double precision, for
// tests and reference renders. Straightforward on purpose.
#pragma once

#include "subdiv/tables.h"

#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace limn {

// All table vertices (levels concatenated) from the control points, level by level: face
// points, then edge points, then vertex points (they read the level's face points).
std::vector<glm::dvec3> evaluateVertices(const Tables& tables, std::span<const glm::dvec3> control);

struct SurfacePoint {
    glm::dvec3 position, du, dv, normal; // du, dv: derivatives in the patch's ptex u and v
};

// The bicubic B-spline of paper 000 eq. (1) at patch-local (s, t) in [0,1]^2, with phantom
// points beyond boundary edges (math.md C.4). Derivatives are per unit of ptex u and v.
SurfacePoint evaluatePatch(const Patch& patch, std::span<const glm::dvec3> vertices, double s,
                           double t);

// Positions only, at every (s, t) of params x params (s outer), appended to out: the same bits
// as evaluatePatch(...).position, with the control points gathered once (framing samples).
// A regular patch's 16 control points P[i][j] (i along u) from the table vertices, phantoms
// put in for its boundary bits (math.md C.4): columns first, then rows over all columns.
void gatherControlPoints(const Patch& patch, std::span<const glm::dvec3> vertices, glm::dvec3 P[4][4]);

void patchPositions(const Patch& patch, std::span<const glm::dvec3> vertices, std::span<const double> params,
                    std::vector<glm::dvec3>& out);

struct LimitPoint {
    glm::dvec3 position, tangent1, tangent2, normal;
};

std::vector<LimitPoint> evaluateLimitPoints(const Tables& tables, std::span<const glm::dvec3> vertices);

// The surface of irregular face `face` at its local (s, t) in [0,1]^2 (docs/irregular.md): on
// its quadtree's sub-patch there, or, in a leaf (within 2^-K of an extraordinary corner), the
// bilinear blend of the leaf's corner limit points, which is exact only at those corners;
// `exact` (if given) says which. Faces of tables without a quadtree are all leaf. Derivatives
// are per unit of ptex u and v.
SurfacePoint evaluateIrregular(const Tables& tables, std::span<const glm::dvec3> vertices,
                               std::span<const LimitPoint> limits, uint32_t face, double s,
                               double t, bool* exact = nullptr);

// The 16 control points P[i][j] (i along the band's first axis, away from the extraordinary
// corner) of smooth irregular face `smooth`'s band-k sub-patch in quadrant q (irregular_basis.h:
// per-valence weights of its support points), as evaluateIrregular sums them. For data that
// does not change per frame (smooth face-varying UVs) they are worth computing once.
void smoothSubPatchControlPoints(const Tables& tables, uint32_t smooth, std::span<const glm::dvec3> vertices,
                                 uint32_t k, uint32_t q, glm::dvec3 P[4][4]);

// Uniform cubic B-spline basis and its derivative at t in [0,1] (paper 000, section 3.2).
void bsplineBasis(double t, double b[4], double d[4]);

// The basis of a single-crease patch across its crease (Nießner, Loop and Greiner 2012): the
// limit of a cubic B-spline curve Q0..Q3 whose vertex Q1 is semi-sharp with `sharpness`, on the
// segment from Q1 (t = 0) to Q2 (t = 1), found by halving the segment toward Q1 until the
// sharpness has decayed (at most ceil(sharpness) steps). Along the crease the patch is a plain
// B-spline, so the patch is this basis times the B-spline one.
void creaseBasis(double t, double sharpness, double b[4], double d[4]);

} // namespace limn
