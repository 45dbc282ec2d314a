// Normals of the view-adaptively tessellated displaced surface: the triangles change with the
// view, so instead of gathering them (displaced_normals.comp) each vertex differentiates the
// displaced surface S + n * scale * (h(uv) - mid) of its owner element at its own parameter, by
// one-sided differences of 1/1024 of the element in s and in t (h sampled in the owner's chart).
// Copies of a shared point name the same owner and parameter, so they get the same normal.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "surface_eval.glsl"
#include "adaptive_tess.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Patches { Patch p[]; } patches;
layout(std430, binding = 2) readonly buffer Irregulars { IrregularFace f[]; } irregulars;
layout(std430, binding = 3) readonly buffer Limits { vec4 v[]; } limits;
layout(std430, binding = 4) readonly buffer TessVertices { uvec4 v[]; } tessVertices;
layout(std430, binding = 5) readonly buffer Elements { AdaptiveElement e[]; } elements;
layout(std430, binding = 6) readonly buffer Map { uint width; uint height; float v[]; } map;
layout(std430, binding = 7) writeonly buffer Normals { vec4 n[]; } normals;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint patchCount;
    float scale;
    float mid;
} pc;

#include "surface_eval_impl.glsl"
#include "adaptive_sample.glsl"

vec3 displacedAt(uint e, int S, int T) {
    SurfaceSample p = evaluateElement(e, uint(S) | (uint(T) << 16), pc.patchCount);
    float s = float(S) / 32768.0, t = float(T) / 32768.0;
    AdaptiveElement el = elements.e[e];
    vec2 uv = mix(mix(el.uv[0], el.uv[1], s), mix(el.uv[3], el.uv[2], s), t);
    return p.position + p.normal * (pc.scale * (sampleMap(uv) - pc.mid));
}

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    uvec4 tv = tessVertices.v[i];
    int S = int(tv.y & 0xFFFFu), T = int(tv.y >> 16);
    const int h = 32; // 1/1024
    int ds = S + h <= 32768 ? h : -h, dt = T + h <= 32768 ? h : -h;
    vec3 p0 = displacedAt(tv.x, S, T);
    vec3 du = (displacedAt(tv.x, S + ds, T) - p0) * float(sign(ds));
    vec3 dv = (displacedAt(tv.x, S, T + dt) - p0) * float(sign(dt));
    vec3 n = cross(du, dv);
    float len = length(n);
    normals.n[i] = vec4(len > 0.0 ? n / len : vec3(0.0), 0.0);
}
