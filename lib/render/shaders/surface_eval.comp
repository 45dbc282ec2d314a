// The same evaluation as surface.vert, for every tessellation vertex once, into buffers: what
// --mesh-out writes and what --wire draws its lines through.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "surface_eval.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Patches { Patch p[]; } patches;
layout(std430, binding = 2) readonly buffer Irregulars { IrregularFace f[]; } irregulars;
layout(std430, binding = 3) readonly buffer Limits { vec4 v[]; } limits;
layout(std430, binding = 4) readonly buffer TessVertices { uvec4 v[]; } tessVertices;
layout(std430, binding = 5) writeonly buffer Positions { vec4 p[]; } positions;
layout(std430, binding = 6) writeonly buffer Normals { vec4 n[]; } normals;
layout(std430, binding = 7) writeonly buffer Info { uvec4 i[]; } info; // ptex, u, v bits, level

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint patchCount;
} pc;

#include "surface_eval_impl.glsl"

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    SurfaceSample s = evaluateTessVertex(i, pc.patchCount);
    positions.p[i] = vec4(s.position, 1.0);
    normals.n[i] = vec4(s.normal, 0.0);
    info.i[i] = uvec4(s.ptex, floatBitsToUint(s.uv.x), floatBitsToUint(s.uv.y), s.level);
}
