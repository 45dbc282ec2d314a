// Adapters that let OpenSubdiv's Sdc::Scheme<CATMARK> compute subdivision masks on limn's own
// levels, so limn's stencils use exactly OpenSubdiv's rules (creases with fractional sharpness,
// Chaikin, corners, boundaries, smooth triangles) without its topology refiner.
#pragma once

#include "subdiv/level.h"

#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/options.h>

#include <vector>

namespace limn {

OpenSubdiv::Sdc::Options toSdcOptions(const SchemeOptions& options);

// A mask as Sdc fills it: weights on the vertex, on the far end of each incident edge, and on
// each incident face (its centre, i.e. the child face point, for Catmark interpolation masks).
struct SdcMask {
    using Weight = double;
    std::vector<double> vertexWeights, edgeWeights, faceWeights;
    int vCount = 0, eCount = 0, fCount = 0;
    bool faceCenters = false;

    explicit SdcMask(int maxValence)
        : vertexWeights(2), edgeWeights(maxValence), faceWeights(maxValence) {} // 2: edge masks
    int GetNumVertexWeights() const { return vCount; }
    int GetNumEdgeWeights() const { return eCount; }
    int GetNumFaceWeights() const { return fCount; }
    void SetNumVertexWeights(int n) { vCount = n; }
    void SetNumEdgeWeights(int n) { eCount = n; }
    void SetNumFaceWeights(int n) { fCount = n; }
    double& VertexWeight(int i) { return vertexWeights[i]; }
    double& EdgeWeight(int i) { return edgeWeights[i]; }
    double& FaceWeight(int i) { return faceWeights[i]; }
    const double& VertexWeight(int i) const { return vertexWeights[i]; }
    const double& EdgeWeight(int i) const { return edgeWeights[i]; }
    const double& FaceWeight(int i) const { return faceWeights[i]; }
    bool AreFaceWeightsForFaceCenters() const { return faceCenters; }
    void SetFaceWeightsForFaceCenters(bool on) { faceCenters = on; }
};

// The neighbourhood of a complete, manifold vertex in counter-clockwise order: edges e_0..e_m
// (m = k faces for an interior vertex, k+1 for a boundary one) and faces f_0..f_{k-1}, face i
// between edges i and i+1 (the order Vtr uses and the limit tangent masks need).
struct VertexNeighborhood {
    uint32_t vertex = 0;
    std::vector<uint32_t> edges;      // topology edge ids
    std::vector<uint32_t> ringVertex; // far end of each edge
    std::vector<uint32_t> faces;      // face ids
    std::vector<uint32_t> diagonal;   // for quads: the vertex opposite `vertex` in each face
    bool boundary = false;
};

void gatherNeighborhood(const Topology& topo, uint32_t v, VertexNeighborhood& out);

// Sdc's VERTEX interface over a gathered neighbourhood.
class SdcVertex {
public:
    // `scratch` holds the ring's edge sharpness; reused between vertices to avoid allocations.
    SdcVertex(const VertexNeighborhood& hood, const std::vector<float>& edgeSharpness,
              float vertexSharpness, float childVertexSharpness, std::vector<float>& scratch)
        : hood_(hood), sharp_(scratch), vertexSharpness_(vertexSharpness),
          childSharpness_(childVertexSharpness) {
        sharp_.clear();
        for (uint32_t e : hood.edges) sharp_.push_back(edgeSharpness[e]);
    }
    int GetNumEdges() const { return static_cast<int>(hood_.edges.size()); }
    int GetNumFaces() const { return static_cast<int>(hood_.faces.size()); }
    float GetSharpness() const { return vertexSharpness_; }
    float* GetSharpnessPerEdge(float* out) const {
        for (size_t i = 0; i < sharp_.size(); ++i) out[i] = sharp_[i];
        return out;
    }
    float GetChildSharpness(const OpenSubdiv::Sdc::Crease&) const { return childSharpness_; }
    float* GetChildSharpnessPerEdge(const OpenSubdiv::Sdc::Crease& crease, float* out) const {
        crease.SubdivideEdgeSharpnessesAroundVertex(GetNumEdges(), sharp_.data(), out);
        return out;
    }

private:
    const VertexNeighborhood& hood_;
    std::vector<float>& sharp_;
    float vertexSharpness_, childSharpness_;
};

// Sdc's EDGE interface.
class SdcEdge {
public:
    SdcEdge(const Topology& topo, uint32_t edge, float sharpness) : sharpness_(sharpness) {
        uint32_t h = topo.edgeHalfedge(edge);
        sizes_[0] = static_cast<int>(topo.faceSize(topo.face(h)));
        faces_ = 1;
        if (topo.twin(h) != kNone) sizes_[faces_++] = static_cast<int>(topo.faceSize(topo.face(topo.twin(h))));
    }
    int GetNumFaces() const { return faces_; }
    float GetSharpness() const { return sharpness_; }
    void GetChildSharpnesses(const OpenSubdiv::Sdc::Crease&, float s[2]) const {
        s[0] = s[1] = sharpness_ - 1.0f; // as Vtr's EdgeInterface; only used without a child rule
    }
    void GetNumVerticesPerFace(int* out) const {
        for (int i = 0; i < faces_; ++i) out[i] = sizes_[i];
    }

private:
    float sharpness_;
    int faces_ = 0;
    int sizes_[2] = {0, 0};
};

} // namespace limn
