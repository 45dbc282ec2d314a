// Edge points and vertex points of one level (paper 000, 3.3 steps 2-3 and 4.2), as weighted
// gathers with OpenSubdiv's masks (creases included): V[out] = sum w_k V[src_k]. Sources are the
// previous level and this level's face points, written by the previous pass. Gather, never
// scatter: every output is written by one invocation in a fixed order (deterministic bits).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Starts { uint s[]; } starts;
layout(std430, binding = 2) readonly buffer Indices { uint i[]; } indices;
layout(std430, binding = 3) readonly buffer Weights { float w[]; } weights;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint firstOut;
    uint firstRow;
} pc;

void main() {
    uint r = limnInvocationIndex(pc.limnRowInvocations);
    if (r >= pc.limnCount) return;
    uint b = starts.s[pc.firstRow + r], e = starts.s[pc.firstRow + r + 1];
    vec3 sum = vec3(0.0);
    if (e - b > 64u) {
        // A vertex of more than 31 faces: hundreds of small terms added one by one to a sum near
        // the point itself round the same way each time in float (catmark_pole360's valence-360
        // vertex drifted 2e-5 a level). A row's weights sum to 1, so it is its first point plus
        // the weighted differences from it, whose terms and sum are the ring's size. Shorter rows
        // keep their sums (same bits).
        vec3 origin = vertices.p[indices.i[b]].xyz;
        for (uint k = b; k < e; ++k) sum += weights.w[k] * (vertices.p[indices.i[k]].xyz - origin);
        sum += origin;
    } else {
        for (uint k = b; k < e; ++k) sum += weights.w[k] * vertices.p[indices.i[k]].xyz;
    }
    vertices.p[pc.firstOut + r] = vec4(sum, 1.0);
}
