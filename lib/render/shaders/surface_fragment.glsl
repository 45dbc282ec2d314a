// Shading of the subdivision surface: smooth limit normals; `levels` colours patches by the level
// they were found at like paper 000's Figure 1 (grey, pink, yellow, green for levels 0-3, then
// more), irregular faces drawn at their limit points in blue.
// The body of surface.frag and surface_per_sample.frag.
#define LIMN_FRAGMENT_STAGE
#include "draw_common.glsl"

layout(location = 0) LIMN_SMOOTH_IN vec3 inWorld;
layout(location = 1) LIMN_SMOOTH_IN vec3 inNormal;
layout(location = 2) LIMN_SMOOTH_IN vec2 inUV;
#ifdef LIMN_PIXEL_NORMALS
// Lit only, so the level is never read; without its input the fragment stage's inter-stage
// variables are the three above, the net's 12 and gl_FrontFacing, which WebGPU counts too:
// 16, its maxInterStageShaderVariables' default.
const uint inLevel = 0u;
#else
layout(location = 3) flat in uint inLevel;
#endif
layout(location = 0) out vec4 outColor;

#define LIMN_TEXTURE_BINDING 7
#include "texture_sample.glsl"

vec3 levelColour(uint level) {
    if (level == 255u) return vec3(0.25, 0.45, 0.95); // irregular faces
    const vec3 palette[8] = vec3[8](vec3(0.72, 0.72, 0.72), vec3(0.95, 0.55, 0.70),
                                    vec3(0.95, 0.85, 0.35), vec3(0.45, 0.85, 0.45),
                                    vec3(0.40, 0.85, 0.85), vec3(0.95, 0.60, 0.30),
                                    vec3(0.70, 0.50, 0.90), vec3(0.55, 0.40, 0.30));
    return palette[min(level, 7u)];
}

// kShade: the shading mode, fixed in the lit and texture variants (why in draw_common.glsl).

#ifdef LIMN_PIXEL_NORMALS
// Per-pixel limit normals (surface_lit_pixel*.frag): the triangle's element's own (s, t) (inUV's
// place), interpolated from its corners', and its control net as flat inputs (surface_vertex.glsl,
// writeNet): the normal of the limit surface at the pixel, not one interpolated across the
// triangle, so large triangles shade like small ones. Only on smooth patches: an irregular face's
// evaluation (its quadtree, the valence basis) and the crease basis keep the interpolated normal,
// and adaptive_rates.comp keeps their pieces fine.
layout(location = 4) flat in vec4 inNet0;
layout(location = 5) flat in vec4 inNet1;
layout(location = 6) flat in vec4 inNet2;
layout(location = 7) flat in vec4 inNet3;
layout(location = 8) flat in vec4 inNet4;
layout(location = 9) flat in vec4 inNet5;
layout(location = 10) flat in vec4 inNet6;
layout(location = 11) flat in vec4 inNet7;
layout(location = 12) flat in vec4 inNet8;
layout(location = 13) flat in vec4 inNet9;
layout(location = 14) flat in vec4 inNet10;
layout(location = 15) flat in vec4 inNet11;
#include "surface_eval.glsl"

// surface_eval_impl.glsl's smooth patch normal (patchPoint's sums relative to cv[5]; the phantom
// points are in the net).
vec3 pixelNormal() {
    uint mask = floatBitsToUint(inNet11.y);
    if ((mask & 16u) == 0u) return normalize(inNormal);
    // writeNet's packing, unpacked with constant indices only (per-lane scratch otherwise).
    vec3 r[16] = vec3[16](inNet0.xyz, vec3(inNet0.w, inNet1.xy), vec3(inNet1.zw, inNet2.x), inNet2.yzw,
                          inNet3.xyz, vec3(0.0), vec3(inNet3.w, inNet4.xy), vec3(inNet4.zw, inNet5.x),
                          inNet5.yzw, inNet6.xyz, vec3(inNet6.w, inNet7.xy), vec3(inNet7.zw, inNet8.x),
                          inNet8.yzw, inNet9.xyz, vec3(inNet9.w, inNet10.xy), vec3(inNet10.zw, inNet11.x));
    vec2 st = clamp(inUV, 0.0, 1.0);
    float bu[4], du[4], bv[4], dv[4];
    bspline(st.x, bu, du);
    bspline(st.y, bv, dv);
    vec3 Du = vec3(0.0), Dv = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        vec3 rowRel = vec3(0.0), rowDu = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            rowRel += bu[i] * r[4 * j + i];
            rowDu += du[i] * r[4 * j + i];
        }
        Du += bv[j] * rowDu;
        Dv += dv[j] * rowRel;
    }
    vec3 n = cross(Du, Dv);
    return dot(n, n) > 0.0 ? normalize(n) : normalize(inNormal);
}
#endif

void main() {
    if (backFaceKey(outColor)) return;
#ifdef LIMN_PIXEL_NORMALS
    vec3 n = pixelNormal();
#else
    vec3 n = normalize(inNormal);
#endif
    if (kShade == SHADE_NORMAL) {
        outColor = vec4(srgbToLinear(n * 0.5 + 0.5), 1.0);
        return;
    }
    if (kShade == SHADE_UV) {
        outColor = vec4(srgbToLinear(vec3(clamp(inUV, 0.0, 1.0), 0.0)), 1.0);
        return;
    }
    if (kShade == SHADE_LEVELS) {
        outColor = vec4(levelsLight(srgbToLinear(levelColour(inLevel)), n, inWorld), 1.0);
        return;
    }
    vec3 albedo = kShade == SHADE_TEXTURE ? sampleTexture(inUV) * baseColour() : baseColour();
    outColor = vec4(lightRig(albedo, n, inWorld), 1.0);
}
