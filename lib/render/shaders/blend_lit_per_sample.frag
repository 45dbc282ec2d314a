// The blending surface's fragment stage (blend_fragment.glsl) for --shade lit only, each covered
// sample shaded on its own (blend_per_sample.frag): the other modes' code compiled out (why:
// draw_common.glsl, LIMN_SHADE).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_PER_SAMPLE
#define LIMN_SHADE SHADE_LIT
#include "blend_fragment.glsl"
