// Codec of the mesh chunks MESH, FVUV and TAGS (formats/limn.md, "Mesh chunks").
#pragma once

#include "container/container.h"
#include "mesh/material.h"
#include "mesh/mesh.h"

#include <optional>

namespace limn {

inline constexpr FourCC kMeshChunk{"MESH"};
inline constexpr FourCC kUVChunk{"FVUV"};
inline constexpr FourCC kTagsChunk{"TAGS"};
inline constexpr FourCC kMaterialChunk{"MATL"};

Chunk encodeMeshChunk(const Mesh& mesh);
Chunk encodeUVChunk(const Mesh& mesh);
Chunk encodeTagsChunk(const Tags& tags);

// Stores MESH, TAGS and (when the mesh has UVs) FVUV; removes a stale FVUV otherwise.
void storeMesh(Container& container, const Mesh& mesh);

// MATL (optional): the base colour factor and the encoded texture (formats/limn.md).
Chunk encodeMaterialChunk(const MeshMaterial& material);
// The decoded MATL chunk, or nullopt when the container has none. Throws Error(BadInput) for a
// malformed one.
std::optional<MeshMaterial> loadMaterial(const Container& container);

// Decodes and validates the mesh chunks. Throws Error(BadInput) when MESH is missing or any
// count, index or value is out of bounds.
Mesh loadMesh(const Container& container);

} // namespace limn
