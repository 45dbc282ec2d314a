// PLY and OFF import through OpenMesh's readers. OpenMesh's own importer duplicates the vertices of
// faces it cannot add to a half-edge mesh (non-manifold input), which would silently change the
// topology; limn plugs in an importer that records vertices, faces and texture coordinates as
// they are read, so nothing is lost and non-manifold input reaches the topology layer intact.
// UVs come from per-vertex s/t (or u/v) properties or a per-corner "texcoord" face list (PLY).
// OpenMesh trusts its input, so the bytes pass limn's checks first (openmesh_guard.h): text and
// binary PLY, and text OFF as OFF, NOFF, STOFF or STNOFF (STOFF texture coordinates ignored).
#pragma once

#include "base/warnings.h"
#include "mesh/mesh.h"

#include <span>
#include <string>

namespace limn {

// `extension` is ".ply" or ".off".
Mesh readWithOpenMesh(std::span<const uint8_t> bytes, const std::string& extension,
                      Warnings& warnings);

// ASCII PLY (float64 positions, faces as vertex_indices lists; per-corner UVs as a face
// "texcoord" list when the mesh has UVs) and OFF, with shortest round-trip numbers.
std::string writePly(const Mesh& mesh);
std::string writeOff(const Mesh& mesh);

} // namespace limn
