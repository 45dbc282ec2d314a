// View-adaptive tessellation, pass 2 of 5 (issue 11): per edge piece, its segments this frame.
// Decided once per piece from data both sides share: the piece owner's surface at the piece's
// two ends and middle (the draw's own sums, surface_eval_impl.glsl's elementPositions3), projected to
// pixels; so the two patches of an edge can never disagree (OpenSubdiv PR #435). The rate is
// ceil(length / edgePixels), at least the displacement map's texels along the piece (at most
// one segment per 2 pixels), clamped to 1..tess and to the piece's parameter span. A piece whose
// every user element is culled gets 1, so does one whose samples are all beyond one clip plane
// (off screen: only its look is at stake, never the watertightness, which holds at any rates);
// one that crosses the eye plane gets tess. Written as rate | size << 16, where size is the
// rate its projected length alone asks for: adaptive_counts.comp sizes an element's interior
// from its sides' sizes, so a large element whose sides are off screen stays fine inside.
// Also written: the piece's two ends in pixels (from the image's bottom left, as the cull's
// sample positions), which adaptive_counts.comp tests a flat element's triangles with; far
// beyond any image (ADAPTIVE_NO_ENDS) where the piece was not evaluated or an end is behind the eye.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "surface_eval.glsl"
#include "adaptive_tess.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Patches { Patch p[]; } patches;
layout(std430, binding = 2) readonly buffer Irregulars { IrregularFace f[]; } irregulars;
layout(std430, binding = 3) readonly buffer Limits { vec4 v[]; } limits;
layout(std430, binding = 4) readonly buffer Pieces { uvec4 v[]; } pieces;
layout(std430, binding = 5) readonly buffer Cull { uint c[]; } cull;
layout(std430, binding = 6) writeonly buffer Rates { uint r[]; } rates;
layout(std430, binding = 7) writeonly buffer PieceEnds { vec4 v[]; } pieceEnds; // start xy, end xy

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) mat4 viewProj;
    vec2 halfViewport;  // pixels per unit of NDC
    float edgePixels;   // target segment length
    uint tess;          // most segments per piece
    uint patchCount;
    float texels;       // displacement map texels per unit of UV (0: none)
} pc;

// Chord tolerance per pixel of --edge-pixels: 0.1 px at the default 4 (on spot and catmark_car at
// depth 6 it drew 1.4-3.6% more triangles and halved the 4-sample silhouette pixels that differ
// from the fixed grids'); coarser targets loosen it with them.
const float kChordPerEdgePixel = 0.025;
// Across a semi-sharp crease: a piece the crease patch owns is graded towards the crease
// (adaptive_emit.comp), its first segment about len / r^2, kept below kCreaseFirstPixels (at
// most 2^ceil(sharpness) segments, and enough for its last one, about 2 len / r, to keep the
// target); a piece another element owns is even, segments of about kCreasePixels.
const float kCreaseFirstPixels = 0.25;
const float kCreasePixels = 1.0;

#define LIMN_NO_TESS_VERTICES
#include "surface_eval_impl.glsl"

