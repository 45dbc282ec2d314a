#include "subdiv/crease_basis.h"

#include "subdiv/support_index.h"
#include "subdiv/tables_build.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <stdexcept>

namespace limn {

namespace {

// Where creaseSupport's key entries come from (sourcesOf): an edge's index, a corner vertex's
// index with this bit, or kNone (a support index, or an edge no stencil reads).
constexpr uint32_t kVertexEntry = 1u << 31;

bool supportOf(const Level& L, uint32_t f, int corner, std::vector<uint32_t>& support, std::vector<uint32_t>& key,
               std::vector<uint32_t>* faces, std::vector<uint32_t>* sources);

} // namespace

bool creaseSupport(const Level& L, uint32_t f, int corner, std::vector<uint32_t>& support,
                   std::vector<uint32_t>& key, std::vector<uint32_t>* faces) {
    return supportOf(L, f, corner, support, key, faces, nullptr);
}

namespace {

bool supportOf(const Level& L, uint32_t f, int corner, std::vector<uint32_t>& support, std::vector<uint32_t>& key,
               std::vector<uint32_t>* faces, std::vector<uint32_t>* sources) {
    const Topology& T = L.topo;
    if (T.faceSize(f) != 4 || L.noLimit[f]) return false;
    const FaceFrame& fr = L.frames[f];
    const uint32_t h0f = T.faceHalfedge(f);
    uint32_t corners[4];
    for (int k = 0; k < 4; ++k) corners[k] = T.vertex(h0f + (fr.rotation + corner + k) % 4);
    auto atCorner = [&](uint32_t v) { return v == corners[0] || v == corners[1] || v == corners[2] || v == corners[3]; };
    support.clear();
    key.clear();
    if (faces) faces->clear();
    if (sources) sources->clear();
    auto push = [&](uint32_t value, uint32_t source) {
        key.push_back(value);
        if (sources) sources->push_back(source);
    };
    // Support indices by vertex (SupportIndex): this runs for every corner tried of every
    // irregular face at level N and for every band.
    constexpr size_t kMaxSupport = 2 * size_t(kMaxBasisValence) + 8;
    constexpr size_t kKeyRoom = 512; // a key around a pole of valence 24 has about 300 entries
    static_assert(kMaxSupport + 4 <= SupportIndex::kMaxVertices);
    // Room for a pole's support and key at once (a fresh vector grew a dozen times per call).
    support.reserve(kMaxSupport + 4);
    key.reserve(kKeyRoom);
    if (sources) sources->reserve(kKeyRoom);
    SupportIndex indexOf(kMaxSupport + 4); // a face past kMaxSupport adds at most 4 before the check
    auto index = [&](uint32_t v) {
        const auto [i, added] = indexOf.insert(v, uint32_t(support.size()));
        if (added) support.push_back(v);
        return i;
    };
    std::array<uint32_t, kMaxBasisValence + 1> fan;
    for (int j = 0; j < 4; ++j) {
        const uint32_t hc = h0f + (fr.rotation + corner + j) % 4;
        if (T.vertexIsNonManifold(T.vertex(hc))) return false;
        size_t fanSize = 0;
        fan[fanSize++] = hc;
        bool closed = false;
        for (uint32_t h = T.rotateCCW(hc); h != kNone; h = T.rotateCCW(h)) {
            if (h == hc) {
                closed = true;
                break;
            }
            if (fanSize > kMaxBasisValence) return false;
            fan[fanSize++] = h;
        }
        if (!closed)
            for (uint32_t h = T.rotateCW(hc); h != kNone; h = T.rotateCW(h)) {
                if (fanSize > kMaxBasisValence) return false;
                fan[fanSize++] = h;
            }
        push(uint32_t(fanSize) << 1 | (closed ? 1u : 0u), kNone);
        for (uint32_t h : std::span(fan).first(fanSize)) {
            const uint32_t g = T.face(h);
            if (T.faceSize(g) != 4) return false; // a hole is no feature (smoothSupport)
            if (faces) faces->push_back(g);
            uint32_t x = h;
            // Which of the face's vertices are corners of f, each asked once.
            bool isCorner[4];
            for (int c = 0; c < 4; ++c, x = T.next(x)) isCorner[c] = atCorner(T.vertex(x));
            for (int c = 0; c < 4; ++c, x = T.next(x)) {
                const uint32_t v = T.vertex(x);
                push(index(v), kNone);
                const bool read = isCorner[c] || isCorner[(c + 1) % 4];
                push(read ? std::bit_cast<uint32_t>(L.edgeSharpness[T.edge(x)]) : 0u, read ? T.edge(x) : kNone);
            }
            if (support.size() > kMaxSupport) return false;
        }
    }
    for (uint32_t v : corners) push(std::bit_cast<uint32_t>(L.vertexSharpness[v]), v | kVertexEntry);
    return true;
}

} // namespace

namespace {

// The key with every sharpness entry s replaced by map(s).
template <class Map>
std::vector<uint32_t> mapSharpness(const std::vector<uint32_t>& key, Map map) {
    std::vector<uint32_t> out = key;
    auto apply = [&](uint32_t& x) { x = std::bit_cast<uint32_t>(map(std::bit_cast<float>(x))); };
    size_t at = 0;
    for (int j = 0; j < 4; ++j) {
        const size_t faces = out[at++] >> 1;
        for (size_t k = 0; k < 4 * faces; ++k, at += 2) apply(out[at + 1]);
    }
    for (; at < out.size(); ++at) apply(out[at]);
    return out;
}

// One level of uniform creasing (Sdc::Crease's decrement): what the key of the next band is
// when the chain face's neighbourhood repeats itself.
float decrement(float s) { return s >= kInfiniteSharpness ? s : s > 1.0f ? s - 1.0f : 0.0f; }

std::vector<uint32_t> decremented(const std::vector<uint32_t>& key) { return mapSharpness(key, decrement); }

} // namespace

std::vector<uint32_t> programKey(const std::vector<uint32_t>& key, float sharp) {
    return mapSharpness(key, [sharp](float s) { return s >= sharp ? sharp : s; });
}

// localLevel, kindOf and bandProgram are declared in crease_basis.h (the study's crease trees
// build from them too).

// A level of the faces in `faces` (sorted by index, so that every stencil's entries come in the
// order of the level's own: vertex rings start at the lowest half-edge, edges at their first),
// vertex i being support[i], with their sharpness; the copy's own boundary (the rim, where the
// level goes on) infinitely sharp, which only the rim's rows read. Face f's frame turned so that
// `corner` is at (0, 0).
Level localLevel(const Level& L, const std::vector<uint32_t>& support, std::vector<uint32_t> faces, uint32_t f,
                 int corner, uint32_t& face0) {
    const Topology& T = L.topo;
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    auto local = [&](uint32_t v) { return uint32_t(std::find(support.begin(), support.end(), v) - support.begin()); };
    std::vector<uint32_t> offsets{0}, corners;
    for (uint32_t g : faces) {
        for (uint32_t k = 0; k < 4; ++k) corners.push_back(local(T.vertex(T.faceHalfedge(g) + k)));
        offsets.push_back(uint32_t(corners.size()));
    }
    const uint32_t M = uint32_t(support.size());
    // The copy's twins are the level's between two copied faces (Topology::withTwins: the
    // constructor's arrays without matching edges) where the faces' edges are manifold.
    std::vector<uint32_t> twins;
    twins.reserve(corners.size());
    bool manifold = true;
    for (uint32_t g : faces)
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t rh = T.faceHalfedge(g) + k, t = T.twin(rh);
            manifold = manifold && !T.edgeIsNonManifold(T.edge(rh));
            auto at = t == kNone ? faces.end() : std::lower_bound(faces.begin(), faces.end(), T.face(t));
            twins.push_back(at == faces.end() || *at != T.face(t) ? kNone
                                                                  : 4 * uint32_t(at - faces.begin()) + T.cornerIndex(t));
        }
    Topology topo = manifold ? Topology::withTwins(M, std::move(offsets), std::move(corners), std::move(twins))
                             : Topology(M, offsets, corners);
    Sharpness s;
    s.edge.assign(topo.edgeCount(), 0.0f);
    s.vertex.resize(M);
    s.faceNoLimit.assign(faces.size(), 0);
    s.vertexOnUnsharpBoundary.assign(M, 0);
    for (uint32_t i = 0; i < faces.size(); ++i)
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t lh = topo.faceHalfedge(i) + k, rh = T.faceHalfedge(faces[i]) + k;
            s.edge[topo.edge(lh)] =
                topo.twin(lh) == kNone && T.twin(rh) != kNone ? kInfiniteSharpness : L.edgeSharpness[T.edge(rh)];
        }
    for (uint32_t i = 0; i < M; ++i) s.vertex[i] = L.vertexSharpness[support[i]];
    Level out = makeBaseLevel(std::move(topo), std::move(s));
    face0 = uint32_t(std::find(faces.begin(), faces.end(), f) - faces.begin());
    out.frames[face0].rotation = uint8_t((L.frames[f].rotation + corner) % 4);
    return out;
}

