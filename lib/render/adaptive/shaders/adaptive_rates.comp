// View-adaptive tessellation, pass 2 of 5: per edge piece, its segments this frame.
// Decided once per piece from data both sides share: the piece owner's surface at its ends and
// middle, and with maxError > 0 its quarters too (the draw's own sums, surface_eval_impl.glsl's
// elementPositions5), projected to pixels; so the two patches of an edge can never disagree
// (OpenSubdiv PR #435). The rate is the fewest segments whose chords stay within maxError pixels
// of the curve (see errorSegments below), at least ceil(length / edgePixels) (the longest segment
// allowed) and the displacement map's texels along the piece (at most one segment per 2 pixels),
// clamped to 1..tess and to the piece's parameter span. maxError 0 keeps the length rule with
// the chord tolerance it had before (kChordPerEdgePixel). A piece whose
// every user element is culled gets 1, so does one whose samples are all beyond one clip plane
// (off screen: only its look is at stake, never the watertightness, which holds at any rates);
// one that crosses the eye plane gets tess. Written as rate | size << 16, where size is the
// rate its projection alone asks for: adaptive_counts.comp sizes an element's interior
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
    float edgePixels;   // longest segment allowed (maxError 0: target segment length)
    uint tess;          // most segments per piece
    uint patchCount;
    float texels;       // displacement map texels per unit of UV (0: none)
    float maxError;     // pixels between a chord and the surface, at most (0: the length rule)
    // ... where every sample faces the eye (normal within 70 degrees of the view ray): there the
    // chords' error moves no outline, only where the shading lands (0: maxError everywhere).
    float interiorError;
} pc;

// maxError 0 (the length rule): chord tolerance per pixel of --edge-pixels: 0.1 px at 4 (on spot and catmark_car at
// depth 6 it drew 1.4-3.6% more triangles and halved the 4-sample silhouette pixels that differ
// from the fixed grids'); coarser targets loosen it with them.
const float kChordPerEdgePixel = 0.025;
// Across a semi-sharp crease: a piece the crease patch owns is graded towards the crease
// (adaptive_emit.comp), its first segment about len / r^2, kept below kCreaseFirstPixels (at
// most 2^ceil(sharpness) segments, and enough for its last one, about 2 len / r, to keep the
// target); a piece another element owns is even, segments of about kCreasePixels.
const float kCreaseFirstPixels = 0.25;
const float kCreasePixels = 1.0;
// A piece faces the eye (interiorError) where every sample's normal is within about 70 degrees
// of its view ray (cos 0.35), all on one side: nearer the outline, the chords' error moves it.
// Measured with --pixel-normals --interior-error 1 at 640x480 against --edge-pixels 1: within
// 60 degrees (cos 0.5) spot drew 18,773 triangles, 0.48% of its pixels off; at cos 0.35
// 17,235, 0.48%; at cos 0.25 16,275, 0.52% (over the criterion's 0.5%).
const float kFacingCos = 0.35;

#define LIMN_NO_TESS_VERTICES
#include "surface_eval_impl.glsl"

uint midST(uint a, uint b) {
    return (((a & 0xFFFFu) + (b & 0xFFFFu)) / 2u) | ((((a >> 16) + (b >> 16)) / 2u) << 16);
}

// The projection's Jacobian d(pixels)/dP at world point P (rows: x, y).
void pixelJacobian(vec3 P, out vec3 jx, out vec3 jy) {
    mat4 M = pc.viewProj;
    vec4 c = M * vec4(P, 1.0);
    vec3 rx = vec3(M[0][0], M[1][0], M[2][0]), ry = vec3(M[0][1], M[1][1], M[2][1]);
    vec3 rw = vec3(M[0][3], M[1][3], M[2][3]);
    jx = pc.halfViewport.x * (rx - (c.x / c.w) * rw) / c.w;
    jy = pc.halfViewport.y * (ry - (c.y / c.w) * rw) / c.w;
}

