// View-adaptive tessellation, pass 3 of 5 (issue 11): per element, its interior rates mu along s
// and mv along t (the larger projected size of the two sides running that way, see
// adaptive_rates.comp; 1 when culled, at most tess; at least 2 for the grid below) and how many
// vertices and triangles it will emit (adaptive_emit.comp): B boundary points (every side's
// segments) plus the (mu-1)(mv-1) interior grid points; 2(mu-2)(mv-2) grid triangles plus
// B + 2(mu-2) + 2(mv-2) in the four zipper strips (mu = mv = 2: one centre point fanned to the
// boundary). An element with one segment per side and both rates <= 2 (B = 4: the common case
// of a small deep patch) is two triangles and no centre. Separate rates per direction matter on
// patches seen at a grazing angle and on long thin ones (a sphere's polar rings): one square
// rate would cut the short direction as finely as the long one.
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
    uint B = 0u, most[2] = uint[2](1u, 1u); // along s (sides 0, 2), along t (sides 1, 3)
    for (int k = 0; k < 4; ++k) {
        uint side = 0u, size = 0u;
        for (uint p = 0u; p < el.sideCount[k]; ++p) {
            uint r = rates.r[sidePieces.v[el.sideFirst[k] + p].x];
            side += r & 0xFFFFu;
            size += r >> 16;
        }
        B += side;
        most[k & 1] = max(most[k & 1], size);
    }
    bool culled = cull.c[e] != 0u;
    uint cap = max(pc.tess, 1u);
    uint mu = culled ? 2u : clamp(most[0], 2u, max(cap, 2u));
    uint mv = culled ? 2u : clamp(most[1], 2u, max(cap, 2u));
    bool twoTriangles = B == 4u && mu == 2u && mv == 2u;
    uint V = B + (twoTriangles ? 0u : (mu - 1u) * (mv - 1u));
    uint T = twoTriangles ? 2u : 2u * (mu - 2u) * (mv - 2u) + B + 2u * (mu - 2u) + 2u * (mv - 2u);
    info.v[e] = uvec4(adaptivePackRates(mu, mv) | (culled ? ADAPTIVE_CULLED : 0u), V, T, 0u);
}
