// Evaluates every surface point of the blending surface's tessellation once (blend_draw.h: each
// point by its owner face), into buffers: what --eval compute draws, --wire draws its lines
// through and --mesh-out writes. The same evaluation as blend.vert (blend_eval.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "blend_eval.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer BlendVertices { BlendVertex v[]; } blendVertices;
layout(std430, binding = 1) readonly buffer BlendFaces { BlendFace f[]; } blendFaces;
layout(std430, binding = 2) readonly buffer Points { uvec2 p[]; } points; // face, i | j << 16
layout(std430, binding = 3) writeonly buffer Positions { vec4 p[]; } positions;
layout(std430, binding = 4) writeonly buffer Normals { vec4 n[]; } normals;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint grid; // K: (u, v) = (i, j) / K
    uint weights;                  // BLEND_WEIGHTS_*
} pc;

#include "blend_eval_impl.glsl"

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    uvec2 point = points.p[i];
    float u = float(point.y & 0xFFFFu) / float(pc.grid), v = float(point.y >> 16) / float(pc.grid);
    BlendSample s = evaluateBlend(point.x, u, v, pc.weights);
    positions.p[i] = vec4(s.position, 1.0);
    normals.n[i] = vec4(s.normal, 0.0);
}
