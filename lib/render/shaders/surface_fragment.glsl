// Shading of the subdivision surface: smooth limit normals; `levels` colours patches by the level
// they were found at like paper 000's Figure 1 (grey, pink, yellow, green for levels 0-3, then
// more), irregular faces drawn at their limit points in blue.
// The body of surface.frag and surface_per_sample.frag.
#define LIMN_FRAGMENT_STAGE
#include "draw_common.glsl"

layout(location = 0) LIMN_SMOOTH_IN vec3 inWorld;
layout(location = 1) LIMN_SMOOTH_IN vec3 inNormal;
layout(location = 2) LIMN_SMOOTH_IN vec2 inUV;
layout(location = 3) flat in uint inLevel;
layout(location = 0) out vec4 outColor;

// The colour texture (--texture): sRGB RGBA8 texels packed in uints, rows top to bottom (image row
// = (1 - v) * height), filtered bilinearly in linear light with wrap-around.
layout(std430, binding = 7) readonly buffer Texture { uint width; uint height; uint rgba[]; } tex;

vec3 texel(uint x, uint y) {
    uint c = tex.rgba[y * tex.width + x];
    return srgbToLinear(vec3(c & 255u, (c >> 8) & 255u, (c >> 16) & 255u) / 255.0);
}

uint wrap(float i, uint n) {
    int k = int(i) % int(n);
    return uint(k < 0 ? k + int(n) : k);
}

vec3 sampleTexture(vec2 uv) {
    float x = uv.x * float(tex.width) - 0.5, y = (1.0 - uv.y) * float(tex.height) - 0.5;
    float x0 = floor(x), y0 = floor(y);
    float fx = x - x0, fy = y - y0;
    uint ix0 = wrap(x0, tex.width), ix1 = wrap(x0 + 1.0, tex.width);
    uint iy0 = wrap(y0, tex.height), iy1 = wrap(y0 + 1.0, tex.height);
    vec3 top = mix(texel(ix0, iy0), texel(ix1, iy0), fx);
    vec3 bottom = mix(texel(ix0, iy1), texel(ix1, iy1), fx);
    return mix(top, bottom, fy);
}

vec3 levelColour(uint level) {
    if (level == 255u) return vec3(0.25, 0.45, 0.95); // irregular faces
    const vec3 palette[8] = vec3[8](vec3(0.72, 0.72, 0.72), vec3(0.95, 0.55, 0.70),
                                    vec3(0.95, 0.85, 0.35), vec3(0.45, 0.85, 0.45),
                                    vec3(0.40, 0.85, 0.85), vec3(0.95, 0.60, 0.30),
                                    vec3(0.70, 0.50, 0.90), vec3(0.55, 0.40, 0.30));
    return palette[min(level, 7u)];
}

void main() {
    if (backFaceKey(outColor)) return;
    vec3 n = normalize(inNormal);
    if (pc.shade == SHADE_NORMAL) {
        outColor = vec4(srgbToLinear(n * 0.5 + 0.5), 1.0);
        return;
    }
    if (pc.shade == SHADE_UV) {
        outColor = vec4(srgbToLinear(vec3(clamp(inUV, 0.0, 1.0), 0.0)), 1.0);
        return;
    }
    if (pc.shade == SHADE_LEVELS) {
        outColor = vec4(levelsLight(srgbToLinear(levelColour(inLevel)), n, inWorld), 1.0);
        return;
    }
    vec3 albedo = pc.shade == SHADE_TEXTURE ? sampleTexture(inUV) * baseColour() : baseColour();
    outColor = vec4(lightRig(albedo, n, inWorld), 1.0);
}
