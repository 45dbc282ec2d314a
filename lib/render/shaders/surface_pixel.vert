// The subdivision surface's vertex stage (surface_vertex.glsl) for per-pixel limit normals
// (--pixel-normals, surface_lit_pixel*.frag): also the triangle's element, its own (s, t) and
// its control net.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_PIXEL_NORMALS
#include "surface_vertex.glsl"
