// The test models (tests/data) as triangle meshes for Loop subdivision, imported with the
// defaults (no --triangulate: a polygon is an error), warnings dropped.
#pragma once

#include "loop/trimesh.h"
#include "mesh/import.h"
#include "test_support.h"

#include <string>

namespace limn::test {

inline loop::TriMesh loadTriMesh(const std::string& model) {
    Warnings w;
    return loop::fromMesh(importMeshFile(modelPath(model).string(), w), {}, w);
}

} // namespace limn::test
