// Codec of the BLND chunk (formats/limn.md, "BLND"): the blending surface as a vertex shader reads
// it (math.md A.9; paper 001, 4.1: local-surface coefficients uploaded once, per-face data per
// draw). Records are fixed-size and 4-byte-word based, so the arrays upload to std430 storage
// buffers unchanged.
#pragma once

#include "blend/blend_surface.h"
#include "container/container.h"
#include "mesh/mesh.h"

#include <cstdint>

namespace limn::blend {

inline constexpr FourCC kBlendChunk{"BLND"};
inline constexpr uint32_t kBlendChunkVersion = 1;
inline constexpr size_t kBlendHeaderBytes = 24;
inline constexpr size_t kBlendVertexBytes = 128; // 32 words: k, kind, Θ, p, q, 27 coefficients
inline constexpr size_t kBlendFaceBytes = 32;    // 8 words: 4 vertex ids, 4 ring indices

// FNV-1a (container.h hashBytes) of the MESH payload; BLND records it to detect a stale surface.
uint64_t meshPayloadHash(const Container& container);

// Coefficients and chart parameters are rounded to f32 (the GPU's precision).
Chunk encodeBlendChunk(const BlendSurface& surface, uint64_t meshHash);

struct DecodedBlend {
    BlendSurface surface; // f32 values widened to f64
    uint64_t meshHash = 0;
};
// Checks everything the chunk can check alone (formats/limn.md, BLND validity) and throws
// Error(BadInput) naming the offset, vertex or face.
DecodedBlend decodeBlendChunk(const Chunk& chunk);

// Decodes the container's BLND and checks it against its MESH (counts, hash, face corners).
BlendSurface loadBlendSurface(const Container& container, const Mesh& mesh);

} // namespace limn::blend
