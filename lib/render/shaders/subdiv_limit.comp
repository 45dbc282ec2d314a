// Limit positions and normals of the irregular faces' corners (paper 000, 4.4, with the
// corrected masks of math.md C): position and two tangents as weighted gathers over the last
// level; normal = normalize(t1 x t2).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Starts { uint s[]; } starts;   // 3 tables, rows of each
layout(std430, binding = 2) readonly buffer Indices { uint i[]; } indices;
layout(std430, binding = 3) readonly buffer Weights { float w[]; } weights;
layout(std430, binding = 4) writeonly buffer Limits { vec4 v[]; } limits; // position, normal pairs

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint rowsPerTable; // rows of each table; starts holds 3 tables back to back
    uint firstRow;     // the chunk's first limit point (tables over 128 MiB come in chunks)
} pc;

// affine: the row's weights sum to 1 (a position), else to 0 (a tangent). Rows of more than 64
// entries are summed relative to their first point, as in subdiv_stencils.comp.
vec3 gather(uint row, bool affine) {
    uint b = starts.s[row], e = starts.s[row + 1];
    vec3 sum = vec3(0.0);
    if (e - b > 64u) {
        vec3 origin = vertices.p[indices.i[b]].xyz;
        for (uint k = b; k < e; ++k) sum += weights.w[k] * (vertices.p[indices.i[k]].xyz - origin);
        return affine ? sum + origin : sum;
    }
    for (uint k = b; k < e; ++k) sum += weights.w[k] * vertices.p[indices.i[k]].xyz;
    return sum;
}

void main() {
    uint r = limnInvocationIndex(pc.limnRowInvocations);
    if (r >= pc.limnCount) return;
    uint stride = pc.rowsPerTable + 1;
    vec3 position = gather(r, true);
    vec3 t1 = gather(stride + r, false), t2 = gather(2 * stride + r, false);
    vec3 n = cross(t1, t2);
    float len = length(n);
    uint o = pc.firstRow + r;
    limits.v[2 * o] = vec4(position, 1.0);
    limits.v[2 * o + 1] = vec4(len > 0.0 ? n / len : vec3(0.0), len > 0.0 ? 1.0 : 0.0);
}
