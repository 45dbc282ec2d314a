// The subdivision surface's vertex stage when the tessellation vertices were evaluated once by
// the compute pass (surface_eval.comp, --eval compute): it only fetches them. Same outputs as
// surface.vert.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"

layout(std430, binding = 0) readonly buffer Positions { vec4 p[]; } positions;
layout(std430, binding = 1) readonly buffer Normals { vec4 n[]; } normals;
layout(std430, binding = 2) readonly buffer TessVertices { uvec4 v[]; } tessVertices;
layout(std430, binding = 3) readonly buffer Triangles { uint i[]; } triangles;
layout(std430, binding = 4) readonly buffer TriangleLevels { uint l[]; } triangleLevels;

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUV;
layout(location = 3) flat out uint outLevel;

void main() {
    uint vi = uint(gl_VertexIndex);
    uint level = 0u;
    if ((pc.flags & DRAW_PULL_INDICES) != 0u) {
        level = triangleLevels.l[vi / 3u];
        vi = triangles.i[vi];
    }
    vec3 p = positions.p[vi].xyz;
    outWorld = p;
    outNormal = normals.n[vi].xyz;
    outUV = uintBitsToFloat(tessVertices.v[vi].zw);
    outLevel = level;
    gl_Position = pc.viewProj * vec4(p, 1.0);
}
