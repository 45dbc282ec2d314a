// The control mesh's fragment stage (mesh_fragment.glsl) for --shade lit only: the other modes'
// code compiled out (why: draw_common.glsl, LIMN_SHADE).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_SHADE SHADE_LIT
#include "mesh_fragment.glsl"
