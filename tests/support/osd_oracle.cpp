#include "osd_oracle.h"

#include "osd_descriptor.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <glm/geometric.hpp>

#include <map>
#include <set>
#include <stdexcept>

namespace limn::test {

namespace {

using namespace OpenSubdiv;

struct Point {
    double p[3] = {0, 0, 0};
    void Clear() { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Point& s, double w) {
        p[0] += w * s.p[0];
        p[1] += w * s.p[1];
        p[2] += w * s.p[2];
    }
};

Far::TopologyRefiner* makeRefiner(const Mesh& mesh, const SchemeOptions& options) {
    return makeOsdRefiner(mesh, options);
}

} // namespace

struct OsdLimitSurface::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> table;
    std::unique_ptr<Far::PatchMap> map;
    std::vector<Point> verts;
    int ptexCount = 0;
};

OsdLimitSurface::OsdLimitSurface(const Mesh& mesh, const SchemeOptions& options, int isolation)
    : impl_(std::make_unique<Impl>()) {
    impl_->refiner.reset(makeRefiner(mesh, options));
    Far::PatchTableFactory::Options po(isolation);
    po.SetPatchPrecision<double>();
    po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    po.useInfSharpPatch = true;
    po.generateLegacySharpCornerPatches = false;
    impl_->refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    impl_->table.reset(Far::PatchTableFactory::Create(*impl_->refiner, po));
    int nRef = impl_->refiner->GetNumVerticesTotal();
    int nLoc = impl_->table->GetNumLocalPoints();
    impl_->verts.resize(nRef + nLoc);
    for (size_t i = 0; i < mesh.vertexCount(); ++i)
        for (int k = 0; k < 3; ++k) impl_->verts[i].p[k] = mesh.positions[i][k];
    Far::PrimvarRefinerReal<double> pr(*impl_->refiner);
    Point* src = impl_->verts.data();
    for (int l = 1; l < impl_->refiner->GetNumLevels(); ++l) {
        Point* dst = src + impl_->refiner->GetLevel(l - 1).GetNumVertices();
        pr.Interpolate(l, src, dst);
        src = dst;
    }
    if (nLoc)
        impl_->table->GetLocalPointStencilTable<double>()->UpdateValues(impl_->verts.data(),
                                                                        impl_->verts.data() + nRef);
    impl_->map = std::make_unique<Far::PatchMap>(*impl_->table);
    impl_->ptexCount = Far::PtexIndices(*impl_->refiner).GetNumFaces();
}

OsdLimitSurface::~OsdLimitSurface() = default;

int OsdLimitSurface::ptexFaceCount() const { return impl_->ptexCount; }

bool OsdLimitSurface::evaluate(int ptex, double u, double v, glm::dvec3& P, glm::dvec3& N) const {
    return evaluate(ptex, u, v, u, v, P, N);
}

bool OsdLimitSurface::evaluate(int ptex, double u, double v, double iu, double iv, glm::dvec3& P,
                               glm::dvec3& N) const {
    const auto* h = impl_->map->FindPatch(ptex, iu, iv);
    if (!h) return false;
    // EvaluateBasis takes ptex coordinates and maps them into the patch itself.
    double wP[20], wDu[20], wDv[20];
    impl_->table->EvaluateBasis(*h, u, v, wP, wDu, wDv);
    Far::ConstIndexArray cv = impl_->table->GetPatchVertices(*h);
    glm::dvec3 pos(0.0), du(0.0), dv(0.0);
    for (int i = 0; i < cv.size(); ++i) {
        const Point& q = impl_->verts[cv[i]];
        glm::dvec3 x(q.p[0], q.p[1], q.p[2]);
        pos += wP[i] * x;
        du += wDu[i] * x;
        dv += wDv[i] * x;
    }
    P = pos;
    N = glm::normalize(glm::cross(du, dv));
    return true;
}

