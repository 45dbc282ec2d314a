// Control-mesh edges as a line list; the index buffer holds vertex indices. Each vertex is moved
// a little towards the eye along its view ray (same pixel, smaller depth) so the edges win the
// depth test against the faces they bound. Lines get no depth bias in Vulkan or WebGPU.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;

void main() {
    vec3 p = vertices.p[gl_VertexIndex].xyz;
    p = mix(p, pc.eye.xyz, pc.wirePull);
    gl_Position = pc.viewProj * vec4(p, 1.0);
}
