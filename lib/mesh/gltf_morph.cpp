// A glTF's morph-target animation as control-point sets (readGltfMorphFrames): the positions of
// every frame are mapped onto readGltf's welded vertices through their default-weight positions,
// so that all frames share one topology and the tables built for it.
#include "mesh/gltf.h"
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace limn {

namespace {

// One `weights` channel: the node it drives and its sampler.
struct WeightsChannel {
    int node = -1;
    std::string interpolation;
    std::vector<double> times;
    gltf::AccessorData values; // times.size() * (3 for CUBICSPLINE, else 1) elements of `targets` weights
    size_t targets = 0;
};

// The channel's weights at time t (glTF 2.0, 3.11 and Appendix C).
std::vector<double> sample(const WeightsChannel& c, double t) {
    const size_t n = c.times.size(), T = c.targets;
    const bool cubic = c.interpolation == "CUBICSPLINE";
    auto value = [&](size_t k, size_t part) { // part: 0 in-tangent, 1 value, 2 out-tangent
        std::vector<double> v(T);
        for (size_t i = 0; i < T; ++i) v[i] = c.values.values[(cubic ? (3 * k + part) : k) * T + i];
        return v;
    };
    if (t <= c.times.front()) return value(0, 1);
    if (t >= c.times.back()) return value(n - 1, 1);
    const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const double td = c.times[k + 1] - c.times[k], s = (t - c.times[k]) / td;
    if (c.interpolation == "STEP") return value(k, 1);
    const auto a = value(k, 1), b = value(k + 1, 1);
    std::vector<double> out(T);
    if (!cubic) {
        for (size_t i = 0; i < T; ++i) out[i] = a[i] + s * (b[i] - a[i]);
        return out;
    }
    const auto outTangent = value(k, 2), inTangent = value(k + 1, 0);
    const double s2 = s * s, s3 = s2 * s;
    for (size_t i = 0; i < T; ++i)
        out[i] = (2 * s3 - 3 * s2 + 1) * a[i] + td * (s3 - 2 * s2 + s) * outTangent[i] + (-2 * s3 + 3 * s2) * b[i] +
                 td * (s3 - s2) * inTangent[i];
    return out;
}

std::vector<WeightsChannel> weightsChannels(const tinygltf::Model& model) {
    if (model.animations.empty()) throwBadInput("glTF: the file has no animation");
    const auto& animation = model.animations[0];
    std::vector<WeightsChannel> out;
    for (size_t i = 0; i < animation.channels.size(); ++i) {
        const auto& ch = animation.channels[i];
        if (ch.target_path != "weights") continue;
        const std::string what = "glTF: animation 0 channel " + std::to_string(i);
        if (ch.target_node < 0 || ch.target_node >= static_cast<int>(model.nodes.size()))
            throwBadInput(what + " targets a node that does not exist");
        const auto& node = model.nodes[ch.target_node];
        if (node.mesh < 0 || node.mesh >= static_cast<int>(model.meshes.size()))
            throwBadInput(what + " animates the weights of a node without a mesh");
        if (ch.sampler < 0 || ch.sampler >= static_cast<int>(animation.samplers.size()))
            throwBadInput(what + " has no sampler");
        const auto& sampler = animation.samplers[ch.sampler];
        WeightsChannel c;
        c.node = ch.target_node;
        c.interpolation = sampler.interpolation.empty() ? "LINEAR" : sampler.interpolation;
        if (c.interpolation != "LINEAR" && c.interpolation != "STEP" && c.interpolation != "CUBICSPLINE")
            throwBadInput(what + ": interpolation '" + c.interpolation + "' is not one glTF defines");
        const gltf::AccessorData input = gltf::readAccessor(model, sampler.input, what + " input");
        if (input.components != 1 || input.count == 0) throwBadInput(what + ": the input is not a list of times");
        c.times = input.values;
        for (size_t k = 0; k < c.times.size(); ++k)
            if (!std::isfinite(c.times[k]) || (k && !(c.times[k] > c.times[k - 1])))
                throwBadInput(what + ": keyframe times must be finite and increasing");
        c.values = gltf::readAccessor(model, sampler.output, what + " output");
        const size_t per = c.interpolation == "CUBICSPLINE" ? 3 : 1;
        size_t targets = 0;
        for (const auto& p : model.meshes[node.mesh].primitives) targets = std::max(targets, p.targets.size());
        if (c.values.components != 1 || targets == 0 || c.values.count != c.times.size() * per * targets)
            throwBadInput(what + ": " + std::to_string(c.values.count) + " weights for " +
                          std::to_string(c.times.size()) + " keyframes of " + std::to_string(targets) + " targets");
        c.targets = targets;
        out.push_back(std::move(c));
    }
    if (out.empty()) throwBadInput("glTF: the first animation has no morph target weights");
    return out;
}

} // namespace

GltfMorphFrames readGltfMorphFrames(std::span<const uint8_t> bytes, bool binary, const std::string& baseDir,
                                    Warnings& warnings, const GltfMorphRequest& request) {
    const double fps = request.fps;
    Warnings ignored; // readGltf's warnings are the same file's; report them once
    const std::string* dir = request.embeddedOnly ? nullptr : &baseDir;
    const Mesh reference = gltf::readFrom(bytes, binary, dir, ignored, request.filesRead, nullptr, nullptr);
    const gltf::Loaded loaded = gltf::load(bytes, binary, dir, warnings, nullptr, nullptr);
    const tinygltf::Model& model = loaded.model;
    const std::vector<WeightsChannel> channels = weightsChannels(model);

    GltfMorphFrames out;
    std::set<double> keys;
    for (const auto& c : channels) keys.insert(c.times.begin(), c.times.end());
    if (!(fps > 0)) {
        out.times.assign(keys.begin(), keys.end());
    } else {
        const double first = *keys.begin(), last = *keys.rbegin();
        const double count = std::floor((last - first) * fps + 1e-9) + 1;
        if (!(count <= double(request.maxFrames)))
            throwBadInput("glTF: the animation at " + std::to_string(fps) + " frames per second is more than " +
                          std::to_string(request.maxFrames) + " frames");
        for (double k = 0; k < count; ++k) out.times.push_back(first + k / fps);
    }
    if (out.times.size() > request.maxFrames)
        throwBadInput("glTF: the animation has " + std::to_string(out.times.size()) + " keyframes, more than " +
                      std::to_string(request.maxFrames));
    const uint64_t bytesNeeded = uint64_t(out.times.size()) * reference.positions.size() * sizeof(glm::dvec3);
    if (bytesNeeded > request.maxPositionBytes)
        throwBadInput("glTF: " + std::to_string(out.times.size()) + " frames of " +
                      std::to_string(reference.positions.size()) + " vertices need " + std::to_string(bytesNeeded) +
                      " bytes of positions, more than the " + std::to_string(request.maxPositionBytes) + " allowed");
    out.base = reference.positions;
    // Default-weight position -> welded vertex, exactly as readGltf welded it.
    std::map<std::array<double, 3>, uint32_t> vertexAt;
    for (size_t v = 0; v < reference.positions.size(); ++v)
        vertexAt[{reference.positions[v].x, reference.positions[v].y, reference.positions[v].z}] = uint32_t(v);
    for (const double t : out.times) {
        std::map<int, std::vector<double>> weights; // per animated node
        for (const auto& c : channels) weights[c.node] = sample(c, t);
        std::vector<glm::dvec3> positions = reference.positions;
        std::vector<uint8_t> set(positions.size(), 0);
        bool apart = false;
        for (const auto& instance : loaded.instances) {
            const auto& node = model.nodes[instance.node];
            if (node.mesh < 0) continue;
            const auto& mesh = model.meshes[node.mesh];
            const std::vector<double>& defaults = node.weights.empty() ? mesh.weights : node.weights;
            auto animated = weights.find(instance.node);
            for (size_t p = 0; p < mesh.primitives.size(); ++p) {
                const auto& prim = mesh.primitives[p];
                const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
                if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                    mode != TINYGLTF_MODE_TRIANGLE_FAN)
                    continue;
                const std::string what = "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p);
                const auto base = gltf::primitiveData(model, prim, loaded.pre, {node.mesh, int(p)}, defaults, what);
                if (animated == weights.end()) continue; // unchanged: the reference's positions
                std::vector<double> w = animated->second;
                w.resize(prim.targets.size(), 0.0);
                const auto frame = gltf::primitiveData(model, prim, loaded.pre, {node.mesh, int(p)}, w, what);
                for (size_t i = 0; i < base.positions.size(); ++i) {
                    const glm::dvec3 key(instance.transform * glm::dvec4(base.positions[i], 1.0));
                    auto it = vertexAt.find({key.x, key.y, key.z});
                    if (it == vertexAt.end()) continue; // in no face of the reference (a degenerate triangle's)
                    const glm::dvec3 q(instance.transform * glm::dvec4(frame.positions[i], 1.0));
                    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                        throwBadInput("glTF: " + what + " POSITION " + std::to_string(i) + " is not finite at time " +
                                      std::to_string(t));
                    if (set[it->second] && positions[it->second] != q) apart = true;
                    if (!set[it->second]) positions[it->second] = q;
                    set[it->second] = 1;
                }
            }
        }
        out.unwelded += apart;
        out.positions.push_back(std::move(positions));
    }
    if (out.unwelded)
        warnings.add(std::to_string(out.unwelded) + " frames move vertices apart that the mesh welds (same "
                     "position under the default weights); each takes its first vertex's position");
    return out;
}

} // namespace limn