std::vector<std::vector<glm::dvec3>> osdUniformLevels(const Mesh& mesh, const SchemeOptions& options,
                                                      int depth) {
    std::unique_ptr<Far::TopologyRefiner> r(makeRefiner(mesh, options));
    Far::TopologyRefiner::UniformOptions uo(depth);
    uo.fullTopologyInLastLevel = true;
    r->RefineUniform(uo);
    std::vector<Point> buf(r->GetNumVerticesTotal());
    for (size_t i = 0; i < mesh.vertexCount(); ++i)
        for (int k = 0; k < 3; ++k) buf[i].p[k] = mesh.positions[i][k];
    Far::PrimvarRefinerReal<double> pr(*r);
    Point* src = buf.data();
    std::vector<std::vector<glm::dvec3>> out;
    size_t offset = 0;
    for (int l = 0; l <= depth; ++l) {
        int n = r->GetLevel(l).GetNumVertices();
        if (l > 0) {
            Point* dst = src + r->GetLevel(l - 1).GetNumVertices();
            pr.Interpolate(l, src, dst);
            src = dst;
        }
        std::vector<glm::dvec3> level(n);
        for (int i = 0; i < n; ++i)
            level[i] = {buf[offset + i].p[0], buf[offset + i].p[1], buf[offset + i].p[2]};
        offset += n;
        out.push_back(std::move(level));
    }
    return out;
}

std::vector<uint8_t> smoothCorners(const Mesh& m, const SchemeOptions& o) {
    // Edges with their face counts, and which are infinitely sharp (boundaries, tags >= 10).
    std::map<std::pair<uint32_t, uint32_t>, int> faces;
    auto key = [](uint32_t a, uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
    for (size_t f = 0; f < m.faceCount(); ++f) {
        auto face = m.face(f);
        for (size_t k = 0; k < face.size(); ++k) ++faces[key(face[k], face[(k + 1) % face.size()])];
    }
    std::set<std::pair<uint32_t, uint32_t>> sharp;
    for (const auto& [e, n] : faces)
        if (n == 1) sharp.insert(e);
    for (const auto& c : m.tags.creases)
        if (c.sharpness >= Sdc::Crease::SHARPNESS_INFINITE) sharp.insert(key(c.v0, c.v1));
    std::vector<int> sharpEdges(m.vertexCount(), 0), faceCount(m.vertexCount(), 0);
    for (const auto& e : sharp) ++sharpEdges[e.first], ++sharpEdges[e.second];
    std::vector<uint8_t> cornerTag(m.vertexCount(), 0);
    for (const auto& c : m.tags.corners)
        if (c.sharpness >= Sdc::Crease::SHARPNESS_INFINITE) cornerTag[c.vertex] = 1;
    std::vector<uint8_t> out(m.vertexCount(), 0);
    for (size_t f = 0; f < m.faceCount(); ++f) {
        auto face = m.face(f);
        const size_t n = face.size();
        for (size_t k = 0; k < n; ++k) {
            const uint32_t v = face[k];
            ++faceCount[v];
            // Both of the face's edges at v sharp: a sector of one face.
            if (sharp.count(key(v, face[(k + 1) % n])) && sharp.count(key(face[(k + n - 1) % n], v)))
                out[v] = 1;
        }
    }
    for (size_t v = 0; v < m.vertexCount(); ++v) {
        // The crease rule needs exactly two sharp edges and no corner; edge-and-corner makes a
        // boundary vertex of one face a corner. None does not: a face at the boundary is drawn only
        // where tags sharpen its boundary edges (catmark_edgenone), and a vertex of one face
        // with two of them follows the crease rule, as under edge-only.
        const bool boundaryCorner = o.boundary == BoundaryRule::EdgeAndCorner && faceCount[v] == 1;
        if (sharpEdges[v] != 2 || cornerTag[v] || boundaryCorner) out[v] = 0;
    }
    return out;
}

int baseVertexAt(const Mesh& m, uint32_t ptex, double u, double v) {
    uint32_t id = 0;
    for (size_t f = 0; f < m.faceCount(); ++f) {
        uint32_t n = m.faceSize(f), count = n == 4 ? 1 : n;
        if (ptex < id + count) {
            if (n == 4) {
                if ((u != 0 && u != 1) || (v != 0 && v != 1)) return -1;
                int corner = u == 0 ? (v == 0 ? 0 : 3) : (v == 0 ? 1 : 2);
                return int(m.face(f)[corner]);
            }
            return (u == 0 && v == 0) ? int(m.face(f)[ptex - id]) : -1;
        }
        id += count;
    }
    return -1;
}

Mesh osdUniformRefinedMesh(const Mesh& mesh, const SchemeOptions& options, int levels) {
    std::unique_ptr<Far::TopologyRefiner> r(makeRefiner(mesh, options));
    Far::TopologyRefiner::UniformOptions uo(levels);
    uo.fullTopologyInLastLevel = true;
    r->RefineUniform(uo);
    const std::vector<glm::dvec3> positions = osdUniformLevels(mesh, options, levels).back();
    const Far::TopologyLevel& last = r->GetLevel(levels);
    Mesh out;
    out.positions = positions;
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        std::vector<uint32_t> face(fv.begin(), fv.end());
        out.addFace(face);
        if (last.IsFaceHole(f)) out.tags.holes.push_back(static_cast<uint32_t>(f));
    }
    // What sharpness is left after `levels` steps, so the refined mesh has the same limit.
    for (int e = 0; e < last.GetNumEdges(); ++e) {
        // Far marks boundary edges infinitely sharp itself; they need no tag.
        const float s = last.GetEdgeSharpness(e);
        if (s <= 0 || last.IsEdgeBoundary(e)) continue;
        Far::ConstIndexArray ev = last.GetEdgeVertices(e);
        out.tags.creases.push_back({static_cast<uint32_t>(ev[0]), static_cast<uint32_t>(ev[1]), s});
    }
    for (int v = 0; v < last.GetNumVertices(); ++v)
        // Far sharpens boundary corners itself under the edge-and-corner rule.
        if (const float s = last.GetVertexSharpness(v);
            s > 0 && !(last.IsVertexBoundary(v) && s >= Sdc::Crease::SHARPNESS_INFINITE &&
                       options.boundary == BoundaryRule::EdgeAndCorner))
            out.tags.corners.push_back({static_cast<uint32_t>(v), s});
    out.tags.boundary = options.boundary;
    out.tags.creaseMethod = options.creaseMethod;
    out.tags.triangles = options.triangles;
    return out;
}

