// One flat normal per face (Newell's method: exact for planar polygons, a robust average for
// non-planar ones), gathered over the face's corners in their stored order, so the result does
// not depend on scheduling. Degenerate faces get the zero vector.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer FaceOffsets { uint o[]; } faceOffsets;
layout(std430, binding = 2) readonly buffer FaceVertices { uint v[]; } faceVertices;
layout(std430, binding = 3) writeonly buffer FaceNormals { vec4 n[]; } faceNormals;
layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint firstVertex;
} pc;

void main() {
    uint f = limnInvocationIndex(pc.limnRowInvocations);
    if (f >= pc.limnCount) return;
    uint begin = faceOffsets.o[f], end = faceOffsets.o[f + 1];
    vec3 n = vec3(0.0);
    vec3 prev = vertices.p[pc.firstVertex + faceVertices.v[end - 1]].xyz;
    for (uint c = begin; c < end; ++c) {
        vec3 cur = vertices.p[pc.firstVertex + faceVertices.v[c]].xyz;
        n += vec3((prev.y - cur.y) * (prev.z + cur.z),
                  (prev.z - cur.z) * (prev.x + cur.x),
                  (prev.x - cur.x) * (prev.y + cur.y));
        prev = cur;
    }
    float len = length(n);
    faceNormals.n[f] = vec4(len > 0.0 ? n / len : vec3(0.0), 0.0);
}
