// Mesh import by format: chosen by the file's extension, or by content when reading stdin.
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"

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
Mesh importMesh(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings);

// Reads the file (or stdin) and imports it.
Mesh importMeshFile(const std::string& path, Warnings& warnings);

// Writes OBJ, PLY or OFF by the output's extension (stdout and unknown extensions: OBJ).
std::string exportMesh(const Mesh& mesh, const std::string& path);

} // namespace limn
