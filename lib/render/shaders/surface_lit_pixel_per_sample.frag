// The subdivision surface's fragment stage (surface_fragment.glsl) for --shade lit with per-pixel
// limit normals (--pixel-normals), each covered sample shaded on its own (surface_per_sample.frag).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_PER_SAMPLE
#define LIMN_SHADE SHADE_LIT
#define LIMN_PIXEL_NORMALS
#include "surface_fragment.glsl"
