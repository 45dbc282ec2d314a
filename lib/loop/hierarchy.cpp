#include "loop/hierarchy.h"

#include "loop/rules.h"

#include <algorithm>

namespace limn::loop {

UniformHierarchy::UniformHierarchy(const TriMesh& control, int levels) {
    meshes_.push_back(std::make_unique<TriMesh>(control));
    for (int l = 0; l < levels; ++l) extend();
}

void UniformHierarchy::extend() {
    const TriMesh& last = *meshes_.back();
    levels_.push_back(std::make_unique<Level>(last));
    const Level& level = *levels_.back();
    auto even = evenPositions(level), odd = oddPositions(level);
    std::vector<uint8_t> all(level.topology().edgeCount(), 1);
    meshes_.push_back(std::make_unique<TriMesh>(refine(level, all, EvenUpdate::All, even, odd).mesh));
}

namespace {

// Which triangles of the hierarchy are present (active), split 1-to-4 (red), and which of their
// edges carry a vertex (split). It is the least state closed under these rules, so it does not
// depend on the order in which the work list is processed:
//   an edge the metric selects (want) on an active triangle is split;
//   a split edge makes the triangles on both of its sides active;
//   an active triangle of level k > 0 needs its parent red;
//   an active triangle with three split edges is red; a red triangle has three split edges and
//   four active children.
class Selection {
public:
    explicit Selection(const UniformHierarchy& h) : h_(h) {
        active_.emplace_back(h.mesh(0).triangleCount(), 1);
    }

    // Level l's metric decisions: split the wanted edges of its active triangles, then close.
    // Needs U_{l+1} and the Level of U_l in the hierarchy.
    void decide(int l, std::vector<uint8_t> want) {
        current_ = l;
        const Topology& topo = h_.level(l).topology();
        want_.push_back(std::move(want));
        red_.emplace_back(topo.faceCount(), 0);
        split_.emplace_back(topo.edgeCount(), 0);
        active_.emplace_back(h_.mesh(l + 1).triangleCount(), 0);
        for (uint32_t t = 0; t < topo.faceCount(); ++t)
            if (active_[l][t])
                for (int i = 0; i < 3; ++i)
                    if (want_[l][topo.edge(3 * t + i)]) work_.push_back({kSplit, l, topo.edge(3 * t + i)});
        close();
    }

    int decidedLevels() const { return current_ + 1; }
    bool active(int l, uint32_t t) const { return active_[l][t] != 0; }
    bool red(int l, uint32_t t) const { return l <= current_ && red_[l][t] != 0; }
    bool split(int l, uint32_t e) const { return l <= current_ && split_[l][e] != 0; }
    uint32_t splitCount(int l) const {
        return static_cast<uint32_t>(std::count(split_[l].begin(), split_[l].end(), 1));
    }

private:
    enum Op : uint8_t { kSplit, kActive, kRed };
    struct Item {
        Op op;
        int level;
        uint32_t index;
    };

    bool allSplit(int l, uint32_t t) const {
        const Topology& topo = h_.level(l).topology();
        for (int i = 0; i < 3; ++i)
            if (!split_[l][topo.edge(3 * t + i)]) return false;
        return true;
    }

