// View-adaptive tessellation, pass 3 of 5 (issue 11): per element, its interior rate m (the
// largest of its sides' projected sizes, see adaptive_rates.comp; 1 when culled, at most tess) and how many vertices and
// triangles it will emit (adaptive_emit.comp): B boundary points (every side's segments) plus a
// centre (m <= 2) or the (m-1)^2 interior grid points; B fan triangles, or 2(m-2)^2 grid
// triangles plus B + 4(m-2) in the four zipper strips. An element with one segment per side and
// m <= 2 (B = 4: the common case of a small deep patch) is two triangles and no centre.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "adaptive_tess.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Elements { AdaptiveElement e[]; } elements;
layout(std430, binding = 1) readonly buffer SidePieces { uvec4 v[]; } sidePieces;
layout(std430, binding = 2) readonly buffer Rates { uint r[]; } rates;
layout(std430, binding = 3) readonly buffer Cull { uint c[]; } cull;
layout(std430, binding = 4) writeonly buffer Info { uvec4 v[]; } info; // m | culled, V, T, 0

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint tess;
} pc;

void main() {
    uint e = limnInvocationIndex(pc.limnRowInvocations);
    if (e >= pc.limnCount) return;
    AdaptiveElement el = elements.e[e];
    uint B = 0u, most = 1u;
    for (int k = 0; k < 4; ++k) {
        uint side = 0u, size = 0u;
        for (uint p = 0u; p < el.sideCount[k]; ++p) {
            uint r = rates.r[sidePieces.v[el.sideFirst[k] + p].x];
            side += r & 0xFFFFu;
            size += r >> 16;
        }
        B += side;
        most = max(most, size);
    }
    bool culled = cull.c[e] != 0u;
    uint m = culled ? 1u : clamp(most, 1u, max(pc.tess, 1u));
    uint V = B + (m <= 2u ? (B == 4u ? 0u : 1u) : (m - 1u) * (m - 1u));
    uint T = m <= 2u ? (B == 4u ? 2u : B) : 2u * (m - 2u) * (m - 2u) + B + 4u * (m - 2u);
    info.v[e] = uvec4(m | (culled ? ADAPTIVE_CULLED : 0u), V, T, 0u);
}
