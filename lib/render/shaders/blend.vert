// The blending surface's vertex stage, the paper's vertex program (paper 001, 4.2): each grid
// vertex is mapped into the charts of its face's four corners, the local surfaces and weights are
// evaluated and blended (blend_eval.glsl). A vertex on a shared edge or corner evaluates its
// owner's (face, u, v), so every face that draws it computes the same bits (blend_draw.h).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"
#include "blend_eval.glsl"
#include "blend_draw.glsl"
#include "blend_vertex_out.glsl"
#include "blend_eval_impl.glsl"

void main() {
    uint d = uint(gl_VertexIndex);
    uvec4 dv = drawVertices.v[d];
    float u = float(dv.z & 0xFFFFu) / float(drawData.grid), v = float(dv.z >> 16) / float(drawData.grid);
    BlendSample s = evaluateBlend(dv.y, u, v, drawData.weights);
    blendVertexOut(d, dv.w, s.position, s.normal, drawData.hasUVs != 0u);
}