    void close() {
        while (!work_.empty()) {
            const Item it = work_.back();
            work_.pop_back();
            const int l = it.level;
            const uint32_t x = it.index;
            if (it.op == kSplit) {
                if (split_[l][x]) continue;
                split_[l][x] = 1;
                const Topology& topo = h_.level(l).topology();
                const uint32_t h = topo.edgeHalfedge(x);
                for (uint32_t g : {h, topo.twin(h)}) {
                    if (g == kNone) continue;
                    const uint32_t t = topo.face(g);
                    work_.push_back({kActive, l, t});
                    if (active_[l][t] && allSplit(l, t)) work_.push_back({kRed, l, t});
                }
            } else if (it.op == kActive) {
                if (active_[l][x]) continue;
                active_[l][x] = 1;
                if (l > 0) work_.push_back({kRed, l - 1, x / 4});
                if (l > current_) continue; // a child level: nothing decided there yet
                if (allSplit(l, x)) work_.push_back({kRed, l, x});
                const Topology& topo = h_.level(l).topology();
                for (int i = 0; i < 3; ++i)
                    if (want_[l][topo.edge(3 * x + i)]) work_.push_back({kSplit, l, topo.edge(3 * x + i)});
            } else {
                if (red_[l][x]) continue;
                red_[l][x] = 1;
                work_.push_back({kActive, l, x});
                const Topology& topo = h_.level(l).topology();
                for (int i = 0; i < 3; ++i) work_.push_back({kSplit, l, topo.edge(3 * x + i)});
                for (uint32_t c = 4 * x; c < 4 * x + 4; ++c) work_.push_back({kActive, l + 1, c});
            }
        }
    }

    const UniformHierarchy& h_;
    int current_ = -1;
    std::vector<std::vector<uint8_t>> active_, red_, split_, want_;
    std::vector<Item> work_;
};

// Edges of a triangle t of level l as half-edges 3t, 3t+1, 3t+2 (corner i to corner i+1).
uint32_t triangleEdge(const UniformHierarchy& h, int l, uint32_t t, int i) {
    return h.level(l).topology().edge(3 * t + i);
}

// The adaptive mesh the selection describes, in hierarchy vertex ids (stable across levels).
// `depth`: levels 0..depth hold leaves.
TriMesh assemble(const UniformHierarchy& h, const Selection& s, int depth, EvenUpdate update) {
    const TriMesh& finest = h.mesh(depth);
    const uint32_t ids = finest.vertexCount();
    // The level whose position each vertex takes (math.md B.7): (a) the last level for all;
    // (b) one past the last level at which one of its edges was split, else its birth level.
    std::vector<uint8_t> positionLevel(ids, 0);
    for (int l = 1; l <= depth; ++l)
        for (uint32_t v = h.mesh(l - 1).vertexCount(); v < h.mesh(l).vertexCount(); ++v)
            positionLevel[v] = static_cast<uint8_t>(l);
    for (int l = 0; l < depth && l < s.decidedLevels(); ++l) {
        const Topology& topo = h.level(l).topology();
        for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
            if (!s.split(l, e)) continue;
            for (uint32_t v : topo.edgeVertices(e))
                positionLevel[v] = std::max<uint8_t>(positionLevel[v], static_cast<uint8_t>(l + 1));
        }
    }
    if (update == EvenUpdate::All) std::fill(positionLevel.begin(), positionLevel.end(), depth);
    std::vector<glm::dvec3> P(ids);
    for (uint32_t v = 0; v < ids; ++v) P[v] = h.mesh(positionLevel[v]).positions[v];

    TriMesh out;
    const bool uv = finest.hasUVs();
    for (int l = 0; l <= depth; ++l) {
        const TriMesh& m = h.mesh(l);
        for (uint32_t t = 0; t < m.triangleCount(); ++t) {
            if (!s.active(l, t) || s.red(l, t)) continue;
            Tri mid{kNone, kNone, kNone}, uvMid{};
            for (int i = 0; i < 3 && l < depth; ++i) {
                uint32_t e = triangleEdge(h, l, t, i);
                if (!s.split(l, e)) continue;
                mid[i] = m.vertexCount() + e;
                if (uv) uvMid[i] = h.mesh(l + 1).uvTriangles[4 * t + 3][i]; // the centre child
            }
            appendTemplate(m.triangles[t], mid, P, out, uv ? &m.uvTriangles[t] : nullptr,
                           uv ? &uvMid : nullptr);
            // Interior creases of the leaf (U_l's sorted crease list), halved where split.
            for (int i = 0; i < 3; ++i) {
                uint32_t a = m.triangles[t][i], b = m.triangles[t][(i + 1) % 3];
                VertexPair key{std::min(a, b), std::max(a, b)};
                if (!std::binary_search(m.creases.begin(), m.creases.end(), key)) continue;
                if (mid[i] == kNone) {
                    out.creases.push_back(key);
                } else {
                    out.creases.push_back({std::min(a, mid[i]), std::max(a, mid[i])});
                    out.creases.push_back({std::min(b, mid[i]), std::max(b, mid[i])});
                }
            }
        }
    }
    std::sort(out.creases.begin(), out.creases.end());
    out.creases.erase(std::unique(out.creases.begin(), out.creases.end()), out.creases.end());

