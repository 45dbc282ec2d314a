// A bounding-volume hierarchy over triangles for exact point-to-mesh distances, the kernel of the
// measurement in math.md B.8 (there done with a KD-tree and candidate triangles; a BVH with
// branch-and-bound search gives the exact nearest triangle instead).
#pragma once

#include "loop/trimesh.h"

#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace limn::loop {

class TriangleBvh {
public:
    TriangleBvh(const std::vector<glm::dvec3>& positions, const std::vector<Tri>& triangles);
    TriangleBvh(const TriangleBvh&) = delete;
    TriangleBvh& operator=(const TriangleBvh&) = delete;

    // Squared distance from p to the nearest point of the mesh (infinity for an empty mesh).
    double squaredDistance(const glm::dvec3& p) const;

private:
    static constexpr uint32_t kLeafSize = 4;
    void build(const std::vector<uint64_t>& codes, uint32_t node, uint32_t begin, uint32_t end);

    struct Node {
        float lo[3], hi[3]; // rounded outwards, so the box still contains its triangles
        uint32_t first = 0; // leaf: first triangle in tris_; inner: left child (right = first+1)
        uint32_t count = 0; // triangles in a leaf; 0 for an inner node
    };
    std::vector<Node> nodes_;
    std::vector<std::array<glm::dvec3, 3>> tris_; // triangle corners in leaf order (cache-friendly)
};

// Squared distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
double pointTriangleSquaredDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                    const glm::dvec3& c);

} // namespace limn::loop
