// Auxiliary texture coordinates for crack-free displacement (paper 000, 3.4, 4.1 and 4.5,
// Figures 5, 8, 9): for every drawn element (the regular patches, then the irregular faces, in
// TBLS order) the UVs of its four corners in every base face around them, and for each of its
// edges the UVs of its ends in each face on either side. A vertex shared by several faces
// averages the displacement sampled with each of their UVs; an edge point averages the two
// sides' samples at interpolated UVs; both in increasing face order, so every element sharing
// the point computes the same bits. UVs of refined levels follow the linear face-varying rule
// (bilinear in each face's chart, rule "all"); for the smoothing rules the fixed grids take
// their samples from tess/chart_uvs.h instead, in the same order.
#pragma once

#include "container/container.h"
#include "mesh/mesh.h"
#include "subdiv/tables.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace limn {

inline constexpr FourCC kSeamsChunk{"SEAM"};

// The most distinct UVs one point may have in the faces around it (a vertex with a UV seam
// between each pair of its faces): what the readers accept for a corner.
inline constexpr uint32_t kMaxPointUVs = 4096;

struct ElementSeams {
    glm::vec2 own[4];           // the element's corners in its own face's chart
    uint32_t cornerFirst[4];    // corner k: distinct UVs of the point in every face around it
    uint32_t cornerCount[4];
    uint32_t edgeFirst[4];      // edge k (corner k -> k+1): per side, the UVs at its two ends
    uint32_t edgeSides[4];      // 1 inside a face or on the mesh boundary, 2 across a base edge
};

struct Seams {
    uint64_t sourceHash = 0; // of the TBLS and FVUV payloads they were made from
    std::vector<ElementSeams> elements;
    std::vector<glm::vec2> uvs;
};

// Throws Error(BadInput) if the mesh has no UVs, a vertex has more than kMaxPointUVs distinct
// UVs, or the UVs would pass one 128 MiB GPU storage buffer.
Seams computeSeams(const Mesh& mesh, const Tables& tables, uint64_t sourceHash);

// The hash computeSeams records, from the container's chunks.
uint64_t seamsSourceHash(const Container& container);

Chunk encodeSeamsChunk(const Seams& seams);
// Validates counts, index ranges and finiteness; with `expectedElements` and `expectedHash`
// (non-zero) also that the seams match the container's tables and UVs.
Seams decodeSeamsChunk(const Chunk& chunk, uint32_t expectedElements, uint64_t expectedHash);

} // namespace limn
