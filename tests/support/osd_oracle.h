// OpenSubdiv as the reference for tests (../shared/docs/opensubdiv.md): the limit surface at
// (ptex, u, v) from an adaptive patch table with Gregory end caps and infinitely sharp patches,
// and uniformly refined vertex positions per level. Built from a limn Mesh with the same scheme
// options limn uses.
#pragma once

#include "mesh/mesh.h"
#include "topology/features.h"

#include <glm/vec3.hpp>

#include <memory>
#include <vector>

namespace limn::test {

class OsdLimitSurface {
public:
    OsdLimitSurface(const Mesh& mesh, const SchemeOptions& options, int isolationLevel = 8);
    ~OsdLimitSurface();

    int ptexFaceCount() const;
    // Evaluates the limit surface at (u, v) of ptex face `ptex`, using the patch that contains
    // the point (insideU, insideV) (pass the same point to let OpenSubdiv choose; pass a point
    // just inside a face to pick the side of a crease). Returns false on holes.
    bool evaluate(int ptex, double u, double v, glm::dvec3& position, glm::dvec3& normal) const;
    bool evaluate(int ptex, double u, double v, double insideU, double insideV,
                  glm::dvec3& position, glm::dvec3& normal) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Positions of every vertex of uniform refinement levels 0..depth (double precision).
std::vector<std::vector<glm::dvec3>> osdUniformLevels(const Mesh& mesh, const SchemeOptions& options,
                                                      int depth);

// Base vertices that are smooth corners: the crease rule (exactly two infinitely sharp edges,
// boundaries or tags, and no infinitely sharp corner) with a sector of one face, i.e. a face
// whose two edges at the vertex are both sharp: a boundary vertex of one face under edge-only,
// or an interior crease turning at the vertex (counted independently of limn, from the mesh and
// its tags). The subdivision matrix has a Jordan block there, so limit normals converge like
// 1/level, too slowly for OpenSubdiv's patches to reach (tests/subdiv SmoothCorner).
std::vector<uint8_t> smoothCorners(const Mesh& m, const SchemeOptions& o);
// The base vertex at a ptex-face corner (u, v in {0,1}), or -1 when (u, v) is no base vertex.
int baseVertexAt(const Mesh& m, uint32_t ptex, double u, double v);

// `levels` steps of OpenSubdiv's uniform refinement as a mesh with the same limit surface: the
// refined faces, positions, and the crease and corner sharpness left after those steps.
Mesh osdUniformRefinedMesh(const Mesh& mesh, const SchemeOptions& options, int levels);

// What OpenSubdiv's adaptive patch table holds for a mesh (Gregory end caps, legacy sharp
// corners off), for the benches' side-by-side counts: patches by kind and the bytes a GPU draw
// would upload: patch control-vertex indices (4 each), patch params (8 each), single-crease
// sharpness (index and value, 8 per patch when present), and the stencils computing every
// refined and local point from the control points (8 per stencil, 8 per entry).
struct OsdPatchCounts {
    size_t regular = 0, singleCrease = 0, boundary = 0, gregory = 0, other = 0;
    size_t total() const { return regular + gregory + other; }
    size_t bytes = 0;
};
OsdPatchCounts osdPatchCounts(const Mesh& mesh, const SchemeOptions& options, int isolation,
                              bool infSharpPatches, bool singleCreasePatches);

} // namespace limn::test
