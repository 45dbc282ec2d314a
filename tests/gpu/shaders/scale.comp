// out[i] = in[i] * scale + offset for i < count: a gather pass with the dispatch conventions.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { uint values[]; } src;
layout(std430, binding = 1) writeonly buffer Out { uint values[]; } dst;
layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint scale;
    uint offset;
} pc;

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    dst.values[i] = src.values[i] * pc.scale + pc.offset;
}
