// Normals of the displaced surface (issue: shade with the displaced surface's normal): for each
// drawn vertex, the normalized sum of the (area-weighted) normals of the triangles around its
// point, gathered in a fixed order (no scatter, no float atomics: deterministic). All copies of a
// point on a UV seam share one triangle list, so they get the same normal.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Displaced { vec4 p[]; } displaced;
layout(std430, binding = 1) readonly buffer Triangles { uint i[]; } triangles;
layout(std430, binding = 2) readonly buffer Ranges { uvec2 r[]; } ranges; // per vertex
layout(std430, binding = 3) readonly buffer Incident { uint t[]; } incident;
layout(std430, binding = 4) writeonly buffer Normals { vec4 n[]; } normals;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
} pc;

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    uvec2 r = ranges.r[i];
    vec3 sum = vec3(0.0);
    for (uint k = r.x; k < r.x + r.y; ++k) {
        uint t = incident.t[k];
        vec3 a = displaced.p[triangles.i[3 * t]].xyz;
        vec3 b = displaced.p[triangles.i[3 * t + 1]].xyz;
        vec3 c = displaced.p[triangles.i[3 * t + 2]].xyz;
        sum += cross(b - a, c - a);
    }
    float len = length(sum);
    normals.n[i] = vec4(len > 0.0 ? sum / len : vec3(0.0), 0.0);
}