// The fewest even segments whose chords stay within maxError pixels of the piece's curve f on
// screen. A chord over a parameter step h is within h^2 / 8 max|f''| of its arc (linear
// interpolation's error bound), so n segments of a piece of span H keep E / n^2, E = H^2 / 8 f''.
// The second differences of the five samples are f''(1/4), f''(1/2), f''(3/4) times H^2 / 32,
// H^2 / 8, H^2 / 32 exactly when the piece is a cubic (a patch side: one polynomial segment of
// the bicubic B-spline), whose f'' is linear: so E at the ends and the three samples, a vector
// in world units, is E(0) = 2 E(1/4) - E(1/2) and E(1) = 2 E(3/4) - E(1/2), and its largest
// length is at an end. Each is projected to pixels with the projection's Jacobian at its point:
// what moves on screen (at a silhouette the outline, facing the eye only depth, which no pixel
// shows). That bounds the on-screen error up to the projection's change across a segment
// (first order). Not a bound where the piece is not a cubic: irregular faces (a valence basis,
// exact only away from their extraordinary corner) and across a semi-sharp crease (the crease
// rules below handle those); and inside an element only the sides are measured (docs/adaptive.md).
float errorSegments(vec3 S[5], vec3 SN[5], bool mayLoosen) {
    vec3 P[5] = vec3[5](S[0], S[3], S[1], S[4], S[2]); // in order along the piece
    vec3 E[5];
    E[1] = 4.0 * (P[1] - 0.5 * (P[0] + P[2]));
    E[2] = P[2] - 0.5 * (P[0] + P[4]);
    E[3] = 4.0 * (P[3] - 0.5 * (P[2] + P[4]));
    E[0] = 2.0 * E[1] - E[2];
    E[4] = 2.0 * E[3] - E[2];
    vec3 N[5] = vec3[5](SN[0], SN[3], SN[1], SN[4], SN[2]);
    float most = 0.0, side = 0.0;
    bool facing = mayLoosen && pc.interiorError > pc.maxError;
    for (int k = 0; k < 5; ++k) {
        vec3 jx, jy;
        pixelJacobian(P[k], jx, jy);
        most = max(most, length(vec2(dot(jx, E[k]), dot(jy, E[k]))));
        // The view ray at P is the kernel of the Jacobian, jx x jy. Every sample on the same
        // side (a piece across the outline turns from facing to facing away between two), none
        // degenerate.
        vec3 ray = cross(jx, jy);
        float c = dot(N[k], ray);
        facing = facing && abs(c) > kFacingCos * length(N[k]) * length(ray) && c * side >= 0.0;
        side = c;
    }
    float n = ceil(sqrt(most / (facing ? pc.interiorError : pc.maxError)));
    return n < 1e9 ? n : 1e9; // not finite: as fine as the piece may be
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
        // Start, middle, end, then the quarters (the error estimate's only).
        uint mid = midST(p0.y, p0.z);
        uint st[5] = uint[5](p0.y, mid, p0.z, midST(p0.y, mid), midST(mid, p0.z));
        uint count = pc.maxError > 0.0 ? 5u : 3u;
        vec2 px[5];
        uint behind = 0u, allOut = 63u;
        vec3 P[5], N[5];
        elementPositions5(p0.x, st, count, pc.patchCount, P, N);
        for (uint k = 0u; k < count; ++k) {
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
        float len = count == 5u
            ? distance(px[0], px[3]) + distance(px[3], px[1]) + distance(px[1], px[4]) + distance(px[4], px[2])
            : distance(px[0], px[1]) + distance(px[1], px[2]);
        if (behind == 0u) ends = vec4(px[0], px[2]) + pc.halfViewport.xyxy;
        if (behind == count) {
            r = 1u, size = 1u;
        } else if (behind != 0u || !(len < 1e9)) {
            r = cap, size = cap;
        } else {
            // maxError 0, flatness (the chord criterion): the middle sample's distance in pixels from the
            // chord of the ends, d, shrinks like d / n^2 over n segments; where the projected
            // edge bends (silhouettes, tight curves) enough segments keep each chord within
            // kChordPerEdgePixel * edgePixels of the curve, so the outline the rasterizer
            // samples is the surface's.
            float want = ceil(len / pc.edgePixels);
            if (pc.maxError > 0.0) {
                // Loosened only between smooth patches: per-pixel normals shade
                // only those (surface_fragment.glsl), irregular faces and creases keep theirs.
                bool smoothBoth = true;
                for (int k = 0; k < 2; ++k) {
                    uint e = k == 0 ? p1.x : p1.y;
                    if (e == 0xFFFFFFFFu) continue;
                    smoothBoth = smoothBoth && e < pc.patchCount && ((patches.p[e].levelBoundary >> 16) & 0xFu) == 0u;
                }
                want = max(want, errorSegments(P, N, smoothBoth));
            } else {
                vec2 chord = px[2] - px[0];
                float cl = length(chord);
                vec2 off = px[1] - 0.5 * (px[0] + px[2]);
                float d = cl > 1e-6 ? abs(chord.x * off.y - chord.y * off.x) / cl : length(off);
                want = max(want, ceil(sqrt(d / (kChordPerEdgePixel * pc.edgePixels))));
            }
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
                if (k == 0) // graded (adaptive_emit.comp's pieceST; the last segment twice an even one)
                    want = max(want, max(pc.maxError > 0.0 ? 2.0 * want : ceil(2.0 * len / pc.edgePixels),
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
