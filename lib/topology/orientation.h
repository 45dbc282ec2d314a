// Whether a mesh's faces can be given one consistent orientation. An edge whose two faces run it
// in the same direction is either a fixable inconsistency (flip some faces) or, on a Möbius strip
// or a Klein bottle, a property of the surface: no choice of face orientations removes it.
// Subdivision needs the first kind fixed and cannot handle the second at all; the messages say
// which it is.
#pragma once

#include "topology/topology.h"

#include <cstdint>
#include <string>

namespace limn {

struct Orientation {
    uint32_t misorientedEdges = 0; // edges of two faces that run them in the same direction
    bool orientable = true;        // false: some connected piece is not orientable
    uint32_t facesToFlip = 0;      // orientable: the fewest faces whose flip makes all consistent
    uint32_t exampleEdge = kNone;  // a misoriented edge (the first), for messages
};
Orientation checkOrientation(const Topology& topo);

// For an error about misoriented edge `e`: "faces of opposite orientation meet at edge (a,b);
// flipping N faces makes the mesh consistent" or "the mesh is not orientable (a Möbius strip or
// Klein bottle: ...)".
std::string describeMisorientation(const Topology& topo, const Orientation& o);

} // namespace limn
