// Control-mesh triangles, pulled from storage buffers: the index buffer holds fan triangles over
// face corners; each corner names its vertex, its face (for the flat normal) and its UV.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer FaceNormals { vec4 n[]; } faceNormals;
layout(std430, binding = 2) readonly buffer Corners { uvec4 c[]; } corners; // vertex, face, uv, ptex
layout(std430, binding = 3) readonly buffer UVs { vec2 uv[]; } uvs;

layout(location = 0) out vec3 outWorld;
layout(location = 1) flat out vec3 outNormal;
layout(location = 2) out vec2 outUV;

void main() {
    uvec4 corner = corners.c[gl_VertexIndex];
    vec3 p = vertices.p[corner.x].xyz;
    outWorld = p;
    outNormal = faceNormals.n[corner.y].xyz;
    outUV = uvs.uv[corner.z];
    gl_Position = pc.viewProj * vec4(p, 1.0);
}
