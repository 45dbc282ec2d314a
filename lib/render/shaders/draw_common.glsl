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
#define DRAW_Z_UP 4u          // the world's up is +Z (else +Y), for lightRig's sky and ground

layout(push_constant) uniform DrawPush {
    mat4 viewProj;   // world -> clip, Y up, depth 0..1
    vec4 eye;        // xyz: camera position (world); w: lit base colour, sRGB8 bits 0x00BBGGRR
    vec4 light;      // xyz: unit direction towards the key light (world)
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
// The smooth-shaded surfaces' interpolated inputs. With LIMN_PER_SAMPLE (the *_per_sample.frag
// variants, --sample-shading) they are read at each sample, which makes the fragment stage run
// once per covered sample: 4x multisampling then also averages 4 shadings of a pixel, so a
// highlight on a surface that bends within a pixel (a semi-sharp crease, drawn as sub-pixel
// triangles) no longer sparkles with where the pixel centre falls, and a trim edge is
// anti-aliased. (Shading the pixel's 4 sample positions from one triangle's derivatives was
// tried: catmark_car's view-adaptive image stayed 0.87% from the fixed grids', against 0.34%
// per sample, since the bend lies across triangles.) WebGPU: @interpolate(perspective, sample).
#ifdef LIMN_PER_SAMPLE
#define LIMN_SMOOTH_IN sample in
#else
#define LIMN_SMOOTH_IN in
#endif

// The shading mode: the push constant's, or fixed when a variant compiles with LIMN_SHADE
// (surface_lit*.frag, surface_texture*.frag, blend_lit*.frag, mesh_lit.frag, which the hosts pick
// for those modes). Fixed, the other modes' code is dead and the compiler drops it; from the push
// constant every mode's code runs for every fragment on a SIMD rasterizer that executes both
// sides of a uniform branch under a mask, as lavapipe's does (Mesa 22.3): there the texture
// filter's four fetches and the twenty-odd pow() of the unused modes cost more than the lit
// shading itself (spot, 1920x1080, 4 samples: the frame's CPU time 40% less with the lit
// variant, docs/adaptive.md "Where the frame's time goes"). Each mode's own code is the same in
// every variant, and so are its pixels.
#ifdef LIMN_SHADE
const uint kShade = LIMN_SHADE;
#else
#define kShade pc.shade
#endif

vec3 unpackSrgb8(uint c) {
    return srgbToLinear(vec3(c & 255u, (c >> 8) & 255u, (c >> 16) & 255u) / 255.0);
}

// --back-faces: true (and the key colour set) when this fragment belongs to a face seen from
// behind. Faces are counter-clockwise seen from outside, so on a closed surface seen from
// outside only cracks, holes and flipped faces show one.
bool backFaceKey(out vec4 colour) {
    if ((pc.flags & DRAW_BACK_FACE_KEY) == 0u || gl_FrontFacing) return false;
    colour = vec4(unpackSrgb8(floatBitsToUint(pc.light.w)), 1.0);
    return true;
}

// The lit shading's base colour (--color, a glTF baseColorFactor), linear.
vec3 baseColour() {
    return unpackSrgb8(floatBitsToUint(pc.eye.w));
}

// `lit` and `texture`: a small studio rig in linear light (the sRGB target encodes on write),
// the same for the control mesh, the subdivision surface and the blending surface:
//   - hemisphere ambient (sky above, ground below, blended by the normal's up component; the
//     "hemisphere light" of Akenine-Moller, Haines, Hoffman, Real-Time Rendering, 4th ed., 10.3),
//     so that faces turned away from every light still show which way they turn;
//   - a Lambert key light from pc.light (--light, fixed to the camera);
//   - a dim Lambert fill from the eye (a headlight), so that nothing facing the camera is black;
//   - a modest white Blinn-Phong highlight of the key (Blinn 1977, half vector between the key
//     and the eye), which shows curvature on a white model where diffuse light alone is flat.
// Two-sided: the side facing the camera is lit (control meshes and trimmed surfaces may be open).
// A zero normal (a degenerate face) gets the ambient mid-tone and no direct light.
const vec3 kSky = vec3(0.32), kGround = vec3(0.09); // neutral: a grey model stays grey
const float kKey = 0.75, kFill = 0.18, kSpecular = 0.06, kShininess = 40.0;

vec3 lightRig(vec3 albedo, vec3 n, vec3 world) {
    vec3 v = normalize(pc.eye.xyz - world);
    if (dot(n, v) < 0.0) n = -n;
    vec3 up = (pc.flags & DRAW_Z_UP) != 0u ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0);
    vec3 ambient = mix(kGround, kSky, 0.5 + 0.5 * dot(n, up));
    vec3 l = pc.light.xyz;
    float key = max(dot(n, l), 0.0);
    float fill = max(dot(n, v), 0.0);
    float highlight = 0.0;
    if (key > 0.0) highlight = pow(max(dot(n, normalize(l + v)), 0.0), kShininess);
    return albedo * (ambient + kKey * key + kFill * fill) + kSpecular * highlight;
}

// `levels`: the shading it has always had (a Lambert light from pc.light, which the renderer
// sets to its old headlight for this mode, plus ambient 0.12), so level pictures compare with
// older ones.
vec3 levelsLight(vec3 albedo, vec3 n, vec3 world) {
    if (dot(n, pc.eye.xyz - world) < 0.0) n = -n;
    float diffuse = max(dot(n, pc.light.xyz), 0.0);
    return albedo * (0.12 + (1.0 - 0.12) * diffuse);
}
#endif

#endif
