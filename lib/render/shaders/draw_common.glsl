// Push constants shared by the draw shaders; mirrors limn::render::DrawPush (renderer.cpp).
#ifndef LIMN_DRAW_COMMON_GLSL
#define LIMN_DRAW_COMMON_GLSL

// Shading modes; mirror limn::render::Shade.
#define SHADE_LIT 0u
#define SHADE_NORMAL 1u
#define SHADE_UV 2u
#define SHADE_LEVELS 3u
#define SHADE_TEXTURE 4u

// DrawPush.flags
#define DRAW_PULL_INDICES 1u // the vertex stage reads the index buffer itself (per-triangle data)
#define DRAW_BACK_FACE_KEY 2u // back faces flat in the sRGB8 colour packed in light.w's bits

layout(push_constant) uniform DrawPush {
    mat4 viewProj;   // world -> clip, Y up, depth 0..1
    vec4 eye;        // xyz: camera position (world)
    vec4 light;      // xyz: unit direction towards the light (world)
    vec4 wireColor;  // rgb linear
    uint shade;      // SHADE_*
    float wirePull;  // wire vertices move this fraction of the way to the eye (no z-fighting)
    uint patchCount; // subdivision draw: elements below this are patches, the rest irregular faces
    uint flags;      // DRAW_*
} pc;

// Stored colours (normal, uv) are written so that the PNG holds the value itself: the sRGB
// target encodes on write, so decode first.
vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

#ifdef LIMN_FRAGMENT_STAGE // gl_FrontFacing exists only there
// --back-faces: true (and the key colour set) when this fragment belongs to a face seen from
// behind. Faces are counter-clockwise seen from outside, so on a closed surface seen from
// outside only cracks, holes and flipped faces show one.
bool backFaceKey(out vec4 colour) {
    if ((pc.flags & DRAW_BACK_FACE_KEY) == 0u || gl_FrontFacing) return false;
    uint c = floatBitsToUint(pc.light.w);
    colour = vec4(srgbToLinear(vec3(c & 255u, (c >> 8) & 255u, (c >> 16) & 255u) / 255.0), 1.0);
    return true;
}
#endif

#endif
