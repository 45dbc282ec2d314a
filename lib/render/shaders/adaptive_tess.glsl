// View-adaptive tessellation (issue 11; lib/render/adaptive_tess.h): the records that
// lib/tess/edge_pieces.h builds once from topology, as the compute passes read them. Mirrors
// limn::render::GpuAdaptiveElement and the uvec4 layouts documented in adaptive_tess.h.
#ifndef LIMN_ADAPTIVE_TESS_GLSL
#define LIMN_ADAPTIVE_TESS_GLSL

struct AdaptiveElement {
    uvec4 sideFirst;  // into sidePieces, per side (counter-clockwise: t=0, s=1, t=1, s=0)
    uvec4 sideCount;
    vec2 uv[4];       // own chart's UV at the corners (0,0), (1,0), (1,1), (0,1)
    uint level;       // patch level, 255 for an irregular face
    uint pad0, pad1, pad2;
};

// Side piece: x = piece, y = point where it starts (this side's direction), z = 1 when the side
// runs against the piece owner's direction, w = from | to << 16 (this element's parameter along
// the side, 1/32768).
// Piece (two uvec4): [0] = owner element, owner's st at its start, at its end, parameter span;
// [1] = user elements (0xFFFFFFFF: none), uv length (float bits), 0.
// Point (one uvec4 after the pieces): owner element, owner's st.

#define ADAPTIVE_CULLED 0x80000000u

// An element's interior rates (adaptive_counts.comp) in the info record's first word: mu along s
// in bits 0-14, mv along t in bits 15-29 (--tess is at most 4096), ADAPTIVE_CULLED in bit 31.
uint adaptivePackRates(uint mu, uint mv) { return mu | (mv << 15); }
uvec2 adaptiveRates(uint packed) { return uvec2(packed & 0x7FFFu, (packed >> 15) & 0x7FFFu); }

#endif
