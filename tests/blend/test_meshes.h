// Meshes for the blend tests: generated shapes whose valences are known by construction, the
// shared models, and geometric measures computed independently of lib/blend.
#pragma once

#include "blend/blend_surface.h"
#include "mesh/mesh.h"
#include "topology/topology.h"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace limn::blendtest {

// Closed n-gonal bipyramid (two apexes of valence n, equator vertices of valence 4), triangles.
Mesh bipyramid(int n);
// Fan of n triangles around a centre vertex in the plane z = 0 (a disk; boundary ring).
Mesh fanDisk(int n);
// Closed torus of nu×nv quads (all valence 4), radii R and r.
Mesh torus(int nu, int nv, double R, double r);
// Regular (n+1)×(n+1) vertex grid of unit quads in x,y with z = height(x, y).
Mesh grid(int n, double (*height)(double, double));

Mesh loadModel(const std::string& relative);       // tests/data/<relative>
Mesh loadTestData(const std::string& name);         // tests/blend/data/<name>
Mesh quadrangulated(const Mesh& mesh);              // blend::quadrangulateLinear
// Applies a fixed rotation and translation (a rigid motion), so "planar" is not "z = 0".
Mesh rigidlyMoved(const Mesh& mesh);
glm::dvec3 rigidNormal(); // the image of (0,0,1) under rigidlyMoved's rotation

Topology topologyOf(const Mesh& mesh);
double bboxDiagonal(const Mesh& mesh);
double angleDegrees(const glm::dvec3& a, const glm::dvec3& b); // between unit vectors

// Surface measures on every face / interior edge / vertex (math.md A.11 checks ).
struct Continuity {
    double positionJump = 0; // max |S_f1 − S_f2| at shared edge points
    double normalJump = 0;   // max angle (degrees) between the two normals
    size_t edges = 0;
};
Continuity edgeContinuity(const blend::BlendSurface& s, const Topology& topo, int samplesPerEdge);
double maxInterpolationError(const blend::BlendSurface& s, const Mesh& mesh);
// Max angle between the vertex normal and normals at (s,t) = (d,d) in every incident face.
double maxVertexNormalAngle(const blend::BlendSurface& s, const Topology& topo, double d);

} // namespace limn::blendtest
