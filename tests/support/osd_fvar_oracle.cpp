#include "osd_fvar_oracle.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <stdexcept>
#include <vector>

namespace limn::test {

namespace {

using namespace OpenSubdiv;

struct Value {
    double p[2] = {0, 0};
    void Clear() { p[0] = p[1] = 0; }
    void AddWithWeight(const Value& s, double w) {
        p[0] += w * s.p[0];
        p[1] += w * s.p[1];
    }
};

Sdc::Options sdcOptions(const SchemeOptions& o) {
    Sdc::Options s;
    s.SetVtxBoundaryInterpolation(o.boundary == BoundaryRule::None ? Sdc::Options::VTX_BOUNDARY_NONE
                                  : o.boundary == BoundaryRule::EdgeOnly
                                      ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    s.SetFVarLinearInterpolation(static_cast<Sdc::Options::FVarLinearInterpolation>(o.fvar));
    s.SetCreasingMethod(o.creaseMethod == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                : Sdc::Options::CREASE_UNIFORM);
    s.SetTriangleSubdivision(o.triangles == TriangleSubdivision::Smooth ? Sdc::Options::TRI_SUB_SMOOTH
                                                                        : Sdc::Options::TRI_SUB_CATMARK);
    return s;
}

} // namespace

struct OsdFaceVarying::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> table;
    std::unique_ptr<Far::PatchMap> map;
    std::vector<Value> values;
};

OsdFaceVarying::OsdFaceVarying(const Mesh& m, const SchemeOptions& options, int isolation)
    : impl_(std::make_unique<Impl>()) {
    std::vector<int> sizes, verts(m.faceVertices.begin(), m.faceVertices.end()), creaseVerts, cornerVerts,
        holes(m.tags.holes.begin(), m.tags.holes.end()), uvIndices(m.uvIndices.begin(), m.uvIndices.end());
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
    Far::TopologyDescriptor::FVarChannel channel;
    channel.numValues = static_cast<int>(m.uvs.size());
    channel.valueIndices = uvIndices.data();
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
    desc.numFVarChannels = 1;
    desc.fvarChannels = &channel;
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    impl_->refiner.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdcOptions(options))));
    if (!impl_->refiner) throw std::runtime_error("OpenSubdiv refused the mesh");

    Far::PatchTableFactory::Options po(isolation);
    po.SetPatchPrecision<double>();
    po.SetFVarPatchPrecision<double>();
    po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    po.useInfSharpPatch = true;
    po.generateLegacySharpCornerPatches = false;
    po.generateFVarTables = true;
    po.generateFVarLegacyLinearPatches = false; // smooth face-varying patches; isolates them too
    impl_->refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    impl_->table.reset(Far::PatchTableFactory::Create(*impl_->refiner, po));

    const int total = impl_->refiner->GetNumFVarValuesTotal(0);
    const auto* local = impl_->table->GetLocalPointFaceVaryingStencilTable<double>(0);
    const int nLocal = local ? local->GetNumStencils() : 0;
    impl_->values.resize(total + nLocal);
    for (size_t i = 0; i < m.uvs.size(); ++i) impl_->values[i].p[0] = m.uvs[i].x, impl_->values[i].p[1] = m.uvs[i].y;
    Far::PrimvarRefinerReal<double> pr(*impl_->refiner);
    Value* src = impl_->values.data();
    for (int l = 1; l < impl_->refiner->GetNumLevels(); ++l) {
        Value* dst = src + impl_->refiner->GetLevel(l - 1).GetNumFVarValues(0);
        pr.InterpolateFaceVarying(l, src, dst, 0);
        src = dst;
    }
    if (nLocal) local->UpdateValues(impl_->values.data(), impl_->values.data() + total);
    impl_->map = std::make_unique<Far::PatchMap>(*impl_->table);
}

OsdFaceVarying::~OsdFaceVarying() = default;

bool OsdFaceVarying::evaluate(int ptex, double u, double v, double iu, double iv, glm::dvec2& uv) const {
    const auto* h = impl_->map->FindPatch(ptex, iu, iv);
    if (!h) return false;
    double w[20];
    impl_->table->EvaluateBasisFaceVarying(*h, u, v, w, nullptr, nullptr, nullptr, nullptr, nullptr, 0);
    Far::ConstIndexArray cv = impl_->table->GetPatchFVarValues(*h, 0);
    glm::dvec2 x(0.0);
    for (int i = 0; i < cv.size(); ++i) x += w[i] * glm::dvec2(impl_->values[cv[i]].p[0], impl_->values[cv[i]].p[1]);
    uv = x;
    return true;
}

} // namespace limn::test