CreaseBandKind kindOf(const Patch& p) { return {p.boundary, p.crease, p.sharpness}; }

namespace {

// The child of face f (whose frame is pf) at its feature corner (the frame's (u0, v0)), or kNone.
uint32_t centreChild(const Level& child, uint32_t f, const FaceFrame& pf) {
    for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf)
        if (child.faceParent[cf] == f && !(child.frames[cf].u0 > pf.u0) && !(child.frames[cf].v0 > pf.v0)) return cf;
    return kNone;
}

// The corners of the chain face f (refineLevel's childCorners). A band reads, of the level it
// refines, only the children at f's corners: the patches of f's quadrants (each child's one-ring
// is children at one corner of f of the faces around it) and the next band's support and rows
// (the faces around the centre child's corners, and the edges and faces around those, which
// again are children at f's corners). So the other children of f's one-ring are not made, nor
// their points: around a pole of valence 24 about a quarter of them are. The rows read are the same, in
// the same order (the child vertices kept are numbered in the order they had; every edge and
// face read keeps both its faces, so the edges keep their order). A face with two of f's
// corners opposite each other, and neither between them, would leave its face point two children
// that do not meet (a vertex the level would take for non-manifold): then every child is made.
const std::vector<uint8_t>& chainCorners(const Level& L, uint32_t f, std::vector<uint8_t>& corners) {
    const Topology& T = L.topo;
    corners.assign(T.vertexCount(), 0);
    for (uint32_t v : T.faceVertices(f)) corners[v] = 1;
    for (uint32_t v : T.faceVertices(f))
        for (uint32_t h : T.vertexOutgoing(v)) {
            const uint32_t g = T.face(h);
            if (T.faceSize(g) != 4) continue; // a chain's faces are quads (creaseSupport)
            unsigned at = 0;
            for (uint32_t k = 0; k < 4; ++k) at |= unsigned(corners[T.vertex(T.faceHalfedge(g) + k)]) << k;
            if (at == 0b0101 || at == 0b1010) {
                corners.assign(T.vertexCount(), 1);
                return corners;
            }
        }
    return corners;
}

} // namespace

