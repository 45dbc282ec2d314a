// Wavefront OBJ with OpenSubdiv's `t` tags (tests/data/osd/README.md): v, vt, vn (ignored),
// f with v, v/vt, v//vn, v/vt/vn and negative (relative) indices, faces of any size; tags crease,
// corner, hole, interpolateboundary, facevaryinginterpolateboundary, creasemethod, smoothtriangles.
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"

#include <span>
#include <string>

namespace limn {

// Throws Error(BadInput) with "line N" for malformed input; unknown tags and statements are
// warnings. The result is validated (validateMesh).
Mesh readObj(std::span<const uint8_t> text, Warnings& warnings);

// Shortest text that reads back to the same doubles and floats, so import -> export -> import
// is exact. Tags are written in OpenSubdiv's form.
std::string writeObj(const Mesh& mesh);

} // namespace limn