    // Keep the used ids in increasing order (every control vertex is kept, used or not).
    std::vector<uint32_t> remap(ids, kNone);
    for (uint32_t v = 0; v < h.mesh(0).vertexCount(); ++v) remap[v] = 0;
    for (const Tri& t : out.triangles)
        for (uint32_t v : t) remap[v] = 0;
    uint32_t next = 0;
    for (uint32_t v = 0; v < ids; ++v) {
        if (remap[v] == kNone) continue;
        remap[v] = next++;
        out.positions.push_back(P[v]);
        out.corners.push_back(finest.corners[v]);
    }
    for (Tri& t : out.triangles)
        for (uint32_t& v : t) v = remap[v];
    for (VertexPair& c : out.creases)
        for (uint32_t& v : c) v = remap[v];
    if (uv) {
        std::vector<uint32_t> uvRemap(finest.uvs.size(), kNone);
        for (size_t u = 0; u < h.mesh(0).uvs.size(); ++u) uvRemap[u] = 0; // the control mesh's UVs
        for (const Tri& t : out.uvTriangles)
            for (uint32_t u : t) uvRemap[u] = 0;
        uint32_t nextUV = 0;
        for (size_t u = 0; u < uvRemap.size(); ++u)
            if (uvRemap[u] != kNone) {
                uvRemap[u] = nextUV++;
                out.uvs.push_back(finest.uvs[u]);
            }
        for (Tri& t : out.uvTriangles)
            for (uint32_t& u : t) u = uvRemap[u];
    }
    return out;
}

} // namespace

AdaptiveResult subdivideOnHierarchy(const TriMesh& control, const AdaptiveOptions& options) {
    const double diagonal = boundingBoxDiagonal(control.positions);
    UniformHierarchy h(control);
    Selection s(h);
    AdaptiveResult result;
    int depth = 0;
    uint32_t vertices = control.vertexCount();
    for (int l = 0; l < options.levels; ++l) {
        h.extend();
        // The even and odd positions of U_l are the vertices of U_{l+1}.
        const auto& next = h.mesh(l + 1).positions;
        const uint32_t V = h.mesh(l).vertexCount();
        std::vector<glm::dvec3> even(next.begin(), next.begin() + V), odd(next.begin() + V, next.end());
        s.decide(l, splitDecisions(h.level(l), even, odd, options, diagonal));

        LevelStats stats;
        stats.level = l + 1;
        const Topology& topo = h.level(l).topology();
        for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
            uint32_t g = topo.edgeHalfedge(e), g2 = topo.twin(g);
            if (s.active(l, topo.face(g)) || (g2 != kNone && s.active(l, topo.face(g2)))) ++stats.edges;
        }
        stats.splitEdges = s.splitCount(l);
        if (stats.splitEdges > 0) {
            depth = l + 1;
            vertices = control.vertexCount();
            for (int k = 0; k <= l; ++k) vertices += s.splitCount(k);
        }
        uint32_t faces = 0;
        for (int k = 0; k <= depth; ++k)
            for (uint32_t t = 0; t < h.mesh(k).triangleCount(); ++t) {
                if (!s.active(k, t) || s.red(k, t)) continue;
                ++faces;
                for (int i = 0; i < 3 && k < depth; ++i) faces += s.split(k, triangleEdge(h, k, t, i));
            }
        stats.vertices = vertices;
        stats.faces = faces;
        result.levels.push_back(stats);
        if (stats.splitEdges == 0) break;
    }
    result.mesh = assemble(h, s, depth, options.evenUpdate);
    return result;
}

} // namespace limn::loop