// The program of one band: the rows of `child` (refined from `parent` with stencils `st`) that
// the patches and the next support read, over the parent's support `input` (stencilRows, as
// basisFromMesh's, with any patches and support).
void bandProgram(const Level& child, const LevelStencils& st, const std::vector<uint32_t>& input,
                 uint32_t parentVertices, const std::vector<Patch>& patches, const std::vector<uint32_t>& next,
                 BasisProgram& p, std::vector<std::array<uint32_t, 16>>& controlRows) {
    std::vector<uint8_t> needed(child.topo.vertexCount(), 0);
    for (const Patch& sp : patches)
        for (int i = 0; i < 16; ++i)
            if (!isPhantom(sp.boundary, i)) needed[sp.cv[i]] = 1;
    for (uint32_t v : next) needed[v] = 1;
    const std::vector<uint32_t> row = stencilRows(child, st, input, parentVertices, std::move(needed), p);
    // Phantom points are left to the evaluator (gatherControlPoints, from the kind's bits): a
    // phantom's row is kNone.
    controlRows.clear();
    for (const Patch& sp : patches) {
        std::array<uint32_t, 16> r{};
        for (int i = 0; i < 16; ++i) r[size_t(i)] = isPhantom(sp.boundary, i) ? kNone : row[sp.cv[i]];
        controlRows.push_back(r);
    }
    for (uint32_t v : next) p.nextSupport.push_back(row[v]);
}

