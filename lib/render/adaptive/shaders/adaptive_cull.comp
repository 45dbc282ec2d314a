// View-adaptive tessellation, pass 1 of 5: per element, whether its triangles can
// be left out of the draw. Three conservative tests, each of which leaves out only what could
// not have drawn a sample; a culled element is still emitted at its smallest rate for --mesh-out.
//
// Outside the view frustum: a regular patch lies in the convex hull of its 16 Bezier control
// points (converted from its B-spline ones, paper 000, eq. 1), an irregular face drawn bilinear
// (tables without its sub-patches) in that of its four limit points, a face on a basis
// (docs/irregular.md: per valence, or per boundary configuration) in that of its support points
// (every point of its surface is a limit of Catmull-Clark's smooth and boundary rules, whose
// weights are not negative, over them); the element
// is culled when all of them are outside one clip plane. Patches on a mesh boundary (whose phantom
// points are not among the control points), single-crease patches and the faces on quadtrees of
// sub-patches (their hulls would be those of their sub-patches) are never culled.
//
// Facing away (only for a closed surface seen from outside its control points' bounding box, so
// that every back face is hidden behind a front face; the host decides, eye.w != 0, with the
// sign of the surface's orientation): the normal Du x Dv of a bicubic Bezier patch is a convex
// combination of the 144 cross products of its 12 u- and 12 v-differences of control points
// (the derivative of a Bezier patch is a Bezier patch of the differences), and the point is in
// the hull of the 16 control points; so if (P_k - eye) . (dU_a x dV_b) > 0 for every k, a, b, no
// point of the patch faces the eye. An irregular face (bilinear) the same with its 2 + 2 edge
// vectors.
//
// Between samples (the host gives the sample positions; not with --wire-triangles): the
// projection of a point in the hull lies in the hull of the projected points (all in front of
// the eye), so if their pixel-space bounding box holds no sample position the element's
// triangles cover no sample and draw nothing (the box widened by 1/16 pixel: the rasterizer
// snaps to 1/256 and the two evaluations round differently). Deep isolation around
// extraordinary vertices makes many such sub-pixel elements (the paper's sphere at
// depth 6 has 2,240 elements for about 6,200 covered pixels), each at least two triangles.
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
layout(std430, binding = 4) writeonly buffer Cull { uint c[]; } cull;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) mat4 viewProj;
    vec4 eye;       // xyz; w: 0 no facing test, +1 / -1 the orientation of the surface's normals
    uint patchCount;
    uint enabled;   // bit 0: cull at all; bits 8-15: how many sample positions (0: no test)
    vec2 viewport;  // drawn image size in pixels
    uvec2 samples;  // the sample positions within a pixel, 1/256 pixel units, x | y << 8 in 16 bits each
} pc;

vec2 samplePosition(uint s) { return adaptiveSamplePosition(pc.samples, s); }

// The patch's bicubic Bezier control points in place of its B-spline ones (the same surface;
// uniform cubic B-spline to Bezier along i, then along j): their hull hugs the patch, where the
// B-spline hull reaches about a patch width beyond it on every side, so every test below is
// tighter (the derivative argument holds for the Bezier differences the same way).
void bezierPoints(inout vec3 P[16]) {
    for (int pass = 0; pass < 2; ++pass)
        for (int r = 0; r < 4; ++r) {
            int s0 = pass == 0 ? 4 * r : r, st = pass == 0 ? 1 : 4;
            vec3 a = P[s0], b = P[s0 + st], c = P[s0 + 2 * st], d = P[s0 + 3 * st];
            P[s0] = (a + 4.0 * b + c) / 6.0;
            P[s0 + st] = (2.0 * b + c) / 3.0;
            P[s0 + 2 * st] = (b + 2.0 * c) / 3.0;
            P[s0 + 3 * st] = (b + 4.0 * c + d) / 6.0;
        }
}

// Grows the pixel-space box [lo, hi] by the projection of p; false where p is not in front of the
// eye (then no box bounds the projection).
bool growProjectedBox(vec3 p, inout vec2 lo, inout vec2 hi) {
    vec4 c = pc.viewProj * vec4(p, 1.0);
    if (!(c.w > 1e-6)) return false;
    vec2 px = (c.xy / c.w * 0.5 + 0.5) * pc.viewport;
    lo = min(lo, px), hi = max(hi, px);
    return true;
}

// Whether the pixel-space box [lo, hi] of projected points holds none of the sample positions
// (pixel + offset, for each of the pattern's offsets).
bool boxBetweenSamples(vec2 lo, vec2 hi) {
    uint sampleCount = min((pc.enabled >> 8) & 0xFFu, 4u);
    if (sampleCount == 0u) return false;
    if (!(hi.x - lo.x < 1e6 && hi.y - lo.y < 1e6)) return false; // huge or not finite
    const float slack = 1.0 / 16.0;
    for (uint s = 0u; s < sampleCount; ++s) {
        vec2 first = ceil(lo - slack - samplePosition(s)), last = floor(hi + slack - samplePosition(s));
        if (first.x <= last.x && first.y <= last.y) return false;
    }
    return true;
}

