// Texture displacement with paper 000's seam fix (4.5): each drawn vertex moves along its limit
// normal by scale * (average sample - mid). The samples are taken at the UVs the vertex has in
// every face around it (corner: all faces; edge: both sides, interpolated; interior: its own
// face), in increasing face order, so every copy of a point on a UV seam computes the same bits.
// Without the seam fix each copy has only its own face's UV (and cracks open, as in the paper's
// Figure 4). Bilinear with wrap-around, done here rather than by a sampler so it is exact and a
// test can repeat it (render/texture_image.cpp, sampleBilinear).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Positions { vec4 p[]; } positions;
layout(std430, binding = 1) readonly buffer Normals { vec4 n[]; } normals;
layout(std430, binding = 2) readonly buffer SideRanges { uvec2 r[]; } sideRanges;
layout(std430, binding = 3) readonly buffer SideUVs { vec2 uv[]; } sideUVs;
layout(std430, binding = 4) readonly buffer Map { uint width; uint height; float v[]; } map;
layout(std430, binding = 5) writeonly buffer Displaced { vec4 p[]; } displaced;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) float scale;
    float mid;
} pc;

uint wrap(float i, uint n) {
    int k = int(i) % int(n);
    return uint(k < 0 ? k + int(n) : k);
}

float texel(uint x, uint y) { return map.v[y * map.width + x]; }

float sampleMap(vec2 uv) {
    precise float x = uv.x * float(map.width) - 0.5;
    precise float y = (1.0 - uv.y) * float(map.height) - 0.5;
    precise float fx0 = floor(x), fy0 = floor(y);
    precise float fx = x - fx0, fy = y - fy0;
    uint x0 = wrap(fx0, map.width), x1 = wrap(fx0 + 1.0, map.width);
    uint y0 = wrap(fy0, map.height), y1 = wrap(fy0 + 1.0, map.height);
    precise float top = texel(x0, y0) + fx * (texel(x1, y0) - texel(x0, y0));
    precise float bottom = texel(x0, y1) + fx * (texel(x1, y1) - texel(x0, y1));
    precise float value = top + fy * (bottom - top);
    return value;
}

void main() {
    uint i = limnInvocationIndex(pc.limnRowInvocations);
    if (i >= pc.limnCount) return;
    uvec2 r = sideRanges.r[i];
    precise float sum = 0.0;
    for (uint k = r.x; k < r.x + r.y; ++k) sum += sampleMap(sideUVs.uv[k]);
    precise float height = pc.scale * (sum / float(r.y) - pc.mid);
    displaced.p[i] = vec4(positions.p[i].xyz + height * normals.n[i].xyz, 1.0);
}
