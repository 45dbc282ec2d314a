// vertices[firstVertex + i] = controlPoints[i]: level 0 of the vertex buffer. The subdivision
// passes append levels 1..N after it, each a gather over the level before (paper 000, 4.2).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer ControlPoints { vec4 p[]; } controlPoints;
layout(std430, binding = 1) writeonly buffer Vertices { vec4 p[]; } vertices;
layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint firstVertex;
} pc;

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    vertices.p[pc.firstVertex + i] = controlPoints.p[i];
}
