// Catmull-Clark features of a mesh level: edge and vertex sharpness (from tags plus OpenSubdiv's
// base-level sharpening), vertex rules, and which vertices and faces are regular, i.e. where the
// limit surface is exactly a bicubic B-spline patch of the 4x4 control points around a face
// (paper 000, section 3.2). Shared by limn-classify and the subdivision tables so both agree.
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"
#include "topology/topology.h"

#include <cstdint>
#include <vector>

namespace limn {

// The subdivision options a mesh is refined with, resolved from its tags and the command line.
struct SchemeOptions {
    BoundaryRule boundary = BoundaryRule::EdgeOnly;
    CreaseMethod creaseMethod = CreaseMethod::Uniform;
    TriangleSubdivision triangles = TriangleSubdivision::Catmark;
    FVarRule fvar = FVarRule::All;
    bool operator==(const SchemeOptions&) const = default;
};

// Tags win over defaults; `boundaryOverride` (from --boundary) wins over the tag.
SchemeOptions resolveSchemeOptions(const Tags& tags, std::optional<BoundaryRule> boundaryOverride);

// Vertex rules, as Sdc::Crease::Rule.
enum class VertexRule : uint8_t { Smooth = 1, Dart = 2, Crease = 4, Corner = 8 };

struct Sharpness {
    std::vector<float> edge;   // per topology edge
    std::vector<float> vertex; // per vertex
    // Faces without a limit surface: holes, and under boundary rule "none" every face around a
    // vertex that has a boundary edge not tagged infinitely sharp (as OpenSubdiv's Far factory
    // makes them holes before it sharpens boundaries).
    std::vector<uint8_t> faceNoLimit;
    // Per vertex: the vertices that rule "none" takes out that way. Their boundary is no
    // B-spline boundary, so classification counts them extraordinary (formats/limn.md 5).
    std::vector<uint8_t> vertexOnUnsharpBoundary;
};

// Base-level sharpness exactly as OpenSubdiv's Far factory prepares it: crease and corner tags,
// then boundary and non-manifold edges infinitely sharp, corner vertices (one face, two edges)
// infinitely sharp under edge-and-corner, non-manifold vertices sharp unless they lie on a
// non-manifold crease; plus the faces without a limit surface (holes, boundary rule "none").
// Crease tags naming no edge are reported as warnings and ignored.
Sharpness baseSharpness(const Topology& topo, const Tags& tags, BoundaryRule boundary,
                        Warnings& warnings);

VertexRule vertexRule(const Topology& topo, const Sharpness& sharp, uint32_t v);

// Per-vertex and per-face regularity at one level. A vertex is patch-regular when the surface
// around it follows the uniform B-spline rules: interior, 4 quads, no sharp incident edge and no
// vertex sharpness; or a boundary vertex with 2 quads whose interior edge is smooth (the boundary
// is then a B-spline with phantom points P_-1 = 2 P_0 - P_1, math.md C.4); or an infinitely sharp
// corner with 1 quad (edge-and-corner). Under boundary rule "none" a boundary vertex qualifies
// only when crease tags made its boundary edges infinitely sharp (it then behaves as under
// edge-only). With `infSharpPatches` (OpenSubdiv's useInfSharpPatch), infinitely sharp creases
// act as boundaries: a vertex whose inf-sharp edges split it into regular boundary sectors (a
// straight crease through a 4-valent vertex, a boundary vertex of 2 faces) or into single faces
// (a corner whose every edge is inf-sharp) is regular too. A face is regular when it is a quad
// with 4 patch-regular corners: its 4x4 neighbourhood is then a B-spline patch (with phantom
// points beyond its boundary and inf-sharp edges).
// With `singleCreasePatches` (OpenSubdiv's useSingleCreasePatch) an interior quad with a
// semi-sharp crease of one sharpness along one of its edges, continuing straight through both
// ends, and two smooth regular corners is regular too: a single-crease patch, faceCreaseEdge
// names its crease edge (kNone for every other face). With `only`, just the faces it marks are
// analysed (and vertexRegular set at their corners): the others are left irregular.
struct Regularity {
    std::vector<uint8_t> vertexRegular;
    std::vector<uint8_t> faceRegular; // never set for faces without a limit surface
    std::vector<uint32_t> faceCreaseEdge;
};

Regularity analyzeRegularity(const Topology& topo, const std::vector<float>& edgeSharpness,
                             const std::vector<float>& vertexSharpness,
                             const std::vector<uint8_t>& faceNoLimit,
                             bool infSharpPatches = true, bool singleCreasePatches = true,
                             const std::vector<uint8_t>* only = nullptr);

} // namespace limn