// The rows of a band's program over its support's values, with evaluateVertices' arithmetic
// (double sums in the program's order of float weights times points; face points averaged).
std::vector<glm::dvec3> runBandProgram(const BasisProgram& p, std::span<const glm::dvec3> in) {
    const uint32_t M = uint32_t(in.size());
    std::vector<glm::dvec3> values(p.rows());
    for (uint32_t r = 0; r < p.rows(); ++r) {
        glm::dvec3 sum(0.0);
        for (uint32_t e = p.start[r]; e < p.start[r + 1]; ++e) {
            const uint32_t s = p.source[e];
            const glm::dvec3& x = s < M ? in[s] : values[s - M];
            if (p.averaged[r])
                sum += x;
            else
                sum += double(p.weight[e]) * x;
        }
        values[r] = p.averaged[r] ? sum / double(p.start[r + 1] - p.start[r]) : sum;
    }
    return values;
}

std::vector<glm::dvec3> bandProbe(const CreaseBand& band) {
    // Arbitrary support values of size about 1, made once for the largest support a chain has.
    static const std::vector<glm::dvec3> values = [] {
        std::vector<glm::dvec3> in(2 * size_t(kMaxBasisValence) + 8);
        for (size_t i = 0; i < in.size(); ++i)
            in[i] = glm::dvec3(std::sin(1.0 + double(i)), std::cos(3.0 * double(i)), 0.1 * double(i));
        return in;
    }();
    if (band.support > values.size()) throw std::logic_error("crease basis: a band's support is too large");
    return runBandProgram(band.program, std::span(values).first(band.support));
}

bool sameBandFunction(const CreaseBand& x, const CreaseBand& y, double* difference, double tolerance,
                      const std::vector<glm::dvec3>* xProbe) {
    if (x.support != y.support || x.program.nextSupport.size() != y.program.nextSupport.size()) return false;
    const std::vector<glm::dvec3> own = xProbe ? std::vector<glm::dvec3>{} : bandProbe(x), py = bandProbe(y);
    const std::vector<glm::dvec3>& px = xProbe ? *xProbe : own;
    auto same = [&](uint32_t r, uint32_t q) {
        if (r == kNone || q == kNone) return r == q;
        double most = 0;
        for (int k = 0; k < 3; ++k) most = std::max(most, std::abs(px[r][k] - py[q][k]));
        if (difference) *difference = std::max(*difference, most);
        return tolerance > 0 ? most <= tolerance : px[r] == py[q];
    };
    for (size_t k = 0; k < 48; ++k)
        if (!same(x.program.controlRow[k], y.program.controlRow[k])) return false;
    for (size_t k = 0; k < 16; ++k)
        if ((x.centreRow[k] != 0 || y.centreRow[k] != 0) && !same(x.centreRow[k], y.centreRow[k])) return false;
    for (size_t k = 0; k < x.program.nextSupport.size(); ++k)
        if (!same(x.program.nextSupport[k], y.program.nextSupport[k])) return false;
    return true;
}

