// The topology of view-adaptive tessellation, built once on the CPU from the tables
// alone (positions are never read, so animation and camera motion re-run only GPU passes).
//
// Every element (a regular patch of paper 000, 4.3, or an irregular level-N face) has four sides,
// counter-clockwise in its (s, t). A side is cut into *edge pieces* at every element corner that
// lies on it, so a coarse side next to two finer patches has two pieces (the level transitions
// of paper 000, 4.3, where the fixed grids of 2^(N-l) meet vertex to vertex). Each piece is
// shared by the (one or two) sides that run along it, and has one *owner*: the first side, in
// element order, that registered it. Its points are evaluated from the owner's element and
// parameters only, so both sides of a piece evaluate the same bits (brief, "Watertight to the
// bit"); its rate is decided once per frame, per piece, so both sides always agree (the lesson of
// OpenSubdiv PR #435: never let two patches decide an edge's rate from their own data). Every
// element corner is a *point* with one owner too, so corners and the ends of pieces are shared
// bits as well.
#pragma once

#include "mesh/mesh.h"
#include "subdiv/tables.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace limn {

inline constexpr uint32_t kNoElement = 0xFFFFFFFFu;

// Parameters in the units of TessVertex (1/32768 of the element), packed s | t << 16.
inline uint32_t packST(uint32_t s, uint32_t t) { return s | t << 16; }

struct EdgePiece {
    uint32_t owner;        // element
    uint32_t ownerStart;   // owner's packed (s, t) at the piece's start, in the owner's direction
    uint32_t ownerEnd;     // ... at its end
    uint32_t users[2];     // elements with a side on it (the second kNoElement on a boundary)
    uint32_t startPoint, endPoint; // points at the owner's start and end
    uint32_t span;         // most parameter units between start and end (caps the rate)
    float uvLength;        // length in the owner's UV chart (0 without UVs)
};

struct SidePiece {         // one piece of one element side, in the side's direction
    uint32_t piece;
    uint32_t startPoint;   // the point where it starts in this side's direction
    uint32_t reversed;     // 1 when this side runs against the owner's direction
    uint32_t from, to;     // this element's parameter along the side (1/32768 of the side)
};

struct EdgePoint {
    uint32_t owner;        // element
    uint32_t st;           // owner's packed (s, t): a corner, so each is 0 or 32768
};

struct AdaptiveElement {
    uint32_t sideFirst[4]; // into sidePieces
    uint32_t sideCount[4];
    glm::vec2 cornerUV[4]; // own chart's UV at (0,0), (1,0), (1,1), (0,1) (zero without UVs)
    uint32_t level;        // patch level, 255 for an irregular face
};

struct EdgePieces {
    std::vector<AdaptiveElement> elements; // patches, then irregular faces (TessVertex numbering)
    std::vector<SidePiece> sidePieces;
    std::vector<EdgePiece> pieces;
    std::vector<EdgePoint> points;
};

EdgePieces buildEdgePieces(const Mesh& mesh, const Tables& tables);

} // namespace limn
