// Limit positions and tangents of Catmull-Clark vertices (paper 000, 3.3 and 4.4, with the
// corrected masks of math.md section C). All faces around the vertex must be quads (true from
// level 1 on). Tangents are returned so that tangent1 x tangent2 points outward for
// counter-clockwise faces.
#pragma once

#include "subdiv/sdc_masks.h"

#include <cstdint>
#include <vector>

namespace limn {

struct WeightedPoint {
    uint32_t vertex; // local vertex index at the level
    double weight;
};

struct LimitMasks {
    std::vector<WeightedPoint> position, tangent1, tangent2;
    bool exact = true; // false where the masks only approximate the limit (see limit_masks.cpp)
};

// A sector: the faces around a vertex between two consecutive sharp edges (the whole ring for a
// smooth vertex). Faces [firstFace, firstFace + faceCount) in ring order (wrapping for interior
// vertices); closed == true means the ring has no sharp edge to cut it.
struct Sector {
    uint32_t firstFace = 0, faceCount = 0;
    bool closed = false;
};

// The sectors around a vertex given its rule and the sharpness of its ring edges. A face of the
// ring belongs to exactly one sector.
std::vector<Sector> vertexSectors(const VertexNeighborhood& hood, VertexRule rule,
                                  const std::vector<float>& edgeSharpness);

// Limit position (shared by all sectors) and the tangents of `sector`, into `out` (its vectors
// are reused between calls).
void limitMasks(const VertexNeighborhood& hood, VertexRule rule, const Sector& sector,
                const std::vector<float>& edgeSharpness, float vertexSharpness, LimitMasks& out);

} // namespace limn
