// An OpenSubdiv topology refiner for a limn Mesh, as the test oracles build it (osd_oracle.cpp,
// osd_fvar_oracle.cpp): faces, creases, corners and holes, optionally the UVs as face-varying
// channel 0, and limn's scheme options as Sdc::Options.
#pragma once

#include "mesh/mesh.h"
#include "topology/features.h"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <stdexcept>
#include <vector>

namespace limn::test {

inline OpenSubdiv::Sdc::Options osdSchemeOptions(const SchemeOptions& o) {
    using OpenSubdiv::Sdc::Options;
    Options s;
    s.SetVtxBoundaryInterpolation(o.boundary == BoundaryRule::None       ? Options::VTX_BOUNDARY_NONE
                                  : o.boundary == BoundaryRule::EdgeOnly ? Options::VTX_BOUNDARY_EDGE_ONLY
                                                                         : Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    s.SetFVarLinearInterpolation(static_cast<Options::FVarLinearInterpolation>(o.fvar));
    s.SetCreasingMethod(o.creaseMethod == CreaseMethod::Chaikin ? Options::CREASE_CHAIKIN : Options::CREASE_UNIFORM);
    s.SetTriangleSubdivision(o.triangles == TriangleSubdivision::Smooth ? Options::TRI_SUB_SMOOTH
                                                                        : Options::TRI_SUB_CATMARK);
    return s;
}

// The caller owns the refiner. withUVs: the mesh's UVs (uvIndices) as face-varying channel 0.
inline OpenSubdiv::Far::TopologyRefiner* makeOsdRefiner(const Mesh& m, const SchemeOptions& options,
                                                        bool withUVs = false) {
    using namespace OpenSubdiv;
    std::vector<int> sizes, verts(m.faceVertices.begin(), m.faceVertices.end()), creaseVerts, cornerVerts,
        holes(m.tags.holes.begin(), m.tags.holes.end()), uvIndices;
    std::vector<float> creaseWeights, cornerWeights;
    for (size_t f = 0; f < m.faceCount(); ++f) sizes.push_back(static_cast<int>(m.faceSize(f)));
    for (const auto& c : m.tags.creases) {
        creaseVerts.push_back(static_cast<int>(c.v0));
        creaseVerts.push_back(static_cast<int>(c.v1));
        creaseWeights.push_back(c.sharpness);
    }
    for (const auto& c : m.tags.corners) {
        cornerVerts.push_back(static_cast<int>(c.vertex));
        cornerWeights.push_back(c.sharpness);
    }
    Far::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(m.vertexCount());
    desc.numFaces = static_cast<int>(m.faceCount());
    desc.numVertsPerFace = sizes.data();
    desc.vertIndicesPerFace = verts.data();
    desc.numCreases = static_cast<int>(creaseWeights.size());
    desc.creaseVertexIndexPairs = creaseVerts.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = static_cast<int>(cornerWeights.size());
    desc.cornerVertexIndices = cornerVerts.data();
    desc.cornerWeights = cornerWeights.data();
    desc.numHoles = static_cast<int>(holes.size());
    desc.holeIndices = holes.data();
    Far::TopologyDescriptor::FVarChannel channel;
    if (withUVs) {
        uvIndices.assign(m.uvIndices.begin(), m.uvIndices.end());
        channel.numValues = static_cast<int>(m.uvs.size());
        channel.valueIndices = uvIndices.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &channel;
    }
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    auto* r = Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, osdSchemeOptions(options)));
    if (!r) throw std::runtime_error("OpenSubdiv refused the mesh");
    return r;
}

} // namespace limn::test
