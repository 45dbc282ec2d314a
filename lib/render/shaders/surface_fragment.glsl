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

// The shading mode: the push constant's, or fixed when compiling with LIMN_SHADE (surface_lit*.frag,
// surface_texture*.frag, which the host picks for those modes). Fixed, the other modes' code is
// dead and the compiler drops it; from the push constant every mode's code runs for every
// fragment on a SIMD rasterizer that executes both sides of a uniform branch under a mask, as
// lavapipe's does (Mesa 22.3): there the texture filter's four fetches and the twenty-odd pow()
// of the unused modes cost more than the lit shading itself (spot, 1920x1080, 4 samples: the
// frame's CPU time 40% less with the lit variant, docs/adaptive.md "Where the frame's time goes").
// Each mode's own code is the same in every variant, and so are its pixels.
#ifdef LIMN_SHADE
const uint kShade = LIMN_SHADE;
#else
#define kShade pc.shade
#endif

void main() {
    if (backFaceKey(outColor)) return;
    vec3 n = normalize(inNormal);
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
