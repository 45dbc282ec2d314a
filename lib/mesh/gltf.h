// glTF 2.0 (.gltf with external or data: buffers, .glb) through tinygltf: every triangle
// primitive (triangles, strips, fans; points and lines are skipped with a warning) of every mesh
// instanced by the scene, node transforms applied (a mirroring one reverses the winding, glTF
// 2.0, 3.7.4), the mesh's default morph target weights applied, vertices welded by exact
// position (glTF splits them at UV seams), TEXCOORD_0 kept as face-varying UVs. Compressed
// geometry is decoded by its own library: KHR_draco_mesh_compression by Draco,
// EXT_/KHR_meshopt_compression by meshoptimizer; sparse accessors and accessors without a buffer
// view (zeros) are read. A required extension limn does not read is refused by name; an optional
// one is ignored with a warning. The node graph must be acyclic and draw at most a million
// instances (glTF asks for trees), checked before any geometry is read.
#pragma once

#include "base/warnings.h"
#include "mesh/material.h"
#include "mesh/mesh.h"

#include <cstdint>
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
// The base colour texture's KHR_texture_transform (offset, rotation, scale) is applied to the
// UVs, so that they address the texture as a viewer shows it.
// `polygons` (optional): FB_ngon_encoding (a polygon stored as a fan of consecutive triangles
// that share their first index) is rebuilt into polygons when `polygons->rebuildNgons` is set;
// the reader reports whether the file uses the encoding and how many polygons it rebuilt.
struct GltfPolygons {
    bool rebuildNgons = false;    // in
    bool fileHasNgonEncoding = false; // out
    size_t ngonsRebuilt = 0;       // out: polygons of more than three corners
};
Mesh readGltf(std::span<const uint8_t> bytes, bool binary, const std::string& baseDir,
              Warnings& warnings, std::vector<std::string>* filesRead = nullptr,
              std::optional<MeshMaterial>* material = nullptr, GltfPolygons* polygons = nullptr);

// readGltf for untrusted bytes that must not reach the file system (a fuzzer, a service): no file
// is read, so a buffer or image must be embedded (a GLB buffer or a data: URI); one named by any
// other URI is refused.
Mesh readGltfEmbedded(std::span<const uint8_t> bytes, bool binary, Warnings& warnings,
                      std::optional<MeshMaterial>* material = nullptr);

// A glTF's morph-target animation as control-point sets on readGltf's mesh (same topology, same
// vertex order): the first animation's `weights` channels, sampled at their keyframes (fps 0) or
// every 1/fps seconds from the first keyframe to the last, with the channel's interpolation
// (STEP, LINEAR, CUBICSPLINE; glTF 2.0, 3.11). Vertices that readGltf welds (same position under
// the default weights) take the first one's position; a frame in which they move apart is
// counted in `unwelded`. Refuses a file without such an animation, and one whose frames would be
// more than `maxFrames` or whose positions would take more than `maxPositionBytes` (checked
// before they are computed).
struct GltfMorphFrames {
    std::vector<glm::dvec3> base;                    // readGltf's positions (the default weights)
    std::vector<double> times;                       // seconds
    std::vector<std::vector<glm::dvec3>> positions;  // per frame, one per vertex of readGltf's mesh
    size_t unwelded = 0;                             // frames where welded vertices move apart
};
struct GltfMorphRequest {
    double fps = 0; // 0: the keyframes
    size_t maxFrames = 1'000'000;
    uint64_t maxPositionBytes = UINT64_MAX;
    std::vector<std::string>* filesRead = nullptr; // the external files read, as for readGltf
    bool embeddedOnly = false; // read no file, as readGltfEmbedded
};
GltfMorphFrames readGltfMorphFrames(std::span<const uint8_t> bytes, bool binary, const std::string& baseDir,
                                    Warnings& warnings, const GltfMorphRequest& request = {});

} // namespace limn
