// out[i] = i with one invocation per workgroup, so a modest count needs more than 65535
// workgroups and exercises the 2D dispatch grid.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Out { uint values[]; } dst;
layout(push_constant) uniform Push { LIMN_DISPATCH_HEADER } pc;

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    dst.values[i] = i;
}
