// The subdivision surface's vertex stage (paper 000, 4.3): each vertex of the watertight
// tessellation is evaluated here, from its owning patch's 16 control points (bicubic B-spline,
// eq. 1) or its irregular face's limit points. With DRAW_PULL_INDICES the draw is non-indexed
// and this stage reads the index buffer itself, so it knows its triangle (for --shade levels;
// gl_PrimitiveID would need the Geometry capability, which WebGPU does not have).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"
#include "surface_eval.glsl"

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Patches { Patch p[]; } patches;
layout(std430, binding = 2) readonly buffer Irregulars { IrregularFace f[]; } irregulars;
layout(std430, binding = 3) readonly buffer Limits { vec4 v[]; } limits;
layout(std430, binding = 4) readonly buffer TessVertices { uvec4 v[]; } tessVertices; // element, st, u, v
layout(std430, binding = 5) readonly buffer Triangles { uint i[]; } triangles;
layout(std430, binding = 6) readonly buffer TriangleLevels { uint l[]; } triangleLevels;

#include "surface_eval_impl.glsl"

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
    SurfaceSample s = evaluateTessVertex(vi, pc.patchCount);
    outWorld = s.position;
    outNormal = s.normal;
    outUV = uintBitsToFloat(tessVertices.v[vi].zw);
    outLevel = level;
    gl_Position = pc.viewProj * vec4(s.position, 1.0);
}
