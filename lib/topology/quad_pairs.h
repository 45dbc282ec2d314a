// Quads back from triangles: joins pairs of triangles across their shared edge where that edge
// looks like the diagonal of a quad, as Blender's "Tris to Quads" does (its bmesh operator
// join_triangles, bmesh/operators/bmo_join_triangles.c, as of Blender 2.8 to 4.1). Exporters (glTF carries only triangles)
// split every quad along a diagonal; Catmull-Clark of the triangles is lumpy and makes every
// vertex extraordinary, of the rejoined quads it is the surface the artist modelled.
//
// Candidate edges: shared by exactly two consistently oriented triangles; not a crease; the
// two faces both holes or neither; the UVs of both endpoints the same in both faces (a quad has
// one UV per corner); the triangles' normals within maxFaceAngle; the quad convex across both
// diagonals and each of its corners within maxShapeAngle of a right angle. Each candidate gets
// Blender's error (normal difference + corner-angle deviation + area imbalance of the two
// diagonal splits). Pairs of triangles that are neighbours in the face list (an exporter writes a
// split quad's two triangles together) are joined first, as many as their chains allow, the
// least total error among equals; then the other candidates from the smallest error up (Blender's
// order), ties by edge order, a triangle joined at most once. Deterministic: the same mesh gives
// the same quads.
#pragma once

#include "mesh/mesh.h"

#include <cstddef>
#include <numbers>

namespace limn {

// Blender's two limits ("Max Face Angle", "Max Shape Angle"; 180 degrees turns one off). Blender's
// defaults are 40 and 40 degrees; limn's are wider, measured on spot's exporter-triangulated quads
// (tests/topology/quad_pairs_test.cpp): 176 of its 2928 quads have a corner more than 40 degrees
// from square, and with 60 and 75 all 2928 come back.
struct QuadJoinOptions {
    double maxFaceAngle = 60.0 * std::numbers::pi / 180.0;
    double maxShapeAngle = 75.0 * std::numbers::pi / 180.0;
};

struct QuadJoinReport {
    size_t trianglesBefore = 0;
    size_t quadsMade = 0;
    size_t trianglesLeft = 0;
};

// Joins in place. Faces keep their order (a quad takes the place of its first triangle);
// vertices, UVs and vertex tags are unchanged, hole indices follow their faces.
QuadJoinReport joinTrianglePairs(Mesh& mesh, const QuadJoinOptions& options = {});

} // namespace limn
