// Shading of the control mesh: `lit` is the studio rig (lightRig, draw_common.glsl) on the flat
// face normals, `texture` the same with the colour texture as the subdivision surface samples it
// (texture_sample.glsl); `normal` and `uv` store the value itself.
// The body of mesh.frag and mesh_lit.frag.
#define LIMN_FRAGMENT_STAGE
#include "draw_common.glsl"

layout(location = 0) in vec3 inWorld;
layout(location = 1) flat in vec3 inNormal;
layout(location = 2) in vec2 inUV;
layout(location = 0) out vec4 outColor;

#define LIMN_TEXTURE_BINDING 4
#include "texture_sample.glsl"

// kShade: the shading mode, fixed in the lit variant (why in draw_common.glsl).

void main() {
    if (backFaceKey(outColor)) return;
    vec3 n = inNormal;
    if (kShade == SHADE_NORMAL) {
        outColor = vec4(srgbToLinear(n * 0.5 + 0.5), 1.0);
        return;
    }
    if (kShade == SHADE_UV) {
        outColor = vec4(srgbToLinear(vec3(clamp(inUV, 0.0, 1.0), 0.0)), 1.0);
        return;
    }
    // Two-sided (control meshes may be open); zero for degenerate faces (n = 0).
    vec3 albedo = kShade == SHADE_TEXTURE ? sampleTexture(inUV) * baseColour() : baseColour();
    outColor = vec4(lightRig(albedo, n, inWorld), 1.0);
}
