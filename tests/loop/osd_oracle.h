// OpenSubdiv as the test oracle for Loop subdivision (../shared/docs/opensubdiv.md): uniform
// refinement with Far::PrimvarRefiner::Interpolate (positions) and InterpolateFaceVarying (UVs,
// FVAR_LINEAR_ALL), and vertex limits with PrimvarRefiner::Limit. Built straight from a limn::Mesh
// and its tags, independently of lib/loop.
#pragma once

#include "mesh/mesh.h"

#include <opensubdiv/far/topologyRefiner.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <memory>
#include <vector>

namespace limn::test {

struct OsdLoop {
    std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refiner;
    std::vector<std::vector<glm::dvec3>> positions; // per level 0..levels
    std::vector<std::vector<glm::dvec2>> uvs;       // per level, empty without UVs
    // Limit positions of the last level's vertices.
    std::vector<glm::dvec3> limit;
    const OpenSubdiv::Far::TopologyLevel& level(int l) const { return refiner->GetLevel(l); }
};

// Sdc::SCHEME_LOOP, boundary rule from the mesh's interpolateboundary tag (unset: edge-only, as
// OpenSubdiv's regression harness), crease and corner tags as given.
OsdLoop osdUniformLoop(const Mesh& mesh, int levels);

} // namespace limn::test
