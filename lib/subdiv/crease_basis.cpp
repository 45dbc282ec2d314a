#include "subdiv/crease_basis.h"

#include "subdiv/tables_build.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <unordered_map>
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
    // A linear search, as boundarySupport's: supports are small.
    auto index = [&](uint32_t v) -> uint32_t {
        const auto it = std::find(support.begin(), support.end(), v);
        if (it != support.end()) return uint32_t(it - support.begin());
        support.push_back(v);
        return uint32_t(support.size() - 1);
    };
    std::vector<uint32_t> fan;
    for (int j = 0; j < 4; ++j) {
        const uint32_t hc = h0f + (fr.rotation + corner + j) % 4;
        if (T.vertexIsNonManifold(T.vertex(hc))) return false;
        fan.assign(1, hc);
        bool closed = false;
        for (uint32_t h = T.rotateCCW(hc); h != kNone; h = T.rotateCCW(h)) {
            if (h == hc) {
                closed = true;
                break;
            }
            if (fan.size() > kMaxBasisValence) return false;
            fan.push_back(h);
        }
        if (!closed)
            for (uint32_t h = T.rotateCW(hc); h != kNone; h = T.rotateCW(h)) {
                if (fan.size() > kMaxBasisValence) return false;
                fan.push_back(h);
            }
        push(uint32_t(fan.size()) << 1 | (closed ? 1u : 0u), kNone);
        for (uint32_t h : fan) {
            const uint32_t g = T.face(h);
            if (T.faceSize(g) != 4 || L.noLimit[g]) return false;
            if (faces) faces->push_back(g);
            uint32_t x = h;
            for (int c = 0; c < 4; ++c, x = T.next(x)) {
                const uint32_t v = T.vertex(x);
                push(index(v), kNone);
                const bool read = atCorner(v) || atCorner(T.vertex(T.next(x)));
                push(read ? std::bit_cast<uint32_t>(L.edgeSharpness[T.edge(x)]) : 0u, read ? T.edge(x) : kNone);
            }
            if (support.size() > 2 * size_t(kMaxBasisValence) + 8) return false;
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
    Topology topo(M, offsets, corners);
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

// The program of one band: the rows of `child` (refined from `parent` with stencils `st`) that
// the patches and the next support read, over the parent's support `input` (basisFromMesh's
// construction, irregular_basis.cpp, with any patches and support).
void bandProgram(const Level& child, const LevelStencils& st, const std::vector<uint32_t>& input,
                 uint32_t parentVertices, const std::vector<Patch>& patches, const std::vector<uint32_t>& next,
                 BasisProgram& p, std::vector<std::array<uint32_t, 16>>& controlRows) {
    const size_t M = input.size();
    std::vector<uint32_t> inputOf(parentVertices, kNone);
    for (size_t i = 0; i < M; ++i) inputOf[input[i]] = uint32_t(i);
    const Level& L = child;
    std::vector<uint8_t> needed(L.topo.vertexCount(), 0);
    for (const Patch& sp : patches)
        for (int i = 0; i < 16; ++i)
            if (!isPhantom(sp.boundary, i)) needed[sp.cv[i]] = 1;
    for (uint32_t v : next) needed[v] = 1;
    auto markFacePoints = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                              const std::vector<StencilEntry>& entries) {
        for (uint32_t i = 0; i < count; ++i)
            if (needed[first + i])
                for (uint32_t k = start[i]; k < start[i + 1]; ++k)
                    if (entries[k].fromFacePoint) needed[entries[k].index] = 1;
    };
    markFacePoints(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
    markFacePoints(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
    std::vector<uint32_t> row(needed.size(), kNone);
    uint32_t rows = 0;
    for (size_t v = 0; v < needed.size(); ++v)
        if (needed[v]) row[v] = rows++;
    p = BasisProgram{};
    auto in = [&](uint32_t v) {
        if (inputOf[v] == kNone) throw std::logic_error("crease basis: a row reads outside the support");
        return inputOf[v];
    };
    for (uint32_t i = 0; i < L.facePointCount; ++i) {
        if (!needed[i]) continue;
        for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k) {
            p.source.push_back(in(st.faceVertices[k]));
            p.weight.push_back(1.0f);
        }
        p.start.push_back(uint32_t(p.source.size()));
        p.averaged.push_back(1);
    }
    auto weighted = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                        const std::vector<StencilEntry>& stencil) {
        for (uint32_t i = 0; i < count; ++i) {
            if (!needed[first + i]) continue;
            for (uint32_t k = start[i]; k < start[i + 1]; ++k) {
                const StencilEntry& e = stencil[k];
                p.source.push_back(e.fromFacePoint ? uint32_t(M) + row[e.index] : in(e.index));
                p.weight.push_back(static_cast<float>(e.weight));
            }
            p.start.push_back(uint32_t(p.source.size()));
            p.averaged.push_back(0);
        }
    };
    weighted(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
    weighted(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
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

bool sameBandFunction(const CreaseBand& x, const CreaseBand& y, double* difference, double tolerance) {
    if (x.support != y.support || x.program.nextSupport.size() != y.program.nextSupport.size()) return false;
    std::vector<glm::dvec3> in(x.support);
    for (size_t i = 0; i < in.size(); ++i)
        in[i] = glm::dvec3(std::sin(1.0 + double(i)), std::cos(3.0 * double(i)), 0.1 * double(i));
    const std::vector<glm::dvec3> px = runBandProgram(x.program, in), py = runBandProgram(y.program, in);
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
                      const TablesOptions& opts, CreaseChain& chain) {
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
    // kinds' sharpness less 1 each, as long as no sharpness crosses 2 (below 2 a child's
    // sharpness can reach 0: a kind or the chain's end changes): they are not refined. Then the last refined level is given the band's key
    // (the same topology) and refined from there. bench_crease_bases checks the result against
    // the quadtree, bit for bit.
    const bool uniform = options.creaseMethod == CreaseMethod::Uniform;
    bool repeating = false;
    auto zeroSharpness = [](const std::vector<uint32_t>& k) { return mapSharpness(k, [](float) { return 0.0f; }); };
    for (uint32_t j = 1; j <= K; ++j) {
        if (repeating) {
            if (j < K && programKey(key, 2.0f) == programKey(chain.bands.back().key, 2.0f)) {
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
        std::vector<uint8_t> selected(cur.topo.faceCount(), 0);
        selected[chainFace] = 1;
        LevelStencils st;
        Level child = refineLevel(cur, oneRing(cur.topo, selected), options, ptexBase, st);
        // Only the chain face's children are read.
        std::vector<uint8_t> children(child.topo.faceCount(), 0);
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf) children[cf] = child.faceParent[cf] == chainFace;
        const Regularity r = analyzeRegularity(child.topo, child.edgeSharpness, child.vertexSharpness, child.noLimit,
                                               opts.infSharpPatches, opts.singleCreasePatches, &children);
        identity.resize(child.topo.vertexCount());
        for (uint32_t v = 0; v < identity.size(); ++v) identity[v] = v;
        const FaceFrame& pf = cur.frames[chainFace];
        uint32_t centre = kNone;
        std::vector<Patch> patches(3);
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf) {
            if (child.faceParent[cf] != chainFace) continue;
            const FaceFrame& c = child.frames[cf];
            const int q = (c.u0 > pf.u0 ? 1 : 0) | (c.v0 > pf.v0 ? 2 : 0);
            if (q == 0) {
                centre = cf;
                continue;
            }
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
    }
    return true;
}

namespace {

// The key a band's program is shared by (TBLS stores it once): its programKey, and for a
// chain's last band how the chain ends.
std::vector<uint32_t> sharedProgramKey(const CreaseChain& chain, const CreaseBand& band) {
    std::vector<uint32_t> shared = programKey(band.key, kProgramSharpness);
    shared.push_back(&band == &chain.bands.back() ? 1u + uint32_t(chain.end) : 0u);
    return shared;
}

// Whether a configuration's chain costs fewer bytes than the quadtrees of the faces it draws. A
// band program of its own (300-400 bytes) costs about what one face's quadtree node does (its
// level's stencils and three sub-patches), so a chain pays off where faces share it, or where
// most of its bands run programs shared with other chains or repeated (a long crease); a chain
// of one face whose bands mostly need programs of their own does not (measured over the catmark
// shapes at depths 1-3: docs/irregular-tables.md, "Chains that do not pay off").
// `faces()`: how many faces draw the chain's configuration, asked only where its programs do
// not decide.
constexpr uint32_t kMinChainFaces = 2;
template <class Shared, class Faces>
bool paysOff(const CreaseChain& chain, const Shared& sharedBands, Faces faces) {
    std::vector<std::vector<uint32_t>> own; // a few bands: a linear search
    for (const CreaseBand& band : chain.bands) {
        std::vector<uint32_t> shared = sharedProgramKey(chain, band);
        if (std::find(own.begin(), own.end(), shared) == own.end() && !sharedBands.contains(shared))
            own.push_back(std::move(shared));
    }
    // One band ending in a smooth face: its program is the rows of the quadtree's one level.
    if (3 * own.size() <= chain.bands.size() || (chain.bands.size() == 1 && chain.end == CreaseEnd::Smooth))
        return true;
    return faces() >= kMinChainFaces;
}

// Each face's candidate corners' supports and keys (creaseSupport's), and how many faces each
// key is met at over them: counted once, the first time a chain's programs do not decide, with
// the supports kept for takeCreaseFaces' own loop (so that counting costs little).
struct CreaseKeyCount {
    bool counted = false;
    std::unordered_map<uint64_t, uint32_t> faces; // by keyHash: a decision about bytes only
    std::unordered_map<uint64_t, std::pair<std::vector<uint32_t>, std::vector<uint32_t>>> candidates; // f * 4 + c
};

// FNV-1a over a key's words.
uint64_t keyHash(const std::vector<uint32_t>& key) {
    uint64_t h = 14695981039346656037ull;
    for (uint32_t x : key) h = (h ^ x) * 1099511628211ull;
    return h;
}

template <class Order>
void countCreaseKeys(const Level& L, const std::vector<uint8_t>& T, Order cornerOrder, CreaseKeyCount& out) {
    out.counted = true;
    std::vector<uint32_t> support, key;
    for (uint32_t f = 0; f < L.topo.faceCount(); ++f) {
        if (!T[f] || L.topo.faceSize(f) != 4) continue;
        int order[4], ranks[4];
        cornerOrder(f, order, ranks);
        for (int c : order) {
            if (ranks[c] == 2) break;
            if (!creaseSupport(L, f, c, support, key)) continue;
            ++out.faces[keyHash(key)];
            out.candidates.emplace(uint64_t(f) * 4 + uint64_t(c), std::pair{support, key});
        }
    }
}

} // namespace

void takeCreaseFaces(const Level& L, const SchemeOptions& options, const TablesOptions& opts, uint32_t basisLevels,
                     std::vector<uint8_t>& T, AdaptiveLevels& a) {
    // A configuration's chain is the same for every face of its key (the study checks it), so
    // it is built once; a key without one is remembered too.
    std::map<std::vector<uint32_t>, int> chainOf;
    std::map<int, int> basisOfChain; // TablesOptions::creaseChains: into a.bases, -1 for none
    std::map<std::vector<uint32_t>, CreaseBand> sharedBands; // the first band of each programKey and end
    std::vector<uint32_t> support, key;
    const Topology& topo = L.topo;
    // The feature corner is tried first: an extraordinary vertex, else a regular one with a
    // sharp vertex, a dart, or a crease that does not go straight through with one sharpness. A
    // straight crease of one sharpness through a regular vertex is no feature corner: faces along
    // such a crease that are irregular elsewhere have such corners only, and trying them cost a
    // refinement per key for nothing.
    std::vector<uint32_t> ring;
    auto rank = [&](uint32_t v) {
        if (topo.vertexFaceCount(v) != (topo.vertexIsBoundary(v) ? 2u : 4u)) return 0;
        if (L.vertexSharpness[v] != 0) return 1;
        topo.vertexRing(v, ring);
        int sharp = 0, first = -1, second = -1;
        for (int k = 0; k < int(ring.size()); ++k)
            if (L.edgeSharpness[topo.edge(ring[size_t(k)])] != 0) {
                (sharp++ == 0 ? first : second) = k;
            }
        if (sharp == 0) return 2;
        const bool straight = sharp == 2 && !topo.vertexIsBoundary(v) && second - first == 2 &&
                              L.edgeSharpness[topo.edge(ring[size_t(first)])] ==
                                  L.edgeSharpness[topo.edge(ring[size_t(second)])];
        return straight ? 2 : 1;
    };
    auto cornerOrder = [&](uint32_t f, int order[4], int ranks[4]) {
        for (int c = 0; c < 4; ++c) {
            order[c] = c;
            ranks[c] = rank(topo.vertex(topo.faceHalfedge(f) + (L.frames[f].rotation + c) % 4));
        }
        std::stable_sort(order, order + 4, [&](int x, int y) { return ranks[x] < ranks[y]; });
    };
    CreaseKeyCount count;
    const std::vector<uint8_t> faceSet = T; // before any face is taken: what count counts over
    for (uint32_t f = 0; f < topo.faceCount(); ++f) {
        if (!T[f] || topo.faceSize(f) != 4) continue;
        int order[4], ranks[4];
        cornerOrder(f, order, ranks);
        for (int c : order) {
            if (ranks[c] == 2) break; // a smooth regular corner has no chain
            if (count.counted) {
                auto found = count.candidates.find(uint64_t(f) * 4 + uint64_t(c));
                if (found == count.candidates.end()) continue;
                support = std::move(found->second.first);
                key = std::move(found->second.second);
                count.candidates.erase(found);
            } else if (!creaseSupport(L, f, c, support, key)) {
                continue;
            }
            auto [it, added] = chainOf.try_emplace(key, -1);
            if (added) {
                CreaseChain chain;
                if (buildCreaseChain(L, f, c, a.K, options, opts, chain)) {
                    a.creaseChains.push_back(std::move(chain));
                    it->second = int(a.creaseChains.size() - 1);
                }
            }
            if (it->second < 0) continue;
            if (opts.creaseChains) {
                // The chain's surface as a basis of the face's own support (expandCreaseChain),
                // once per chain; a face whose chain has none is refined.
                auto [b, fresh] = basisOfChain.try_emplace(it->second, -1);
                IrregularBasis basis;
                auto faces = [&] {
                    if (!count.counted) countCreaseKeys(L, faceSet, cornerOrder, count);
                    return count.faces.at(keyHash(key));
                };
                if (fresh && paysOff(a.creaseChains[size_t(it->second)], sharedBands, faces)) {
                    auto chain = std::make_shared<CreaseChain>(a.creaseChains[size_t(it->second)]);
                    // Bands whose keys agree once every sharpness from 1 on is clamped, and that
                    // end alike, run the same function (bench_crease_bases checks it: to 1e-16),
                    // so they share one program, which TBLS then stores once; only their kinds'
                    // sharpness differs.
                    for (CreaseBand& band : chain->bands) {
                        auto [other, first] = sharedBands.try_emplace(sharedProgramKey(*chain, band), band);
                        double difference = 0;
                        if (!first && sameBandFunction(other->second, band, &difference, 1e-12)) {
                            band.program = other->second.program;
                            band.centreRow = other->second.centreRow;
                        }
                    }
                    // A smooth end goes on with its valence's basis, which the tables hold (TBLS
                    // version 8 names it), even where no face of its own draws from it.
                    int end = -1;
                    if (chain->end == CreaseEnd::Smooth) {
                        std::vector<int>& of = a.basisOfValence;
                        if (of.size() <= chain->valence) of.resize(chain->valence + 1, -1);
                        if (of[chain->valence] == -1) {
                            try {
                                a.bases.push_back(buildIrregularBasis(chain->valence, std::max(a.K, basisLevels)));
                                of[chain->valence] = int(a.bases.size() - 1);
                            } catch (const std::exception&) {
                                of[chain->valence] = -2;
                            }
                        }
                        end = of[chain->valence];
                        chain->endBasis = uint32_t(end);
                    }
                    if ((chain->end != CreaseEnd::Smooth || end >= 0) &&
                        expandCreaseChain(*chain, a.K, basis, end >= 0 ? &a.bases[size_t(end)] : nullptr)) {
                        basis.chain = std::move(chain);
                        a.bases.push_back(std::move(basis));
                        b->second = int(a.bases.size() - 1);
                    }
                }
                if (b->second < 0) continue;
                a.smooth.push_back({f, uint32_t(b->second), uint32_t(c), support, L.depth});
                T[f] = 0;
                break;
            }
            a.creaseFaces.push_back({f, uint32_t(it->second), uint32_t(c), support, L.depth});
            T[f] = 0;
            break;
        }
    }
}

} // namespace limn