uint midST(uint a, uint b) {
    return (((a & 0xFFFFu) + (b & 0xFFFFu)) / 2u) | ((((a >> 16) + (b >> 16)) / 2u) << 16);
}

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    uvec4 p0 = pieces.v[2u * i], p1 = pieces.v[2u * i + 1u];
    bool visible = cull.c[p1.x] == 0u || (p1.y != 0xFFFFFFFFu && cull.c[p1.y] == 0u);
    uint cap = max(min(pc.tess, p0.w), 1u);
    uint r = 1u, size = 1u;
    vec4 ends = vec4(ADAPTIVE_NO_ENDS);
    if (visible) {
        uint st[3] = uint[3](p0.y, midST(p0.y, p0.z), p0.z);
        vec2 px[3];
        uint behind = 0u, allOut = 63u;
        vec3 P[3];
        elementPositions3(p0.x, st, pc.patchCount, P);
        for (int k = 0; k < 3; ++k) {
            vec4 c = pc.viewProj * vec4(P[k], 1.0);
            uint o = 0u;
            if (c.x < -c.w) o |= 1u;
            if (c.x > c.w) o |= 2u;
            if (c.y < -c.w) o |= 4u;
            if (c.y > c.w) o |= 8u;
            if (c.z < 0.0) o |= 16u;
            if (c.z > c.w) o |= 32u;
            allOut &= o;
            if (!(c.w > 1e-6)) ++behind;
            px[k] = c.w > 1e-6 ? c.xy / c.w * pc.halfViewport : vec2(0.0);
        }
        float len = distance(px[0], px[1]) + distance(px[1], px[2]);
        if (behind == 0u) ends = vec4(px[0], px[2]) + pc.halfViewport.xyxy;
        if (behind == 3u) {
            r = 1u, size = 1u;
        } else if (behind != 0u || !(len < 1e9)) {
            r = cap, size = cap;
        } else {
            // Flatness (the chord criterion): the middle sample's distance in pixels from the
            // chord of the ends, d, shrinks like d / n^2 over n segments; where the projected
            // edge bends (silhouettes, tight curves) enough segments keep each chord within
            // kChordPerEdgePixel * edgePixels of the curve, so the outline the rasterizer
            // samples is the surface's.
            vec2 chord = px[2] - px[0];
            float cl = length(chord);
            vec2 off = px[1] - 0.5 * (px[0] + px[2]);
            float d = cl > 1e-6 ? abs(chord.x * off.y - chord.y * off.x) / cl : length(off);
            float want = max(ceil(len / pc.edgePixels), ceil(sqrt(d / (kChordPerEdgePixel * pc.edgePixels))));
            // A piece across the crease of a single-crease patch: the surface bends within
            // 2^-ceil(s) of the crease (in the patch's own units at any level, s decayed with the
            // level). Owned by the crease patch, the piece is graded towards the crease: its
            // first segment stays within kCreaseFirstPixels (sqrt(len / that) segments), where
            // the bend decides a pixel's shade, at most 2^ceil(s) and at least twice the length
            // rule (the graded last segment is about twice an even one). Owned by another element
            // it is even, up to one segment per pixel (kCreasePixels). Which way the piece runs
            // is read from its owner's parameters; a piece owned by another element counts as
            // across when its other user is a crease patch (conservative). Pieces along the
            // crease get nothing extra: at 2^ceil(s) both ways (an earlier rule) catmark_car at
            // depth 6 drew 2.9 M triangles instead of about 0.3 M for the same image.
            for (int k = 0; k < 2; ++k) {
                uint e = k == 0 ? p1.x : p1.y;
                if (e == 0xFFFFFFFFu || e >= pc.patchCount) continue;
                Patch pt = patches.p[e];
                uint crease = (pt.levelBoundary >> 16) & 0xFu;
                if (crease == 0u) {
                    if (k == 0) continue; // the owner is no crease patch: ask the other user
                    break;
                }
                if (k == 0) {
                    bool alongS = (p0.y & 0xFFFFu) != (p0.z & 0xFFFFu);
                    bool creaseAlongS = (crease & 5u) != 0u; // on a t = 0 or t = 1 side
                    if (alongS == creaseAlongS) break;   // along the crease
                }
                float most = exp2(ceil(pt.sharpness));
                if (k == 0) // graded (adaptive_emit.comp's pieceST)
                    want = max(want, max(ceil(2.0 * len / pc.edgePixels),
                                         min(most, ceil(sqrt(len / kCreaseFirstPixels)))));
                else
                    want = max(want, min(most, ceil(len / kCreasePixels)));
                break;
            }
            if (pc.texels > 0.0) want = max(want, min(ceil(uintBitsToFloat(p1.z) * pc.texels), ceil(0.5 * len)));
            size = uint(clamp(want, 1.0, float(cap)));
            r = allOut != 0u ? 1u : size;
        }
    }
    rates.r[i] = r | (size << 16);
    pieceEnds.v[i] = ends;
}
