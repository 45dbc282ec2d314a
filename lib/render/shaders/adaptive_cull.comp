// View-adaptive tessellation, pass 1 of 5 (issue 11): per element, whether it lies wholly
// outside the view frustum. Conservative: a regular patch lies in the convex hull of its 16
// B-spline control points (paper 000, eq. 1), an irregular face (bilinear) in that of its four
// limit points; the element is culled only when all of them are outside one clip plane. Patches
// on a mesh boundary (whose phantom points are not among the control points) are never culled.
//
// Facing away (only for a closed surface seen from outside its control points' bounding box, so
// that every back face is hidden behind a front face; the host decides, backFaces != 0, with the
// sign of the surface's orientation): the normal Du x Dv of a bicubic B-spline patch is a convex
// combination of the 144 cross products of its 12 u- and 12 v-differences of control points
// (the derivative of a B-spline is a B-spline of the differences), and the point is in the hull
// of the 16 control points; so if (P_k - eye) . (dU_a x dV_b) > 0 for every k, a, b, no point of
// the patch faces the eye. An irregular face (bilinear) the same with its 2 + 2 edge vectors.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "surface_eval.glsl"
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
    uint enabled;   // 0: cull nothing
} pc;

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
    if (pc.enabled == 0u) {
        all = 0u;
    } else if (e < pc.patchCount) {
        Patch pt = patches.p[e];
        // Boundary and single-crease patches are never culled (their basis is not the plain
        // B-spline one whose hull and derivative cone the tests below use).
        if (((pt.levelBoundary >> 8) & 0xF0Fu) != 0u) {
            all = 0u;
        } else {
            vec3 P[16];
            for (int k = 0; k < 16; ++k) {
                P[k] = vertices.p[pt.cv[k]].xyz;
                all &= outside(P[k]);
            }
            if (all == 0u && pc.eye.w != 0.0) {
                vec3 U[12], V[12];
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 3; ++i) {
                        U[3 * j + i] = P[4 * j + i + 1] - P[4 * j + i];
                        V[4 * i + j] = P[4 * (i + 1) + j] - P[4 * i + j];
                    }
                if (facesAway(P, 16u, U, 12u, V, 12u)) all = 64u;
            }
        }
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
    }
    cull.c[e] = all != 0u ? 1u : 0u;
}
