// View-adaptive tessellation with displacement (paper 000, 4.5): each emitted vertex
// moves along its limit normal by scale * (average sample - mid). With the seam fix the samples
// are those of lib/render/subdivision_draw.cpp's sideUVsOf, taken from the seam record of the
// vertex's *owner* element (corner: every face around it; edge: both sides' UVs interpolated
// along the edge; interior: its own face), so the copies of a shared point that neighbouring
// elements emit use the same inputs in the same order and stay bit-identical. Without it each
// copy samples its own element's chart (and cracks open at UV seams, as in the paper's Fig. 4).
// With smooth UVs the records hold the smooth UVs of the corners (edges interpolate
// them linearly per side, as the paper's auxiliary UVs do) and interior points sample the smooth
// UV the emit pass evaluated.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Positions { vec4 p[]; } positions;
layout(std430, binding = 1) readonly buffer Normals { vec4 n[]; } normals;
layout(std430, binding = 2) readonly buffer TessVertices { uvec4 v[]; } tessVertices;
struct ElementSeams { // mirrors limn::ElementSeams
    vec2 own[4];
    uvec4 cornerFirst, cornerCount, edgeFirst, edgeSides;
};
layout(std430, binding = 3) readonly buffer Seams { ElementSeams e[]; } seams;
layout(std430, binding = 4) readonly buffer SeamUVs { vec2 uv[]; } seamUVs;
layout(std430, binding = 5) readonly buffer Map { uint width; uint height; float v[]; } map;
layout(std430, binding = 6) writeonly buffer Displaced { vec4 p[]; } displaced;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) float scale;
    float mid;
    uint seamFix;
    uint smoothUV; // records of smooth UVs; inside an element its emitted (smooth) UV
} pc;

#include "adaptive_sample.glsl"

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    uvec4 tv = tessVertices.v[i];
    precise float sum = 0.0;
    float count = 1.0;
    if (pc.seamFix == 0u) {
        sum = sampleMap(uintBitsToFloat(tv.zw));
    } else {
        ElementSeams es = seams.e[tv.x];
        uint S = tv.y & 0xFFFFu, T = tv.y >> 16;
        bool s0 = S == 0u, s1 = S == 32768u, t0 = T == 0u, t1 = T == 32768u;
        float s = float(S) / 32768.0, t = float(T) / 32768.0;
        if ((s0 || s1) && (t0 || t1)) {
            uint k = s0 ? (t0 ? 0u : 3u) : (t0 ? 1u : 2u);
            for (uint j = 0u; j < es.cornerCount[k]; ++j) sum += sampleMap(seamUVs.uv[es.cornerFirst[k] + j]);
            count = float(es.cornerCount[k]);
        } else if (t0 || s1 || t1 || s0) {
            uint e = t0 ? 0u : s1 ? 1u : t1 ? 2u : 3u;
            float x = t0 ? s : s1 ? t : t1 ? 1.0 - s : 1.0 - t;
            for (uint j = 0u; j < es.edgeSides[e]; ++j) {
                vec2 a = seamUVs.uv[es.edgeFirst[e] + 2u * j], b = seamUVs.uv[es.edgeFirst[e] + 2u * j + 1u];
                sum += sampleMap(a + x * (b - a));
            }
            count = float(es.edgeSides[e]);
        } else if (pc.smoothUV != 0u) {
            sum = sampleMap(uintBitsToFloat(tv.zw)); // an interior point has one copy, in its owner's chart
        } else {
            vec2 uv = (1.0 - s) * (1.0 - t) * es.own[0] + s * (1.0 - t) * es.own[1] + s * t * es.own[2] +
                      (1.0 - s) * t * es.own[3];
            sum = sampleMap(uv);
        }
    }
    precise float height = pc.scale * (sum / max(count, 1.0) - pc.mid);
    displaced.p[i] = vec4(positions.p[i].xyz + height * normals.n[i].xyz, 1.0);
}
