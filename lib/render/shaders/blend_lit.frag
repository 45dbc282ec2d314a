// The blending surface's fragment stage (blend_fragment.glsl) for --shade lit only, shaded once
// per pixel and primitive: the other modes' code compiled out (why: draw_common.glsl, LIMN_SHADE).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_SHADE SHADE_LIT
#include "blend_fragment.glsl"
