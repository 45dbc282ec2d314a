// Crease trees: what a per-configuration surface for the faces a chain cannot take would hold
// (study code for bench_crease_bases, kept out of lib/ as the chains were until measured).
//
// A chain (lib/subdiv/crease_basis.h) follows one irregular child per level: the feature
// corner's. Along a Chaikin crease whose sharpness varies (catmark_chaikin1/2), OpenSubdiv's rule
// (Sdc::Crease::SubdivideEdgeSharpnessAtVertex: 3/4 of the edge's sharpness and 1/4 of the other
// semi-sharp edges' at the vertex, less 1) gives every child edge a sharpness of its own, so no
// child along the crease is a single-crease patch (one sharpness along three edges) until the
// crease has decayed: the quadtree has 2^j irregular nodes at level N + j, and no corner has a
// chain. A tree keeps every irregular node: per node, one program over the node's own support
// (its key: creaseSupport's from ptex corner 0) whose rows are its regular children's control
// points and its irregular children's supports.
#pragma once

#include "subdiv/crease_basis.h"

#include <array>
#include <cstdint>
#include <vector>

namespace limn {

// What a quadrant of a tree node holds.
enum class CreaseTreeChild : uint8_t { Patch, Node, Smooth, Leaf };

struct CreaseTreeNode {
    std::vector<uint32_t> key;       // creaseSupport(level, node, 0)
    std::vector<uint32_t> turnedKey; // the least of creaseSupport's keys from its four corners
    uint32_t support = 0;
    BasisProgram program; // nextSupport: the Node and Smooth children's supports, in quadrant order
    std::array<CreaseTreeChild, 4> child{};         // by quadrant code (u high: 1, v high: 2)
    std::array<std::array<uint32_t, 16>, 4> rows{}; // a Patch's control rows (kNone: a phantom)
    std::array<CreaseBandKind, 4> kind{};
    std::array<uint32_t, 4> next{}; // a Node's index in CreaseTree::nodes; a Smooth child's valence
    std::array<uint32_t, 4> nextFirst{}, nextCount{}; // its support in program.nextSupport
};

struct CreaseTree {
    std::vector<CreaseTreeNode> nodes; // the root first, then level by level
};

// The tree of face f of level L over `levels` levels, from a copy of its support's faces as
// buildCreaseChain's (localLevel, refineLevel around the irregular nodes only). False where an
// irregular child has no crease support (a non-quad, a hole).
bool buildCreaseTree(const Level& L, uint32_t f, uint32_t levels, const SchemeOptions& options,
                     const TablesOptions& opts, CreaseTree& tree);

} // namespace limn
