#include "osd_oracle.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <stdexcept>

namespace limn::test {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

struct P3 {
    double v[3];
    void Clear() { v[0] = v[1] = v[2] = 0; }
    void AddWithWeight(const P3& s, double w) {
        for (int i = 0; i < 3; ++i) v[i] += w * s.v[i];
    }
};
struct P2 {
    double v[2];
    void Clear() { v[0] = v[1] = 0; }
    void AddWithWeight(const P2& s, double w) {
        for (int i = 0; i < 2; ++i) v[i] += w * s.v[i];
    }
};

} // namespace

OsdLoop osdUniformLoop(const Mesh& mesh, int levels) {
    std::vector<int> vertsPerFace(mesh.faceCount()), faceVerts(mesh.faceVertices.begin(), mesh.faceVertices.end());
    for (size_t f = 0; f < mesh.faceCount(); ++f) vertsPerFace[f] = static_cast<int>(mesh.faceSize(f));
    std::vector<int> creasePairs, corners;
    std::vector<float> creaseWeights, cornerWeights;
    for (const auto& c : mesh.tags.creases) {
        creasePairs.push_back(static_cast<int>(c.v0));
        creasePairs.push_back(static_cast<int>(c.v1));
        creaseWeights.push_back(c.sharpness);
    }
    for (const auto& c : mesh.tags.corners) {
        corners.push_back(static_cast<int>(c.vertex));
        cornerWeights.push_back(c.sharpness);
    }
    std::vector<int> uvIndices(mesh.uvIndices.begin(), mesh.uvIndices.end());

    Far::TopologyDescriptor desc;
    desc.numVertices = static_cast<int>(mesh.vertexCount());
    desc.numFaces = static_cast<int>(mesh.faceCount());
    desc.numVertsPerFace = vertsPerFace.data();
    desc.vertIndicesPerFace = faceVerts.data();
    desc.numCreases = static_cast<int>(creaseWeights.size());
    desc.creaseVertexIndexPairs = creasePairs.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = static_cast<int>(cornerWeights.size());
    desc.cornerVertexIndices = corners.data();
    desc.cornerWeights = cornerWeights.data();
    Far::TopologyDescriptor::FVarChannel channel;
    if (mesh.hasUVs()) {
        channel.numValues = static_cast<int>(mesh.uvs.size());
        channel.valueIndices = uvIndices.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &channel;
    }

    Sdc::Options options;
    // limn's BoundaryRule is numbered like Sdc's VtxBoundaryInterpolation (OBJ tags differ).
    switch (mesh.tags.boundary.value_or(BoundaryRule::EdgeOnly)) {
    case BoundaryRule::None: options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE); break;
    case BoundaryRule::EdgeOnly: options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY); break;
    case BoundaryRule::EdgeAndCorner:
        options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        break;
    }
    options.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    OsdLoop out;
    out.refiner.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, options)));
    if (!out.refiner) throw std::runtime_error("OpenSubdiv refused the mesh");
    if (levels > 0) {
        Far::TopologyRefiner::UniformOptions uo(levels);
        uo.fullTopologyInLastLevel = true;
        out.refiner->RefineUniform(uo);
    }

    Far::PrimvarRefinerReal<double> pr(*out.refiner);
    std::vector<P3> pos(mesh.vertexCount());
    for (size_t v = 0; v < mesh.vertexCount(); ++v)
        pos[v] = {{mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z}};
    std::vector<P2> uv(mesh.uvs.size());
    for (size_t i = 0; i < mesh.uvs.size(); ++i) uv[i] = {{mesh.uvs[i].x, mesh.uvs[i].y}};
    auto store = [&]() {
        std::vector<glm::dvec3> p(pos.size());
        for (size_t i = 0; i < pos.size(); ++i) p[i] = {pos[i].v[0], pos[i].v[1], pos[i].v[2]};
        out.positions.push_back(std::move(p));
        std::vector<glm::dvec2> t(uv.size());
        for (size_t i = 0; i < uv.size(); ++i) t[i] = {uv[i].v[0], uv[i].v[1]};
        out.uvs.push_back(std::move(t));
    };
    store();
    for (int l = 1; l <= levels; ++l) {
        std::vector<P3> next(out.refiner->GetLevel(l).GetNumVertices());
        P3* src = pos.data();
        P3* dst = next.data();
        pr.Interpolate(l, src, dst);
        pos = std::move(next);
        if (mesh.hasUVs()) {
            std::vector<P2> nextUV(out.refiner->GetLevel(l).GetNumFVarValues(0));
            P2* usrc = uv.data();
            P2* udst = nextUV.data();
            pr.InterpolateFaceVarying(l, usrc, udst, 0);
            uv = std::move(nextUV);
        }
        store();
    }
    std::vector<P3> lim(pos.size());
    P3* src = pos.data();
    P3* dst = lim.data();
    pr.Limit(src, dst);
    for (const P3& p : lim) out.limit.push_back({p.v[0], p.v[1], p.v[2]});
    return out;
}

} // namespace limn::test
