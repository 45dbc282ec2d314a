// The smooth UVs of drawn points: a surface point's UV in the chart of each base face
// that contains it, from the face-varying surface, computed once per (point, face) and kept, so
// every element that draws the point in a face gets the same bits (the tessellation splits a
// vertex only where two faces give different UVs, and the seam fix averages the same samples,
// in increasing face order, for every copy of a point).
#pragma once

#include "mesh/mesh.h"
#include "subdiv/fvar_surface.h"
#include "topology/ptex.h"
#include "topology/topology.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace limn {

class ChartUVs {
  public:
    // Points are (U, V) in [0, R]^2 of a ptex face, R = 2^depth of the surface's tables.
    ChartUVs(const Mesh& mesh, const FaceVaryingSurface& surface, uint32_t resolution);

    // The point's UV in the chart of the base face of `ptex`, evaluated from inside the ptex
    // face toward (towardU, towardV) (in units of 1/R) on first use.
    glm::vec2 own(uint32_t ptex, uint32_t U, uint32_t V, double towardU, double towardV);
    // A point strictly inside a ptex face, at (u, v) in [0,1]^2 (no other face contains it).
    glm::vec2 interior(uint32_t ptex, double u, double v) const;
    // The distinct UVs of the point in every base face that contains it, in increasing face
    // order (paper 000, Figures 8 and 9: the displacement samples the seam fix averages).
    void sides(uint32_t ptex, uint32_t U, uint32_t V, std::vector<glm::vec2>& out);
    // For the element edge from (Ua, Va) to (Ub, Vb) of ptex face `ptex`: per base face along it
    // (one inside a face or on the mesh boundary, two across a base edge; increasing face
    // order), the UVs of its two ends in that face's chart, distinct pairs only (the seam
    // record of seams.h, with smooth UVs).
    void edgeSides(uint32_t ptex, uint32_t Ua, uint32_t Va, uint32_t Ub, uint32_t Vb,
                   std::vector<std::pair<glm::vec2, glm::vec2>>& out);

  private:
    struct Located {
        uint32_t face, ptex, U, V;
    };
    // Internally points are (X, Y) = (2U, 2V) in [0, Q]^2, Q = 2R, so that a point on a base
    // edge has integer coordinates in both a quad and an n-gon sub-face (which spans half the
    // edge), and base-edge parameters t are in units of 1/(2Q) of the edge.
    glm::vec2 ownQ(uint32_t ptex, uint32_t X, uint32_t Y, double towardX, double towardY);
    void locate(uint32_t ptex, uint32_t X, uint32_t Y, std::vector<Located>& out) const;
    // Where the point at t from base vertex a toward b (t = 0: a itself) lies in face f.
    Located inFace(uint32_t f, uint32_t a, uint32_t b, uint32_t t) const;

    const Mesh& mesh_;
    Topology topo_;
    PtexMap keys_;
    const FaceVaryingSurface& surface_;
    uint32_t Q_; // the lattice of keys_: twice the resolution
    std::vector<uint32_t> firstPtex_;
    std::unordered_map<uint64_t, std::unordered_map<uint32_t, glm::vec2>> memo_; // point -> face -> UV
    std::vector<Located> located_, ends_[2];
};

} // namespace limn
