// Shading: `lit` is a Lambert key light near the camera plus ambient, computed in linear light
// (the sRGB target gamma-encodes on write); `normal` and `uv` store the value itself.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_FRAGMENT_STAGE
#include "draw_common.glsl"

layout(location = 0) in vec3 inWorld;
layout(location = 1) flat in vec3 inNormal;
layout(location = 2) in vec2 inUV;
layout(location = 0) out vec4 outColor;

const vec3 kAlbedo = vec3(0.80);
const float kAmbient = 0.12;

void main() {
    if (backFaceKey(outColor)) return;
    vec3 toEye = pc.eye.xyz - inWorld;
    vec3 n = inNormal;
    if (pc.shade == SHADE_NORMAL) {
        outColor = vec4(srgbToLinear(n * 0.5 + 0.5), 1.0);
        return;
    }
    if (pc.shade == SHADE_UV) {
        outColor = vec4(srgbToLinear(vec3(clamp(inUV, 0.0, 1.0), 0.0)), 1.0);
        return;
    }
    // Two-sided: light the side that faces the camera (control meshes may be open).
    if (dot(n, toEye) < 0.0) n = -n;
    float diffuse = max(dot(n, pc.light.xyz), 0.0); // zero for degenerate faces (n = 0)
    outColor = vec4(kAlbedo * (kAmbient + (1.0 - kAmbient) * diffuse), 1.0);
}
