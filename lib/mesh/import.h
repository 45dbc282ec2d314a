// Mesh import by format: chosen by the file's extension, or by content when reading stdin.
#pragma once

#include "base/warnings.h"
#include "mesh/gltf.h"
#include "mesh/material.h"
#include "mesh/mesh.h"

#include <optional>
#include <span>
#include <string>

namespace limn {

enum class MeshFormat { Obj, Gltf, Glb, Ply, Off, Container, Unknown };

MeshFormat formatFromExtension(const std::string& extension);
// Sniffs the first bytes: .limn magic, glTF binary magic, '{' (glTF JSON), "ply", "OFF"/"STOFF"
// etc.; anything else is taken as OBJ.
MeshFormat formatFromContent(std::span<const uint8_t> bytes);
const char* formatName(MeshFormat format);

// Reads a mesh from `bytes`; `path` gives the extension and the base directory for external
// glTF buffers ("-" for stdin: sniffed). A .limn container yields its MESH chunks. Errors carry
// the file name.
// `filesRead` (optional) gets the files besides `path` that the mesh pulled in (a .gltf's
// buffers and images), for depfiles. `material` (optional) gets a glTF's base colour (see
// readGltf) and a container's MATL chunk; other formats leave it unchanged.
// `polygons` (optional) is passed to the glTF reader (FB_ngon_encoding); other formats leave it
// unchanged.
Mesh importMesh(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings,
                std::vector<std::string>* filesRead = nullptr, std::optional<MeshMaterial>* material = nullptr,
                GltfPolygons* polygons = nullptr);
// The format importMesh reads `path` (and, for standard input, `bytes`) as.
MeshFormat importFormat(const std::string& path, std::span<const uint8_t> bytes);

// The mesh of a .limn container (its MESH chunks; filesRead untouched) or of any mesh file
// importMesh reads: what every tool that takes "a container or a mesh" reads.
Mesh loadOrImportMesh(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings,
                      std::vector<std::string>* filesRead = nullptr);

// A .gltf's or .glb's morph-target animation (readGltfMorphFrames), its buffers found next to
// `path` as importMesh finds them. Errors carry the file name.
GltfMorphFrames importGltfMorphFrames(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings,
                                      const GltfMorphRequest& request = {});

// Reads the file (or stdin) and imports it.
Mesh importMeshFile(const std::string& path, Warnings& warnings,
                    std::vector<std::string>* filesRead = nullptr);

// Writes OBJ, PLY or OFF by the output's extension (stdout: OBJ; anything else is refused).
std::string exportMesh(const Mesh& mesh, const std::string& path);
// Throws Error(Usage) unless `path` is standard output, a device or pipe, or ends in .obj,
// .ply or .off.
void checkExportPath(const std::string& path);

} // namespace limn
