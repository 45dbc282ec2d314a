// The subdivision surface's fragment stage (surface_fragment.glsl) for --shade texture only, each covered
// sample shaded on its own (surface_per_sample.frag): the other modes' code compiled out (why:
// draw_common.glsl, LIMN_SHADE).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_PER_SAMPLE
#define LIMN_SHADE SHADE_TEXTURE
#include "surface_fragment.glsl"
