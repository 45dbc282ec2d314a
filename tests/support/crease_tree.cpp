// buildCreaseTree (crease_tree.h): buildCreaseChain's construction with every irregular child
// followed.
#include "crease_tree.h"

#include "subdiv/tables_build.h"
#include "topology/features.h"

#include <stdexcept>

namespace limn {

namespace {

std::vector<uint32_t> leastKey(const Level& L, uint32_t f) {
    std::vector<uint32_t> least, support, key;
    for (int c = 0; c < 4; ++c)
        if (creaseSupport(L, f, c, support, key) && (least.empty() || key < least)) least = key;
    return least;
}

} // namespace

bool buildCreaseTree(const Level& L, uint32_t f, uint32_t K, const SchemeOptions& options,
                     const TablesOptions& opts, CreaseTree& tree) {
    tree = CreaseTree{};
    std::vector<uint32_t> support, faces, key;
    if (K == 0 || !creaseSupport(L, f, 0, support, key, &faces)) return false;
    uint32_t face0 = 0;
    Level cur = localLevel(L, support, faces, f, 0, face0);
    std::vector<uint32_t> ptexBase(cur.topo.faceCount());
    for (uint32_t g = 0; g < ptexBase.size(); ++g) ptexBase[g] = cur.frames[g].ptex;
    // The nodes of the level being refined: their face in `cur` and their support there.
    struct Open {
        uint32_t node, face;
        std::vector<uint32_t> support;
    };
    std::vector<Open> open;
    {
        CreaseTreeNode root;
        root.key = key;
        root.turnedKey = leastKey(L, f);
        root.support = uint32_t(support.size());
        tree.nodes.push_back(std::move(root));
        std::vector<uint32_t> identity(support.size());
        for (uint32_t i = 0; i < identity.size(); ++i) identity[i] = i;
        open.push_back({0, face0, std::move(identity)});
    }
    std::vector<uint32_t> identity;
    for (uint32_t j = 1; j <= K && !open.empty(); ++j) {
        std::vector<uint8_t> selected(cur.topo.faceCount(), 0);
        for (const Open& o : open) selected[o.face] = 1;
        LevelStencils st;
        Level child = refineLevel(cur, oneRing(cur.topo, selected), options, ptexBase, st);
        std::vector<uint8_t> children(child.topo.faceCount(), 0);
        for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf)
            children[cf] = child.faceParent[cf] < selected.size() && selected[child.faceParent[cf]];
        const Regularity r =
            analyzeRegularity(child.topo, child.edgeSharpness, child.vertexSharpness, child.noLimit,
                              opts.infSharpPatches, opts.singleCreasePatches, &children);
        identity.resize(child.topo.vertexCount());
        for (uint32_t v = 0; v < identity.size(); ++v) identity[v] = v;
        std::vector<Open> next;
        for (const Open& o : open) {
            std::array<uint32_t, 4> quadrant;
            quadrant.fill(kNone);
            const FaceFrame& pf = cur.frames[o.face];
            for (uint32_t cf = 0; cf < child.topo.faceCount(); ++cf) {
                if (child.faceParent[cf] != o.face) continue;
                const FaceFrame& c = child.frames[cf];
                quadrant[size_t((c.u0 > pf.u0 ? 1 : 0) | (c.v0 > pf.v0 ? 2 : 0))] = cf;
            }
            std::vector<Patch> patches;
            std::vector<uint32_t> nextRows, sub, subKey;
            CreaseTreeNode node;
            for (size_t q = 0; q < 4; ++q) {
                const uint32_t cf = quadrant[q];
                if (cf == kNone) throw std::logic_error("crease tree: a quadrant without a child");
                int c2 = -1;
                uint32_t valence = 0;
                if (r.faceRegular[cf]) {
                    node.child[q] = CreaseTreeChild::Patch;
                    patches.push_back(gatherPatch(child, cf, 0, identity, r.faceCreaseEdge[cf]));
                    node.kind[q] = kindOf(patches.back());
                } else if (j < K &&
                           smoothSupport(child, cf, c2, valence, sub, opts.basisRimFeatures)) {
                    node.child[q] = CreaseTreeChild::Smooth;
                    node.next[q] = valence;
                    node.nextFirst[q] = uint32_t(nextRows.size());
                    node.nextCount[q] = uint32_t(sub.size());
                    nextRows.insert(nextRows.end(), sub.begin(), sub.end());
                } else if (j == K) {
                    node.child[q] = CreaseTreeChild::Leaf;
                } else {
                    if (!creaseSupport(child, cf, 0, sub, subKey)) return false;
                    node.child[q] = CreaseTreeChild::Node;
                    node.nextFirst[q] = uint32_t(nextRows.size());
                    node.nextCount[q] = uint32_t(sub.size());
                    nextRows.insert(nextRows.end(), sub.begin(), sub.end());
                    // The child's place, filled when its level is refined.
                    CreaseTreeNode placeholder;
                    placeholder.key = subKey;
                    placeholder.turnedKey = leastKey(child, cf);
                    placeholder.support = uint32_t(sub.size());
                    tree.nodes.push_back(std::move(placeholder));
                    node.next[q] = uint32_t(tree.nodes.size() - 1);
                    next.push_back({node.next[q], cf, sub});
                }
            }
            std::vector<std::array<uint32_t, 16>> rows;
            bandProgram(child, st, o.support, cur.topo.vertexCount(), patches, nextRows,
                        node.program, rows);
            for (size_t q = 0, p = 0; q < 4; ++q)
                if (node.child[q] == CreaseTreeChild::Patch) node.rows[q] = rows[p++];
            node.key = std::move(tree.nodes[o.node].key);
            node.turnedKey = std::move(tree.nodes[o.node].turnedKey);
            node.support = tree.nodes[o.node].support;
            tree.nodes[o.node] = std::move(node);
        }
        cur = std::move(child);
        open = std::move(next);
    }
    return true;
}

} // namespace limn
