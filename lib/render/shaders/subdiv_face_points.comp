// Face points of one level (paper 000, 3.3 step 1 and 4.2): the average of the face's vertices.
// One invocation per face point; rows of the concatenated face-point table (TBLS).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Vertices { vec4 p[]; } vertices; // all levels
layout(std430, binding = 1) readonly buffer Starts { uint s[]; } starts;
layout(std430, binding = 2) readonly buffer Indices { uint i[]; } indices;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint firstOut; // first vertex of this level's face points
    uint firstRow;                     // this level's first row in `starts`
} pc;

void main() {
    uint r = limnInvocationIndex(pc.limnRowInvocations);
    if (r >= pc.limnCount) return;
    uint b = starts.s[pc.firstRow + r], e = starts.s[pc.firstRow + r + 1];
    vec3 sum = vec3(0.0);
    for (uint k = b; k < e; ++k) sum += vertices.p[indices.i[k]].xyz;
    vertices.p[pc.firstOut + r] = vec4(sum / float(e - b), 1.0);
}
