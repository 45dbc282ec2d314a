// OpenSubdiv's ptex parameterization of a control mesh (opensubdiv.md, "ptex indexing"): one
// ptex face per quad, n per n-gon (sub-face k: (0,0) at corner k, u toward the midpoint of edge
// (k, k+1), v toward the midpoint of edge (k-1, k), (1,1) at the centroid). PtexMap names every
// point (ptex, U/R, V/R) canonically, so the same surface point reached from two ptex faces gets
// the same key, and tells which base faces contain it and where in each face's UV chart.
#pragma once

#include "mesh/mesh.h"
#include "topology/topology.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace limn {

class PtexMap {
  public:
    // `resolution` R (a power of two <= 2^16): points are (U, V) in [0, R]^2.
    PtexMap(const Mesh& mesh, const Topology& topo, uint32_t resolution);

    uint32_t ptexCount() const { return static_cast<uint32_t>(ptex_.size()); }
    uint32_t baseFace(uint32_t ptex) const { return ptex_[ptex].face; }
    int32_t subFace(uint32_t ptex) const { return ptex_[ptex].sub; } // -1 for quads

    // A 64-bit key equal for equal surface points: base vertex, base edge + position along it,
    // n-gon spoke + position, n-gon centroid, or a point inside a ptex face.
    uint64_t key(uint32_t ptex, uint32_t U, uint32_t V) const;
    // Whether a key names a base vertex (whose charts are every face around it).
    static bool isBaseVertexKey(uint64_t key);

    // The UV of the point in each base face that contains it (its face-varying chart, refined
    // linearly: bilinear in quads, in n-gon sub-faces through edge midpoints and the centroid),
    // in increasing face order. Requires the mesh to have UVs.
    struct ChartUV {
        uint32_t face;
        glm::dvec2 uv;
    };
    void charts(uint32_t ptex, uint32_t U, uint32_t V, std::vector<ChartUV>& out) const;

    // The point's UV in the chart of the base face of `ptex` itself.
    glm::dvec2 ownUV(uint32_t ptex, double u, double v) const;

  private:
    struct PtexFace {
        uint32_t face;
        int32_t sub;
    };
    uint64_t onEdge(uint32_t a, uint32_t b, uint32_t t) const;
    glm::dvec2 cornerUV(uint32_t halfedge) const; // UV of a face corner (a halfedge's start)

    const Mesh& mesh_;
    const Topology& topo_;
    uint32_t R_;
    std::vector<PtexFace> ptex_;
    std::vector<uint32_t> firstPtex_; // per base face
    std::vector<glm::dvec2> centroidUV_; // per base face: an n-gon's UV centroid (with UVs)
};

} // namespace limn