bool buildCreaseChain(const Level& L, uint32_t f, int corner, uint32_t K, const SchemeOptions& options,
                      const TablesOptions& opts, CreaseChain& chain, bool sharedPrograms) {
    std::vector<uint32_t> support, faces, key;
    chain = CreaseChain{};
    if (K == 0 || !creaseSupport(L, f, corner, support, chain.key, &faces)) return false;
    uint32_t chainFace = 0;
    Level cur = localLevel(L, support, faces, f, corner, chainFace);
    std::vector<uint32_t> curSupport;
    bool same = creaseSupport(cur, chainFace, 0, curSupport, key) && key == chain.key;
    for (uint32_t i = 0; same && i < curSupport.size(); ++i) same = curSupport[i] == i;
    if (!same)
        throw std::logic_error("crease basis: the copy's support is not the face's");
    std::vector<uint32_t> ptexBase(cur.topo.faceCount());
    for (uint32_t g = 0; g < ptexBase.size(); ++g) ptexBase[g] = cur.frames[g].ptex;
    std::vector<uint32_t> identity, sources, probe, probeKey;
    // Under uniform creasing, once two bands from refined levels have run the same program and
    // each key was the one before less 1 (the neighbourhood repeats itself, Stam's observation
    // with the sharpness counting down), the next bands are that program again, with keys and
    // kinds' sharpness less 1 each, as long as every sharpness of the band's key is 0 or above 1
    // (the rules read none of them, and no child's sharpness reaches 0: the kinds and the
    // chain's end stay as they were; a sharpness of 1 or less changes the program, or a child's
    // rule): they are not refined. Then the last refined level is given the band's key (the same
    // topology) and refined from there. bench_crease_bases checks the result against the
    // quadtree, bit for bit.
    const bool uniform = options.creaseMethod == CreaseMethod::Uniform;
    bool repeating = false;
    auto zeroSharpness = [](const std::vector<uint32_t>& k) { return mapSharpness(k, [](float) { return 0.0f; }); };
    auto aboveOne = [](const std::vector<uint32_t>& k) {
        bool above = true;
        mapSharpness(k, [&above](float s) { return above = above && (s == 0 || s > 1.0f), s; });
        return above;
    };
    for (uint32_t j = 1; j <= K; ++j) {
        if (repeating) {
            if (j < K && aboveOne(key) && programKey(key, 1.0f) == programKey(chain.bands.back().key, 1.0f)) {
                CreaseBand band = chain.bands.back();
                band.key = key;
                for (CreaseBandKind& k : band.kind) k.sharpness = decrement(k.sharpness);
                chain.bands.push_back(std::move(band));
                key = decremented(key);
                continue;
            }
            repeating = false;
            if (!supportOf(cur, chainFace, 0, probe, probeKey, nullptr, &sources) ||
                zeroSharpness(probeKey) != zeroSharpness(key))
                throw std::logic_error("crease basis: a repeated band's level is not the key's");
            for (size_t p = 0; p < sources.size(); ++p) {
                if (sources[p] == kNone) continue;
                const float x = std::bit_cast<float>(key[p]);
                (sources[p] & kVertexEntry ? cur.vertexSharpness[sources[p] & ~kVertexEntry] : cur.edgeSharpness[sources[p]]) = x;
            }
            assignVertexRules(cur);
            if (!creaseSupport(cur, chainFace, 0, probe, probeKey) || probeKey != key)
                throw std::logic_error("crease basis: a repeated band's key did not take");
        }
        std::vector<uint8_t> selected(cur.topo.faceCount(), 0), corners;
        selected[chainFace] = 1;
        LevelStencils st;
        Level child = refineLevel(cur, oneRing(cur.topo, selected), options, ptexBase, st,
                                  &chainCorners(cur, chainFace, corners));
        // Only the chain face's children are read.
        std::vector<uint8_t> children(child.topo.faceCount(), 0);
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf) children[cf] = child.faceParent[cf] == chainFace;
        const Regularity r = analyzeRegularity(child.topo, child.edgeSharpness, child.vertexSharpness, child.noLimit,
                                               opts.infSharpPatches, opts.singleCreasePatches, &children);
        identity.resize(child.topo.vertexCount());
        for (uint32_t v = 0; v < identity.size(); ++v) identity[v] = v;
        const FaceFrame& pf = cur.frames[chainFace];
        const uint32_t centre = centreChild(child, chainFace, pf);
        std::vector<Patch> patches(3);
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf) {
            if (child.faceParent[cf] != chainFace || cf == centre) continue;
            const FaceFrame& c = child.frames[cf];
            const int q = (c.u0 > pf.u0 ? 1 : 0) | (c.v0 > pf.v0 ? 2 : 0);
            if (!r.faceRegular[cf]) return false;
            patches[q == 1 ? 0 : q == 3 ? 1 : 2] = gatherPatch(child, cf, 0, identity, r.faceCreaseEdge[cf]);
        }
        if (centre == kNone) throw std::logic_error("crease basis: no child at the feature corner");
        CreaseBand band;
        band.key = key;
        band.support = uint32_t(curSupport.size());
        for (size_t q = 0; q < 3; ++q) band.kind[q] = kindOf(patches[q]);
        std::vector<uint32_t> next;
        int c2 = -1;
        uint32_t valence = 0;
        bool last = true;
        if (r.faceRegular[centre]) {
            chain.end = CreaseEnd::Regular;
            patches.push_back(gatherPatch(child, centre, 0, identity, r.faceCreaseEdge[centre]));
            band.centreKind = kindOf(patches.back());
        } else if (j < K && smoothSupport(child, centre, c2, valence, next) && c2 == 0) {
            chain.end = CreaseEnd::Smooth;
            chain.valence = valence;
        } else if (j == K) {
            chain.end = CreaseEnd::Leaf;
        } else {
            if (!creaseSupport(child, centre, 0, next, key)) return false;
            last = false;
        }
        std::vector<std::array<uint32_t, 16>> rows;
        bandProgram(child, st, curSupport, cur.topo.vertexCount(), patches, next, band.program, rows);
        for (size_t q = 0; q < 3; ++q)
            std::copy(rows[q].begin(), rows[q].end(), band.program.controlRow.begin() + 16 * long(q));
        if (rows.size() == 4) band.centreRow = rows[3];
        chain.bands.push_back(std::move(band));
        if (last) break;
        const size_t b = chain.bands.size();
        if (uniform && b >= 2) {
            const CreaseBand &x = chain.bands[b - 2], &y = chain.bands[b - 1];
            repeating = y.key == decremented(x.key) && key == decremented(y.key) && sameBandFunction(x, y);
        }
        cur = std::move(child);
        chainFace = centre;
        curSupport = std::move(next);
        // With sharedPrograms, a second band whose key is the first's less 1 (and that repeats
        // it, as above) is the first band again: its program is the first's by programKey, its
        // kinds less 1. Its level is still made (without stencils), and the next key read there,
        // so that the bands refined later are refined from the levels they were before (their
        // rows in those levels' vertex order, the bytes of a program that is the first of its
        // programKey) and the repetition rests on the same two keys.
        if (sharedPrograms && uniform && b == 1 && j + 1 < K && key == decremented(chain.bands[0].key) &&
            aboveOne(key) && programKey(key, 1.0f) == programKey(chain.bands[0].key, 1.0f)) {
            std::vector<uint8_t> around(cur.topo.faceCount(), 0);
            around[chainFace] = 1;
            Level third = refineLevelTopology(cur, oneRing(cur.topo, around), options, ptexBase,
                                              &chainCorners(cur, chainFace, corners));
            const uint32_t thirdFace = centreChild(third, chainFace, cur.frames[chainFace]);
            std::vector<uint32_t> thirdSupport, thirdKey;
            if (thirdFace != kNone && creaseSupport(third, thirdFace, 0, thirdSupport, thirdKey) &&
                thirdKey == decremented(key)) {
                CreaseBand second = chain.bands.back();
                second.key = key;
                second.borrowed = true;
                for (CreaseBandKind& k : second.kind) k.sharpness = decrement(k.sharpness);
                chain.bands.push_back(std::move(second));
                key = std::move(thirdKey);
                cur = std::move(third);
                chainFace = thirdFace;
                curSupport = std::move(thirdSupport);
                repeating = true;
                ++j;
            }
        }
    }
    return true;
}

} // namespace limn
