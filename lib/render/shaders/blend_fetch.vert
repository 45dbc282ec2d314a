// The blending surface's vertex stage when blend_eval.comp evaluated every surface point once
// (--eval compute): it only fetches its point. Same outputs as blend.vert.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"
#include "blend_eval.glsl"
#include "blend_draw.glsl"
#include "blend_vertex_out.glsl"

void main() {
    uint d = uint(gl_VertexIndex);
    uvec4 dv = drawVertices.v[d];
    blendVertexOut(d, dv.w, positions.p[dv.x].xyz, normals.n[dv.x].xyz, drawData.hasUVs != 0u);
}
