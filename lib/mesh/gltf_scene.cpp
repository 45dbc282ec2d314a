// The glTF node graph (glTF 2.0, 3.5.3: disjoint strict trees). Hostile files list a node as the
// child of two nodes, or of itself: walked naively, 60 nodes that each list the next twice draw
// 2^60 instances and a cycle never ends. Both are found before any geometry is read; every walk
// here uses an explicit stack, so a deep chain cannot overflow the call stack.
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>

namespace limn::gltf {

namespace {

glm::dmat4 nodeMatrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
    glm::dmat4 m(1.0);
    if (n.translation.size() == 3)
        m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4) // glTF stores x, y, z, w
        m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
    if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

void checkIndex(const tinygltf::Model& model, int node, const std::string& where) {
    if (node < 0 || node >= static_cast<int>(model.nodes.size()))
        throwBadInput("glTF: " + where + " refers to node " + std::to_string(node) + ", which does not exist");
}

// The number of instances the subtree of each node draws (itself included), saturated just
// above kMaxNodeInstances; throws on a cycle, naming it.
std::vector<uint64_t> subtreeSizes(const tinygltf::Model& model) {
    const size_t N = model.nodes.size();
    enum : uint8_t { kNew, kOnPath, kDone };
    std::vector<uint8_t> state(N, kNew);
    std::vector<uint64_t> size(N, 0);
    struct Frame {
        int node;
        size_t next; // the next child to visit
    };
    std::vector<Frame> stack;
    for (size_t start = 0; start < N; ++start) {
        if (state[start] != kNew) continue;
        stack.push_back({int(start), 0});
        state[start] = kOnPath;
        while (!stack.empty()) {
            Frame& f = stack.back();
            const auto& children = model.nodes[f.node].children;
            if (f.next < children.size()) {
                const int c = children[f.next++];
                checkIndex(model, c, "node " + std::to_string(f.node));
                if (state[c] == kOnPath) {
                    std::string cycle = std::to_string(c);
                    auto it = std::find_if(stack.begin(), stack.end(), [&](const Frame& s) { return s.node == c; });
                    for (++it; it != stack.end(); ++it) cycle += " -> " + std::to_string(it->node);
                    throwBadInput("glTF: the node graph has a cycle (" + cycle + " -> " + std::to_string(c) +
                                  "); glTF requires the nodes to form trees");
                }
                if (state[c] == kNew) {
                    state[c] = kOnPath;
                    stack.push_back({c, 0});
                }
                continue;
            }
            uint64_t total = 1;
            for (int c : children) total = std::min(total + size[c], kMaxNodeInstances + 1);
            size[f.node] = total;
            state[f.node] = kDone;
            stack.pop_back();
        }
    }
    return size;
}

} // namespace

std::vector<NodeInstance> sceneInstances(const tinygltf::Model& model, const std::vector<int>& roots,
                                         Warnings& warnings) {
    for (int r : roots) checkIndex(model, r, "the scene");
    const std::vector<uint64_t> size = subtreeSizes(model);
    uint64_t total = 0;
    for (int r : roots) total = std::min(total + size[r], kMaxNodeInstances + 1);
    if (total > kMaxNodeInstances)
        throwBadInput("glTF: the scene's node graph would draw more than " + std::to_string(kMaxNodeInstances) +
                      " node instances: nodes are listed as the child of several nodes (or several "
                      "times), and each is drawn once per path; glTF requires the nodes to form trees");
    std::vector<uint32_t> parents(model.nodes.size(), 0);
    for (const auto& n : model.nodes)
        for (int c : n.children) ++parents[c];
    size_t shared = 0;
    int first = -1;
    for (size_t i = 0; i < parents.size(); ++i)
        if (parents[i] > 1) {
            if (first < 0) first = int(i);
            ++shared;
        }
    if (shared)
        warnings.add(std::to_string(shared) + " nodes (node " + std::to_string(first) +
                     " first) are listed as a child more than once; glTF requires the nodes to form "
                     "trees; each is drawn once per path");

    // Depth first, a node before its children, children in order: the order of the recursion
    // this replaces, so that the welded vertex order is unchanged.
    std::vector<NodeInstance> out;
    out.reserve(size_t(total));
    std::vector<NodeInstance> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, glm::dmat4(1.0)});
    while (!stack.empty()) {
        NodeInstance at = stack.back();
        stack.pop_back();
        const auto& node = model.nodes[at.node];
        at.transform = at.transform * nodeMatrix(node);
        out.push_back(at);
        for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, at.transform});
    }
    return out;
}

} // namespace limn::gltf