OsdPatchCounts osdPatchCounts(const Mesh& mesh, const SchemeOptions& options, int isolation,
                              bool infSharpPatches, bool singleCreasePatches) {
    std::unique_ptr<Far::TopologyRefiner> refiner(makeRefiner(mesh, options));
    Far::PatchTableFactory::Options po(isolation);
    po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    po.useInfSharpPatch = infSharpPatches;
    po.useSingleCreasePatch = singleCreasePatches;
    po.generateLegacySharpCornerPatches = false;
    refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    std::unique_ptr<Far::PatchTable> table(Far::PatchTableFactory::Create(*refiner, po));
    OsdPatchCounts c;
    for (int a = 0; a < table->GetNumPatchArrays(); ++a) {
        const auto type = table->GetPatchArrayDescriptor(a).GetType();
        for (int i = 0; i < table->GetNumPatches(a); ++i) {
            if (type == Far::PatchDescriptor::REGULAR) {
                ++c.regular;
                if (table->GetPatchParam(a, i).GetBoundary() != 0) ++c.boundary;
                if (singleCreasePatches && table->GetSingleCreasePatchSharpnessValue(a, i) > 0)
                    ++c.singleCrease;
            } else if (type == Far::PatchDescriptor::GREGORY_BASIS) {
                ++c.gregory;
            } else {
                ++c.other;
            }
        }
    }
    c.bytes = 4 * size_t(table->GetNumControlVerticesTotal()) + 8 * size_t(table->GetNumPatchesTotal());
    if (singleCreasePatches) c.bytes += 8 * size_t(table->GetNumPatchesTotal());
    Far::StencilTableFactory::Options so;
    so.generateIntermediateLevels = true;
    so.generateOffsets = true;
    std::unique_ptr<const Far::StencilTable> st(Far::StencilTableFactory::Create(*refiner, so));
    const Far::StencilTable* local = table->GetLocalPointStencilTable();
    for (const Far::StencilTable* t : {st.get(), local})
        if (t) c.bytes += 8 * size_t(t->GetNumStencils()) + 8 * t->GetControlIndices().size();
    return c;
}

} // namespace limn::test
