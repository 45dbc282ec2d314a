// Built-in example meshes, generated here so that the examples and tests need no input files.
// Each exercises features the pipeline must handle: extraordinary vertices, UV seams, non-quad
// faces, creases and corners, open boundaries. All have face-varying UVs; faces are
// counter-clockwise seen from outside. Coordinates are rounded to 6 decimals so the OBJ text does
// not depend on the last bit of the C library's sin and cos.
#pragma once

#include "mesh/mesh.h"

#include <string>
#include <vector>

namespace limn {

// The cube [-1,1]^3: 8 valence-3 vertices; each face has its own UV tile.
Mesh makeCube();
// The cube's faces cut into n x n quads and pushed onto the unit sphere: 6n^2+2 vertices, the 8
// cube corners stay valence 3. UV seams along the 12 cube edges.
Mesh makeQuadSphere(int n);
// A torus of `ring` x `tube` quads, every vertex valence 4 (fully regular); the UV grid wraps, so
// seams run along one ring and one tube loop.
Mesh makeTorus(int ring, int tube);
// A pentagonal tower: a pentagon floor, 5 quad walls and a roof of 5 triangles.
Mesh makePentagonTower();
// makeQuadSphere's lattice left as a 2x2-per-face box, with crease tags: the top rim infinitely
// sharp, the 4 vertical edges semi-sharp (2), and a semi-sharp corner (3) at (-1,-1,-1).
Mesh makeCreasedCube();
// An n x n grid of quads on a shallow dome with the middle 2 x 2 quads removed (n even, >= 4): two
// boundary loops, under the edge-and-corner rule.
Mesh makeGridWithHole(int n);

// Frame k of n of a torus (ring x tube quads, makeTorus's topology and UVs) whose tube is an
// ellipse (semi-axes 0.45 and 0.2) turned once around along the ring and spun about the tube's
// centre line as k goes from 0 to n: frame n would be frame 0's surface (the ellipse is symmetric
// under the half turn, which moves each tube loop's vertices half way round), so the sequence
// loops. Every frame has the same faces; only positions change.
Mesh makeTwistingTorus(int ring, int tube, int k, int n);

struct Example {
    std::string name; // file stem: <name>.obj
    std::string description;
    Mesh mesh;
};

// Every built-in example, in a fixed order.
std::vector<Example> builtinExamples();

// Built-in animations: frame meshes of one topology, for limn-render --frames.
struct ExampleSequence {
    std::string name; // files <name>_0000.obj, <name>_0001.obj, ...
    std::string description;
    std::vector<Mesh> frames;
};
std::vector<ExampleSequence> builtinSequences();

} // namespace limn
