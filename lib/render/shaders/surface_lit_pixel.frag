// The subdivision surface's fragment stage (surface_fragment.glsl) for --shade lit with per-pixel
// limit normals (--pixel-normals): the element's normal evaluated at each pixel's (s, t), shaded
// once per pixel and primitive, the other modes' code compiled out.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_SHADE SHADE_LIT
#define LIMN_PIXEL_NORMALS
#include "surface_fragment.glsl"
