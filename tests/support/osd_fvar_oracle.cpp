#include "osd_fvar_oracle.h"

#include "osd_descriptor.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>

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

} // namespace

struct OsdFaceVarying::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> table;
    std::unique_ptr<Far::PatchMap> map;
    std::vector<Value> values;
};

OsdFaceVarying::OsdFaceVarying(const Mesh& m, const SchemeOptions& options, int isolation)
    : impl_(std::make_unique<Impl>()) {
    impl_->refiner.reset(makeOsdRefiner(m, options, /*withUVs=*/true));

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
