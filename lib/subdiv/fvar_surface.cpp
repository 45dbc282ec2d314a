#include "subdiv/fvar_surface.h"

#include "subdiv/evaluate.h"

#include "base/error.h"
#include "topology/topology.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <string>

namespace limn {

namespace {

// One span of faces around a base vertex that share face-varying continuous edges: a vertex of
// the UV mesh (OpenSubdiv's ValueSpan, fvarLevel.cpp).
struct Span {
    uint32_t value = 0;       // the UV index of its faces' corners
    uint32_t size = 0;        // faces
    uint32_t infSharpEdges = 0, semiSharpEdges = 0; // interior edges of the span
    float maxSemiSharpness = 0;
};

} // namespace

Mesh faceVaryingMesh(const Mesh& mesh, const SchemeOptions& o) {
    if (!mesh.hasUVs()) throw Error(ErrorKind::BadInput, "the mesh has no texture coordinates to smooth");
    const uint32_t nv = static_cast<uint32_t>(mesh.vertexCount());
    Topology topo(nv, mesh.faceOffsets, mesh.faceVertices);
    Warnings quiet;
    const Sharpness sharp = baseSharpness(topo, mesh.tags, o.boundary, quiet);
    const FVarRule mode = o.fvar;
    const bool plus = mode == FVarRule::CornersPlus1 || mode == FVarRule::CornersPlus2;
    const bool linearBoundaries = mode == FVarRule::Boundaries; // (All never gets here)
    const bool fvarCornersAreSharp = mode != FVarRule::LinearNone;
    const bool makeSmoothCornersSharp = o.boundary != BoundaryRule::EdgeAndCorner && fvarCornersAreSharp;
    const bool sharpenBothIfOneCorner = mode == FVarRule::CornersPlus2;
    const bool sharpenDarts = sharpenBothIfOneCorner || linearBoundaries;

    Mesh uv;
    uv.faceOffsets = mesh.faceOffsets;
    uv.faceVertices.assign(mesh.cornerCount(), kNone); // per corner: its UV-mesh vertex
    uv.tags.holes = mesh.tags.holes;
    uv.tags.boundary = BoundaryRule::EdgeOnly; // corners are sharpened explicitly below
    uv.tags.creaseMethod = o.creaseMethod;
    uv.tags.triangles = o.triangles;
    for (uint32_t f = 0; f < sharp.faceNoLimit.size(); ++f)
        if (sharp.faceNoLimit[f] && !std::count(uv.tags.holes.begin(), uv.tags.holes.end(), f))
            uv.tags.holes.push_back(f);

    const auto& U = mesh.uvIndices;
    // An edge between the faces of outgoing half-edges h (before) and g (after, = twin(prev(h)))
    // is face-varying continuous when both its ends have the same UV in both faces.
    auto continuous = [&](uint32_t h, uint32_t g) {
        return U[h] == U[g] && U[topo.prev(h)] == U[topo.next(g)];
    };
    std::vector<uint32_t> ring;
    std::vector<Span> spans;
    std::vector<uint32_t> spanOf; // per ring position
    for (uint32_t v = 0; v < nv; ++v) {
        if (topo.vertexIsIsolated(v)) continue;
        if (topo.vertexIsNonManifold(v))
            throw Error(ErrorKind::BadInput, "vertex " + std::to_string(v) +
                                                 " is non-manifold; smooth face-varying UVs need a manifold mesh");
        topo.vertexRing(v, ring);
        const uint32_t m = static_cast<uint32_t>(ring.size());
        const bool boundary = topo.vertexIsBoundary(v);
        // Split the fan into spans at discontinuous edges (between ring[i] and ring[i+1]).
        std::vector<uint8_t> cont(m, 0);
        bool mismatched = false;
        for (uint32_t i = 0; i < m; ++i) {
            if (boundary && i + 1 == m) break;
            cont[i] = continuous(ring[i], ring[(i + 1) % m]);
            mismatched |= !cont[i];
        }
        // Geometric boundaries count as face-varying boundaries where the mode treats them so.
        if (boundary && !mismatched)
            mismatched = linearBoundaries || (m == 1 && makeSmoothCornersSharp);
        // Spans: start after a discontinuity (or at the boundary / at 0 when all continuous).
        uint32_t start = 0;
        if (!boundary)
            for (uint32_t i = 0; i < m; ++i)
                if (!cont[(i + m - 1) % m]) {
                    start = i;
                    break;
                }
        spans.clear();
        spanOf.assign(m, 0);
        for (uint32_t k = 0; k < m; ++k) {
            uint32_t i = (start + k) % m;
            if (k == 0 || !cont[(i + m - 1) % m]) spans.push_back({U[ring[i]]});
            Span& s = spans.back();
            ++s.size;
            spanOf[i] = static_cast<uint32_t>(spans.size() - 1);
            if (k + 1 < m && cont[i]) { // the interior edge to the next face of this span
                float e = sharp.edge[topo.edge(topo.prev(ring[i]))];
                if (e >= kInfiniteSharpness) ++s.infSharpEdges;
                else if (e > 0) ++s.semiSharpEdges, s.maxSemiSharpness = std::max(s.maxSemiSharpness, e);
            }
        }
        const uint32_t firstVertex = static_cast<uint32_t>(uv.positions.size());
        for (uint32_t i = 0; i < m; ++i) uv.faceVertices[ring[i]] = firstVertex + spanOf[i];
        for (const Span& s : spans) uv.positions.push_back(glm::dvec3(mesh.uvs[s.value], 0.0));
        const float vs = sharp.vertex[v];
        if (vs > 0)
            for (uint32_t k = 0; k < spans.size(); ++k) uv.tags.corners.push_back({firstVertex + k, vs});
        if (!mismatched) continue;

        // OpenSubdiv's sharpening of the values of a mismatched vertex (fvarLevel.cpp): per value
        // (spans with the same UV index together), corner or smooth boundary.
        std::map<uint32_t, Span> values;
        std::map<uint32_t, uint32_t> spanCount;
        for (const Span& s : spans) {
            Span& x = values[s.value];
            x.value = s.value;
            x.size += s.size;
            x.infSharpEdges += s.infSharpEdges;
            x.semiSharpEdges += s.semiSharpEdges;
            x.maxSemiSharpness = std::max(x.maxSemiSharpness, s.maxSemiSharpness);
            ++spanCount[s.value];
        }
        const size_t n = values.size();
        bool allSharp = linearBoundaries || vs >= kInfiniteSharpness || (plus && n > 2) ||
                        (sharpenDarts && n == 1 && !boundary);
        // A "disjoint" value: one UV index in several spans (a bowtie in UV space), or an
        // interior dart value cut by more than one discontinuous edge. OpenSubdiv sharpens it.
        auto disjoint = [&](uint32_t value) { return spanCount[value] > 1; };
        float dependent[2] = {0, 0};
        if (!allSharp && plus && n == 2) {
            const Span& a = values.begin()->second;
            const Span& b = std::next(values.begin())->second;
            allSharp = a.infSharpEdges || b.infSharpEdges || disjoint(a.value) || disjoint(b.value);
            if (sharpenBothIfOneCorner) allSharp |= a.size == 1 || b.size == 1;
            // Dependent sharpness: a value without semi-sharp edges follows the other's decay.
            // Approximated by a vertex sharpness equal to the other's sharpest edge.
            if ((a.semiSharpEdges > 0) != (b.semiSharpEdges > 0))
                dependent[a.semiSharpEdges ? 1 : 0] = std::max(a.maxSemiSharpness, b.maxSemiSharpness);
        }
        uint32_t valueIndex = 0;
        for (const auto& [value, s] : values) {
            const bool corner = allSharp || disjoint(value) || s.infSharpEdges > 0 ||
                                (s.size == 1 && fvarCornersAreSharp);
            // (dependent[] has entries for the two values of a two-value vertex only)
            const float extra = corner ? kInfiniteSharpness : n == 2 ? dependent[valueIndex] : 0.0f;
            ++valueIndex;
            if (extra <= vs) continue;
            for (uint32_t k = 0; k < spans.size(); ++k)
                if (spans[k].value == value) uv.tags.corners.push_back({firstVertex + k, extra});
        }
    }
    // Creases on face-varying continuous edges (on discontinuous ones the UV mesh has two
    // boundary edges, infinitely sharp anyway). A later tag for the same UV vertex wins, so the
    // corner tags above are ordered vertex by vertex with the sharpened ones last.
    for (const auto& c : mesh.tags.creases) {
        uint32_t e = topo.findEdge(c.v0, c.v1);
        if (e == kNone) continue;
        uint32_t h = topo.edgeHalfedge(e);
        uv.tags.creases.push_back({uv.faceVertices[h], uv.faceVertices[topo.next(h)], c.sharpness});
    }
    return uv;
}

uint32_t fvarQuadtreeCell(std::vector<uint32_t>& nodes, uint32_t node, uint32_t levels, uint32_t i, uint32_t j) {
    for (uint32_t level = 0; level < levels; ++level) { // descend, splitting leaves-to-be
        if (nodes[node] == 0xFFFFFFFFu) {
            nodes[node] = static_cast<uint32_t>(nodes.size());
            nodes.insert(nodes.end(), 4, 0xFFFFFFFFu);
        }
        const uint32_t shift = levels - 1 - level;
        node = nodes[node] + ((i >> shift) & 1u) + 2 * ((j >> shift) & 1u);
    }
    return node;
}

namespace {

uint64_t cellKey(uint32_t ptex, uint32_t k, uint32_t i, uint32_t j) {
    return uint64_t(ptex) << 37 | uint64_t(k) << 32 | uint64_t(i) << 16 | j;
}

uint32_t sizeExponent(float size) { return static_cast<uint32_t>(std::lround(-std::log2(double(size)))); }

} // namespace

FaceVaryingSurface::FaceVaryingSurface(const Mesh& mesh, const SchemeOptions& o, uint32_t depth,
                                       uint32_t irregularLevels, Warnings& warnings, size_t maxGpuRecordBytes, bool boundaryBases)
    : depth_(depth) {
    Mesh uv = faceVaryingMesh(mesh, o);
    for (size_t f = 0; f < mesh.faceCount(); ++f) ptexCount_ += mesh.faceSize(f) == 4 ? 1 : mesh.faceSize(f);
    SchemeOptions uo;
    uo.boundary = BoundaryRule::EdgeOnly;
    uo.creaseMethod = o.creaseMethod;
    uo.triangles = o.triangles;
    TablesOptions to;
    to.depth = static_cast<int>(depth);
    // The geometry's K: the UV surface of an irregular face is exact wherever its position is
    // (docs/irregular.md), from the same machinery (quadtrees, per-valence bases).
    // Capped so that the finest UV element stays within the GPU's float walk (fvar_eval.glsl).
    to.irregularLevels = static_cast<int>(std::min(irregularLevels, uint32_t(kMaxDepth) - std::min(depth, uint32_t(kMaxDepth))));
    // Faces along UV seams and boundaries take a basis per configuration instead of K levels of
    // refinement (FVSF version 3): the records they expand to are those pieces.
    to.boundaryBases = to.basisRimFeatures = boundaryBases;
    to.creaseChains = false; // FVSF stores no decaying-crease chains
    tables_ = buildTables(uv, uo, to, warnings);
    vertices_ = evaluateVertices(tables_, uv.positions);
    limits_ = evaluateLimitPoints(tables_, vertices_);
    const uint32_t P = static_cast<uint32_t>(tables_.patches.size());
    hasElements_.assign(ptexCount_, 0);
    auto add = [&](uint32_t e, uint32_t ptex, float u0, float v0, float size) {
        if (ptex < ptexCount_) hasElements_[ptex] = 1;
        const uint32_t k = sizeExponent(size);
        const double scale = std::ldexp(1.0, int(k));
        cells_[cellKey(ptex, k, uint32_t(std::lround(u0 * scale)), uint32_t(std::lround(v0 * scale)))] = e;
    };
    for (uint32_t i = 0; i < P; ++i) add(i, tables_.patches[i].ptex, tables_.patches[i].u0, tables_.patches[i].v0, tables_.patches[i].size);
    for (uint32_t i = 0; i < tables_.irregular.size(); ++i)
        add(P + i, tables_.irregular[i].ptex, tables_.irregular[i].u0, tables_.irregular[i].v0, tables_.irregular[i].size);
    // The GPU's pieces cost about 3 records a level per irregular face (19 at K = 6 instead of
    // 1): on meshes where nearly every face is irregular (triangulated scans) that would
    // overflow a storage buffer. Above maxGpuRecordBytes the pieces stop at fewer levels (their
    // deepest squares bilinear in exact corners), and the warning says so.
    gpuLevels_ = tables_.irregularLevels;
    while (gpuLevels_ > 0 && gpuElementCount(gpuLevels_) * 144 > maxGpuRecordBytes) --gpuLevels_;
    if (gpuLevels_ < tables_.irregularLevels)
        warnings.add("the smooth UVs' irregular faces are drawn exact beyond 2^-" + std::to_string(gpuLevels_) +
                     " of their extraordinary corners only (not 2^-" + std::to_string(tables_.irregularLevels) +
                     "): their " + std::to_string(tables_.irregularLevels) + "-level surface would take more than " +
                     std::to_string(maxGpuRecordBytes >> 20) + " MiB of GPU records");
}

size_t FaceVaryingSurface::gpuElementCount(uint32_t levels) const {
    size_t n = tables_.patches.size();
    auto bands = [&](uint32_t smooth, uint32_t below) {
        const uint32_t b = tables_.irregularBases[tables_.smoothIrregular[smooth].basis].levels;
        return std::min(levels - below, b > below ? b - below : 1);
    };
    auto count = [&](auto&& self, uint32_t node, uint32_t depth) -> size_t {
        size_t c = 0;
        for (uint32_t code : tables_.irregularNodes[node]) {
            if (code == kNodeNone) continue;
            const bool child = (code & ~kNodeIndexMask) == kNodeChild;
            const bool basis = (code & ~kNodeIndexMask) == kNodeBasis; // a smooth face below the root
            c += child && depth + 1 < levels ? self(self, code & kNodeIndexMask, depth + 1)
                 : basis && depth + 1 < levels ? 3 * bands(code & kNodeIndexMask, depth + 1) + 1
                                               : 1;
        }
        return c;
    };
    for (uint32_t q = 0; q < tables_.irregular.size(); ++q) {
        const uint32_t root = q < tables_.irregularNodes.size() ? tables_.irregularNodes[q][0] : kNodeNone;
        if (root == kNodeNone || levels == 0) ++n;
        else if (smoothRoot(tables_.irregularNodes[q]))
            n += 3 * bands(root & kNodeIndexMask, 0) + 1;
        else n += count(count, q, 0);
    }
    return n;
}

FaceVaryingSurface::Gpu FaceVaryingSurface::compactGpu() const {
    Gpu g;
    g.nodes.assign(ptexCount_, 0xFFFFFFFFu);
    const uint32_t P = static_cast<uint32_t>(tables_.patches.size());
    auto insert = [&](uint32_t e, uint32_t ptex, float u0, float v0, float size) -> uint32_t {
        const uint32_t k = sizeExponent(size);
        const uint32_t i = uint32_t(std::lround(u0 * std::ldexp(1.0, int(k))));
        const uint32_t j = uint32_t(std::lround(v0 * std::ldexp(1.0, int(k))));
        const uint32_t node = fvarQuadtreeCell(g.nodes, ptex, k, i, j);
        g.nodes[node] = 0x80000000u | e;
        return node;
    };
    for (uint32_t e = 0; e < P; ++e) {
        const Patch& p = tables_.patches[e];
        insert(e, p.ptex, p.u0, p.v0, p.size);
        glm::dvec3 C[4][4];
        gatherControlPoints(p, vertices_, C); // with evaluatePatch's phantoms
        g.records.push_back({p.u0, p.v0, p.size, 0.0f});
        for (int c = 0; c < 16; c += 2) {
            const glm::dvec3 a = C[c % 4][c / 4], b = C[(c + 1) % 4][(c + 1) / 4];
            g.records.push_back(glm::vec4(a.x, a.y, b.x, b.y));
        }
    }
    // An irregular face is drawn from its surface's pieces (docs/irregular.md), each one record
    // of its own: the sub-patches and leaves of its quadtree. A face with a per-valence basis is
    // a smooth face (its support's UVs, the weights once per valence), which expandSmoothFaces
    // turns into its band sub-patches and leaf where the GPU needs them: a fraction of the bytes
    // in the file. A smooth face below a root (a decayed crease, inside a quadtree) is stored as
    // its pieces, expanded here as the readers expand a root's: there are few. Elements are
    // numbered in record order, smooth faces after them.
    uint32_t next = P;
    auto patchRecord = [&](uint32_t ptex, double u0, double v0, double size, const glm::dvec3 C[4][4]) {
        insert(next++, ptex, float(u0), float(v0), float(size));
        g.records.push_back({float(u0), float(v0), float(size), 0.0f});
        for (int c = 0; c < 16; c += 2) {
            const glm::dvec3 a = C[c % 4][c / 4], b = C[(c + 1) % 4][(c + 1) / 4];
            g.records.push_back(glm::vec4(a.x, a.y, b.x, b.y));
        }
    };
    auto bilinearRecord = [&](uint32_t ptex, double u0, double v0, double size, const glm::dvec3 c[4]) {
        insert(next++, ptex, float(u0), float(v0), float(size));
        g.records.push_back({float(u0), float(v0), float(size), 1.0f});
        g.records.push_back(glm::vec4(c[0].x, c[0].y, c[1].x, c[1].y));
        g.records.push_back(glm::vec4(c[2].x, c[2].y, c[3].x, c[3].y));
        g.records.insert(g.records.end(), 6, glm::vec4(0.0f));
    };
    auto limitsOf = [&](const IrregularFace& f, glm::dvec3 c[4]) {
        for (int k = 0; k < 4; ++k) c[k] = limits_[f.corner[k]].position;
    };
    // Quadtree node `node` covering [u0, u0 + size]^2 (plus v0) of ptex face `ptex`.
    // (fs, ft, fh: the node's square in its face's (s, t), for the pieces cut at gpuLevels_.)
    auto walk = [&](auto&& self, uint32_t face, uint32_t node, uint32_t depth, double u0, double v0, double size,
                    double fs, double ft, double fh) -> void {
        const uint32_t ptex = tables_.irregular[face].ptex;
        for (uint32_t c = 0; c < 4; ++c) {
            const uint32_t code = tables_.irregularNodes[node][c];
            const double h = size / 2, cu = u0 + (c & 1) * h, cv = v0 + (c >> 1) * h;
            const double gh = fh / 2, gs = fs + (c & 1) * gh, gt = ft + (c >> 1) * gh;
            const uint32_t kind = code & ~kNodeIndexMask, index = code & kNodeIndexMask;
            if (code == kNodeNone) continue;
            if ((kind == kNodeChild || kind == kNodeBasis) && depth + 1 >= gpuLevels_) {
                // Cut (a child or a smooth face below the root alike): bilinear in its exact corners.
                glm::dvec3 corners[4];
                const double cs[4] = {gs, gs + gh, gs + gh, gs}, ct[4] = {gt, gt, gt + gh, gt + gh};
                for (int k = 0; k < 4; ++k)
                    corners[k] = evaluateIrregular(tables_, vertices_, limits_, face, cs[k], ct[k]).position;
                bilinearRecord(ptex, cu, cv, h, corners);
            } else if (kind == kNodeChild) {
                self(self, face, index, depth + 1, cu, cv, h, gs, gt, gh);
            } else if (kind == kNodeBasis) {
                // A smooth face below the root (a decayed crease, a corner child of a face with
                // two extraordinary corners): its pieces, by the readers' own expansion of a
                // root's smooth face (expandSmoothFaces), with the bands it has.
                const Tables::SmoothIrregular& sm = tables_.smoothIrregular[index];
                const IrregularBasis& b = tables_.irregularBases[sm.basis];
                SmoothFace sf;
                sf.u0 = float(cu), sf.v0 = float(cv), sf.size = float(h);
                sf.node = insert(0, ptex, sf.u0, sf.v0, sf.size);
                Gpu one;
                one.nodes.swap(g.nodes);
                one.records.swap(g.records);
                Basis x = b;
                x.levels = std::min(gpuLevels_ - (depth + 1), b.levels > depth + 1 ? b.levels - (depth + 1) : 1);
                x.weights.resize(size_t(x.levels) * 48 * b.supportSize());
                x.signature.clear();
                one.bases.push_back(std::move(x));
                for (uint32_t i = 0; i < b.supportSize(); ++i) {
                    const glm::dvec3& p = vertices_[tables_.smoothPoints[sm.first + i]];
                    one.points.emplace_back(float(p.x), float(p.y));
                }
                sf.corner = sm.corner;
                // Its extraordinary vertex is a corner of the irregular face: the limit point there.
                const double es = gs + ((sm.corner == 1 || sm.corner == 2) ? gh : 0.0);
                const double et = gt + (sm.corner >= 2 ? gh : 0.0);
                const glm::dvec3 limit = evaluateIrregular(tables_, vertices_, limits_, face, es, et).position;
                sf.limit = glm::vec2(float(limit.x), float(limit.y));
                one.smoothFaces.push_back(sf);
                one = expandSmoothFaces(std::move(one));
                g.nodes.swap(one.nodes);
                g.records.swap(one.records);
                next = static_cast<uint32_t>(g.records.size() / 9);
            } else if (kind == kNodeSubPatch) {
                glm::dvec3 C[4][4];
                gatherControlPoints(tables_.subPatches[index], vertices_, C);
                patchRecord(ptex, cu, cv, h, C);
            } else if (kind == kNodeLeaf) {
                glm::dvec3 corners[4];
                limitsOf(tables_.irregularLeaves[index], corners);
                bilinearRecord(ptex, cu, cv, h, corners);
            }
        }
    };
    for (uint32_t q = 0; q < tables_.irregular.size(); ++q) {
        const IrregularFace& f = tables_.irregular[q];
        const uint32_t root = q < tables_.irregularNodes.size() ? tables_.irregularNodes[q][0] : kNodeNone;
        if (root != kNodeNone && gpuLevels_ > 0 && smoothRoot(tables_.irregularNodes[q])) {
            const Tables::SmoothIrregular& sm = tables_.smoothIrregular[root & kNodeIndexMask];
            const IrregularBasis& b = tables_.irregularBases[sm.basis];
            const uint32_t levels = std::min(gpuLevels_, b.levels);
            auto basis = std::find_if(g.bases.begin(), g.bases.end(),
                                      [&](const Basis& x) { return x.configuration == b.configuration; });
            if (basis == g.bases.end()) {
                // Band k's weights depend on bands 1..k only: the program expands to these for
                // `levels` bands (expandIrregularBasis).
                Basis x = b;
                x.levels = levels;
                x.weights.resize(size_t(levels) * 48 * b.supportSize());
                x.signature.clear();
                basis = g.bases.insert(g.bases.end(), std::move(x));
            }
            SmoothFace face;
            face.corner = sm.corner;
            face.basis = static_cast<uint32_t>(basis - g.bases.begin());
            face.firstPoint = static_cast<uint32_t>(g.points.size());
            for (uint32_t i = 0; i < b.supportSize(); ++i) {
                const glm::dvec3& x = vertices_[tables_.smoothPoints[sm.first + i]];
                g.points.emplace_back(float(x.x), float(x.y));
            }
            const glm::dvec3& limit = limits_[f.corner[sm.corner]].position;
            face.limit = glm::vec2(float(limit.x), float(limit.y));
            face.u0 = f.u0, face.v0 = f.v0, face.size = f.size;
            face.node = insert(0, f.ptex, f.u0, f.v0, f.size); // named below, after the elements
            g.smoothFaces.push_back(face);
        } else if (root != kNodeNone && gpuLevels_ > 0) {
            walk(walk, q, q, 0, f.u0, f.v0, f.size, 0.0, 0.0, 1.0);
        } else { // tables without the irregular surface: the bilinear blend of its corners
            glm::dvec3 corners[4];
            limitsOf(f, corners);
            bilinearRecord(f.ptex, f.u0, f.v0, f.size, corners);
        }
    }
    const uint32_t elements = static_cast<uint32_t>(g.records.size() / 9);
    for (uint32_t i = 0; i < g.smoothFaces.size(); ++i) g.nodes[g.smoothFaces[i].node] = 0x80000000u | (elements + i);
    return g;
}

FaceVaryingSurface::Gpu FaceVaryingSurface::gpu() const { return expandSmoothFaces(compactGpu()); }

glm::dvec2 FaceVaryingSurface::uvAt(uint32_t ptex, double u, double v, double tu, double tv) const {
    // A probe just inside the element asked about, so exactly one cell of each size contains it.
    const double pu = std::clamp(u + 1e-6 * (tu - u), 0.0, 1.0), pv = std::clamp(v + 1e-6 * (tv - v), 0.0, 1.0);
    const uint32_t P = static_cast<uint32_t>(tables_.patches.size());
    for (uint32_t k = 0; k <= depth_ + 1; ++k) {
        const double scale = std::ldexp(1.0, int(k));
        const uint32_t last = (1u << k) - 1;
        const uint32_t i = std::min(uint32_t(pu * scale), last), j = std::min(uint32_t(pv * scale), last);
        auto it = cells_.find(cellKey(ptex, k, i, j));
        if (it == cells_.end()) continue;
        const uint32_t e = it->second;
        if (e < P) {
            const Patch& p = tables_.patches[e];
            SurfacePoint s = evaluatePatch(p, vertices_, (u - p.u0) / p.size, (v - p.v0) / p.size);
            return {s.position.x, s.position.y};
        }
        const IrregularFace& q = tables_.irregular[e - P];
        const SurfacePoint x = evaluateIrregular(tables_, vertices_, limits_, e - P, (u - q.u0) / q.size, (v - q.v0) / q.size);
        return {x.position.x, x.position.y};
    }
    throw Error(ErrorKind::BadInput, "no face-varying element contains ptex face " + std::to_string(ptex) +
                                         " at (" + std::to_string(u) + ", " + std::to_string(v) + ")");
}

} // namespace limn
