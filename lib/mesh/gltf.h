// glTF 2.0 (.gltf with external or data: buffers, .glb) through tinygltf: every triangle
// primitive (triangles, strips, fans; points and lines are skipped with a warning) of every mesh
// instanced by the scene, node transforms applied, vertices welded by
// exact position (glTF splits them at UV seams), TEXCOORD_0 kept as face-varying UVs.
#pragma once

#include "base/warnings.h"
#include "mesh/material.h"
#include "mesh/mesh.h"

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace limn {

// `baseDir` resolves external buffers (empty for stdin: then only embedded buffers work).
// UVs are converted to limn's convention (v up, as in OBJ): v_limn = 1 - v_gltf.
// `filesRead` (optional) gets every external file the asset pulled in (buffers, images), for
// depfiles.
// `material` (optional) gets the base colour (factor, texture bytes) of the material of the first
// triangle primitive that has one; it is left unchanged when no primitive has a material. Other
// materials are dropped with a warning (limn draws one material per mesh), and so is a texture
// that uses another UV set than TEXCOORD_0.
Mesh readGltf(std::span<const uint8_t> bytes, bool binary, const std::string& baseDir,
              Warnings& warnings, std::vector<std::string>* filesRead = nullptr,
              std::optional<MeshMaterial>* material = nullptr);

} // namespace limn
