// The triangles limn-render drew (DrawnMesh), written for other tools (--mesh-out): PLY (ply.h,
// every value the renderer has), OBJ and glTF 2.0 (positions, normals and the texture UV, for
// Blender and glTF viewers). The format follows the file's extension. Every writer carries the
// same float values bit for bit: OBJ writes the shortest text that reads back to the same float,
// glTF the floats themselves (its texture v flipped, below). The bytes depend only on the mesh.
//
// OBJ: `v`, `vt` (only when the mesh has texture coordinates), `vn`, and triangles
//   `f v/vt/vn` (1-based). Each attribute is written once per distinct value (bit-equal floats,
//   in order of first use by the vertices), so seam copies share their `v` and the mesh is one
//   connected piece where the drawn surface is; `vt` has v = 0 at the bottom of the image (OBJ's
//   convention, the same as the mesh's UVs and PLY's s, t). OBJ has no per-vertex attribute for
//   PLY's `approximate`: when some vertex is, comment lines after the first give their count
//   and list their `v` indices (`# approximate v 12 40 ...`).
// glTF 2.0 (.glb binary, or .gltf JSON with the buffer embedded as a base64 data: URI, so one
//   file is written and it stays atomic): one mesh, one indexed triangle primitive with
//   POSITION (with min/max), NORMAL and, when the mesh has texture coordinates, TEXCOORD_0;
//   indices UNSIGNED_INT. Vertices are the drawn ones, split where the texture UV differs. When
//   some vertex is approximate, the application-specific attribute _APPROXIMATE (FLOAT scalar,
//   1 there, 0 elsewhere) carries PLY's `approximate`.
//   TEXCOORD_0 uses glTF's top-left origin: (s, 1 - t) of OBJ's/PLY's (s, t), computed in float.
//   asset.generator is "limn-render" (no version: the bytes must not change with it).
#pragma once

#include "export/ply.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace limn::exporting {

enum class ExportFormat { Ply, Obj, Gltf, Glb };

// What --mesh-out accepts, for messages and help.
inline constexpr const char* kExportFormats = ".ply, .obj, .gltf, .glb";

// The format of `path` by its extension (case-insensitive); "-" (standard output) is PLY. None
// for any other extension.
std::optional<ExportFormat> exportFormatFromPath(const std::string& path);

// Throws Error(BadInput) when a triangle names a vertex the mesh does not have.
std::vector<uint8_t> encodeObj(const DrawnMesh& mesh);
std::vector<uint8_t> encodeGltf(const DrawnMesh& mesh, bool binary);

// `plyAscii` chooses ASCII PLY (ignored by the other formats).
std::vector<uint8_t> encodeMesh(const DrawnMesh& mesh, ExportFormat format, bool plyAscii);

} // namespace limn::exporting
