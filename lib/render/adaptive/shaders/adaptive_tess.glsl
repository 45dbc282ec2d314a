// View-adaptive tessellation (lib/render/adaptive/adaptive_tess.h, docs/adaptive.md): the records that
// lib/tess/edge_pieces.h builds once from topology, as the compute passes read them. Mirrors
// limn::render::GpuAdaptiveElement and the uvec4 layouts documented in adaptive_tess.h.
#ifndef LIMN_ADAPTIVE_TESS_GLSL
#define LIMN_ADAPTIVE_TESS_GLSL

struct AdaptiveElement {
    uvec4 sideFirst;  // side pieces in the Pieces buffer, per side (counter-clockwise: t=0, s=1, t=1, s=0)
    uvec4 sideCount;
    vec2 uv[4];       // own chart's UV at the corners (0,0), (1,0), (1,1), (0,1)
    uint level;       // patch level, 255 for an irregular face
    uint crease;      // a single-crease patch's crease side (1 t=0, 2 s=1, 4 t=1, 8 s=0), else 0
    uint pad1, pad2;
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
// A flat element (its boundary polygon, fanned) has mu = 1, and in mv's place which of its at
// most 6 fan triangles are drawn (bit i: triangle i; the others cover no sample of the image).
uint adaptivePackRates(uint mu, uint mv) { return mu | (mv << 15); }
uvec2 adaptiveRates(uint packed) { return uvec2(packed & 0x7FFFu, (packed >> 15) & 0x7FFFu); }
uint adaptivePackFlat(uint fanMask) { return adaptivePackRates(1u, fanMask); }

// A flat element's fan (adaptive_emit.comp draws it, adaptive_counts.comp tests it against the
// samples): triangle i of the B - 2 is (apex, apex + i + 1, apex + i + 2) mod B over its boundary
// points, the apex the first point that is not a corner, on the first side with more than one
// point (corner 0 when there is none). That point lies on one side's middle, every other point
// on another side or that side's far end, so no fan triangle has its three points on one side (a
// sliver that folds over the others where the surface bends).
uint adaptiveFanApex(uint sideStart[4], uint sideTotal[4]) {
    uint apex = 0u;
    for (uint k = 4u; k > 0u; --k)
        if (sideTotal[k - 1u] > 1u) apex = sideStart[k - 1u] + 1u;
    return apex;
}

// Sample position s within a pixel (1/256 pixel units, x | y << 8 in 16 bits each, two a word),
// as the host packs the image's pattern for adaptive_cull.comp and adaptive_counts.comp.
vec2 adaptiveSamplePosition(uvec2 packed, uint s) {
    uint b = (s < 2u ? packed.x : packed.y) >> (16u * (s & 1u));
    return vec2(float(b & 0xFFu), float((b >> 8) & 0xFFu)) / 256.0;
}

// All B - 2 triangles of a flat element's fan.
uint adaptiveWholeFan(uint B) { return (1u << (B - 2u)) - 1u; }

// adaptive_rates.comp's piece ends where it has none (not evaluated, or behind the eye).
const float ADAPTIVE_NO_ENDS = 3.0e38;

// Segments graded towards a single-crease patch's crease, whose surface bends within 2^-s of it
// (adaptive_rates.comp asks for them, adaptive_emit.comp places them): the offset of step k of n
// from the crease end of an integer span of D >= n units, k + floor(floor((D - n) k / n) k / n).
// At least one unit a step (no two points meet), quadratic in k (the first step is about D / n^2,
// the last about 2 D / n), exact at both ends, in integers so both users of a piece agree.
uint gradedOffset(uint D, uint k, uint n) { return k + (((D - n) * k / n) * k) / n; }

// Whether an element of crease side c runs its segments along s (false: along t) across it.
bool creaseAcrossS(uint c) { return (c & 10u) != 0u; } // the crease on an s = 1 or s = 0 side
bool creaseAtZero(uint c) { return (c & 9u) != 0u; }   // on a t = 0 or s = 0 side

#endif
