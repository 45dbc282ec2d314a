// View-adaptive tessellation, pass 1 of 5 (issue 11): per element, whether it lies wholly
// outside the view frustum. Conservative: a regular patch lies in the convex hull of its 16
// B-spline control points (paper 000, eq. 1), an irregular face (bilinear) in that of its four
// limit points; the element is culled only when all of them are outside one clip plane. Patches
// on a mesh boundary (whose phantom points are not among the control points) are never culled.
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
    uint patchCount;
    uint enabled; // 0: cull nothing
} pc;

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
        if (((pt.levelBoundary >> 8) & 0xFu) != 0u) all = 0u;
        for (int k = 0; k < 16 && all != 0u; ++k) all &= outside(vertices.p[pt.cv[k]].xyz);
    } else {
        IrregularFace q = irregulars.f[e - pc.patchCount];
        for (int k = 0; k < 4; ++k) all &= outside(limits.v[2u * q.corner[k]].xyz);
    }
    cull.c[e] = all != 0u ? 1u : 0u;
}