bool betweenSamples(vec3 P[16], uint np) {
    if (((pc.enabled >> 8) & 0xFFu) == 0u) return false;
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    for (uint k = 0u; k < np; ++k)
        if (!growProjectedBox(P[k], lo, hi)) return false;
    return boxBetweenSamples(lo, hi);
}

// Whether sign * (P_k - eye) . (U_a x V_b) > 0 for all given points and vectors.
bool facesAway(vec3 P[16], uint np, vec3 U[12], uint nu, vec3 V[12], uint nv) {
    for (uint a = 0u; a < nu; ++a)
        for (uint b = 0u; b < nv; ++b) {
            vec3 C = cross(U[a], V[b]) * pc.eye.w;
            for (uint k = 0u; k < np; ++k)
                if (!(dot(P[k] - pc.eye.xyz, C) > 0.0)) return false;
        }
    return true;
}

// Bits of the clip planes that `p` is outside of: x < -w, x > w, y < -w, y > w, z < 0, z > w.
uint outside(vec3 p) {
    vec4 c = pc.viewProj * vec4(p, 1.0);
    uint m = 0u;
    if (c.x < -c.w) m |= 1u;
    if (c.x > c.w) m |= 2u;
    if (c.y < -c.w) m |= 4u;
    if (c.y > c.w) m |= 8u;
    if (c.z < 0.0) m |= 16u;
    if (c.z > c.w) m |= 32u;
    return m;
}

void main() {
    uint e = limnInvocationIndex(pc.limnRowInvocations);
    if (e >= pc.limnCount) return;
    uint all = 63u;
    if ((pc.enabled & 1u) == 0u) {
        all = 0u;
    } else if (e < pc.patchCount) {
        Patch pt = patches.p[e];
        // Boundary and single-crease patches are never culled (their basis is not the plain
        // B-spline one whose hull and derivative cone the tests below use).
        if (((pt.levelBoundary >> 8) & 0xF0Fu) != 0u) {
            all = 0u;
        } else {
            vec3 P[16];
            for (int k = 0; k < 16; ++k) P[k] = vertices.p[pt.cv[k]].xyz;
            bezierPoints(P);
            for (int k = 0; k < 16; ++k) all &= outside(P[k]);
            if (all == 0u && pc.eye.w != 0.0) {
                vec3 U[12], V[12];
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 3; ++i) {
                        U[3 * j + i] = P[4 * j + i + 1] - P[4 * j + i];
                        V[4 * i + j] = P[4 * (i + 1) + j] - P[4 * i + j];
                    }
                if (facesAway(P, 16u, U, 12u, V, 12u)) all = 64u;
            }
            if (all == 0u && betweenSamples(P, 16u)) all = 128u;
        }
    } else if ((patches.p[e].cv[0] & IRREGULAR_KIND) == IRREGULAR_BASIS && patches.p[e].cv[0] != IRREGULAR_NONE &&
               patches.p[e].cv[1] == patches.p[e].cv[0] && patches.p[e].cv[2] == patches.p[e].cv[0] &&
               patches.p[e].cv[3] == patches.p[e].cv[0]) {
        // A face on a basis: the hull of its support (the header's cv[0] is the support size
        // M, its indices follow it, surface_eval_impl.glsl basisPatchPoint). On a boundary too:
        // the boundary rules (edge midpoints, (1, 6, 1) / 8, corners kept) are convex, and the
        // stored weights' negative phantom terms only re-express those points' B-spline. The facing test would need its sub-patches' derivative cones: not made.
        // Only a root of four equal basis codes is such a face: a basis code in one quadrant
        // alone is a smooth face below level N (a decayed crease), whose hull bounds that
        // quadrant, not the face.
        uint h = patches.p[e].cv[0] & ~IRREGULAR_KIND, M = patches.p[h].cv[0];
        vec2 lo = vec2(1e30), hi = vec2(-1e30);
        bool boxed = ((pc.enabled >> 8) & 0xFFu) != 0u;
        for (uint i = 0u; i < M; ++i) {
            vec3 x = vertices.p[patches.p[h + 1u + i / 16u].cv[i % 16u]].xyz;
            all &= outside(x);
            if (boxed) boxed = growProjectedBox(x, lo, hi);
        }
        if (all == 0u && boxed && boxBetweenSamples(lo, hi)) all = 128u;
    } else if (patches.p[e].cv[0] != IRREGULAR_NONE) {
        // An irregular face on its sub-patches (docs/irregular.md) is not in the hull of its
        // corners: never culled (there are few; their hulls would be those of their sub-patches).
        all = 0u;
    } else {
        IrregularFace q = irregulars.f[e - pc.patchCount];
        vec3 P[16], U[12], V[12];
        for (int k = 0; k < 4; ++k) {
            P[k] = limits.v[2u * q.corner[k]].xyz;
            all &= outside(P[k]);
        }
        if (all == 0u && pc.eye.w != 0.0) {
            U[0] = P[1] - P[0], U[1] = P[2] - P[3];
            V[0] = P[3] - P[0], V[1] = P[2] - P[1];
            if (facesAway(P, 4u, U, 2u, V, 2u)) all = 64u;
        }
        if (all == 0u && betweenSamples(P, 4u)) all = 128u;
    }
    cull.c[e] = all != 0u ? 1u : 0u;
}
