// Codec of the TBLS chunk (formats/limn.md, "Subdivision tables").
#pragma once

#include "container/container.h"
#include "mesh/mesh.h"
#include "subdiv/tables.h"

namespace limn {

inline constexpr FourCC kTablesChunk{"TBLS"};
// Version 2 adds single-crease patches (a crease edge and a sharpness per patch); version 1 is
// still read (its patches have none). Version 3 adds the irregular faces' quadtrees: levels
// beyond the depth, sub-patches, nodes and leaves (docs/irregular.md); older ones have none.
// Version 4 stores the same tables compactly: stencil tables as palette indices and varint
// differences, per-valence bases with each distinct row of weights once (formats/limn.md).
// Version 5 stores each basis as its one-level program (expanded by the reader to the same
// weights) and the quadtree nodes, smooth faces and smooth points as varint streams
// (tables_surface_records.h); and lets a quadtree node below a root name a smooth face (a
// descendant whose semi-sharp creases have decayed, drawn from the per-valence basis; its
// support points at its own level). formats/tbls.md, "Smooth faces below level N". Version 6
// stores a level whose stencil tables are the previous level's shifted one level (below a
// decaying crease, each level is refined as the one before) as a bit instead of its tables, and
// the sub-patches without their domains, which the quadtrees give (formats/tbls.md, "Repeated
// levels", "Sub-patch domains"). Version 7 stores each basis with its configuration and support
// size (FVSF version 3's layout), so that faces around one boundary vertex can take a basis per
// configuration (formats/tbls.md, "Boundary configurations").
inline constexpr uint32_t kTablesChunkVersion = 7;
// Tables with decaying-crease chains (TablesOptions::creaseChains) are written as version 8,
// which the readers also take.
inline constexpr uint32_t kTablesChunkChainVersion = 8;
// Tables with irregular bases are written as version 9, which stores the bases' and chains'
// programs through one program dictionary per chunk (formats/tbls.md, "Program dictionary").
inline constexpr uint32_t kTablesChunkDictionaryVersion = 9;

// Writes the current version (0: version 9 for tables with irregular bases, else 7); 3 (the
// plain layout) to 8 for tests and fuzz seeds of older files (tables with smooth faces below
// level N need version 5 or later, with boundary bases 7, with chains 8).
Chunk encodeTablesChunk(const Tables& tables, uint32_t version = 0);

// Decodes and validates every count and index. With `mesh`, also checks that the tables were
// built from this mesh's topology (hash of faces, tags and options) and that ptex ids exist.
Tables decodeTablesChunk(const Chunk& chunk, const Mesh* mesh);

// Number of ptex faces of a mesh (OpenSubdiv's numbering: 1 per quad, n per n-gon).
uint32_t ptexFaceCount(const Mesh& mesh);

} // namespace limn
