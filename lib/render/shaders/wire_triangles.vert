// --wire in view-adaptive mode: the edges of the triangles the frame drew, so the
// rates chosen from the view can be seen. Non-indexed: vertex 6 t + 2 e + end is end `end` of
// edge e of triangle t, pulled from the triangle index buffer the adaptive passes wrote (an
// interior edge is drawn once per triangle on it; both draws cover the same pixels). The
// positions are those the draw read (evaluated, or displaced), pulled towards the eye as in
// wire.vert so the lines win the depth test.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Triangles { uint i[]; } triangles;

void main() {
    uint t = uint(gl_VertexIndex) / 6u, k = uint(gl_VertexIndex) % 6u;
    uint corner = (k / 2u + k % 2u) % 3u; // edges (0,1), (1,2), (2,0)
    vec3 p = vertices.p[triangles.i[3u * t + corner]].xyz;
    p = mix(p, pc.eye.xyz, pc.wirePull);
    gl_Position = pc.viewProj * vec4(p, 1.0);
}
