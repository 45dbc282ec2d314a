// One linear quadrangulation step (math.md A.0): insert a point at every face centroid and edge
// midpoint and split each n-gon into n quads. Unlike a Catmull–Clark step it moves no vertex, so
// a planar mesh stays planar. Faces with other than 4 sides become extraordinary vertices of
// valence n at their centroids.
#pragma once

#include "mesh/mesh.h"
#include "topology/topology.h"

namespace limn::blend {

bool isQuadMesh(const Mesh& mesh);

// The split mesh. Vertices: the original ones (same ids), then one per edge (Topology's edge
// order), then one per face. Faces: child j of face f is face faceOffsets[f] + j, the quad
// (c_j, mid(c_j,c_{j+1}), centroid, mid(c_{j−1},c_j)), so orientation is kept. UVs are split
// linearly per face (seams stay seams); crease tags are split onto both halves of their edge,
// hole tags move to the children of the hole, corner tags keep their vertex.
Mesh quadrangulateLinear(const Mesh& mesh, const Topology& topo);

} // namespace limn::blend
