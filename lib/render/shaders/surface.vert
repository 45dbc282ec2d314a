// The subdivision surface's vertex stage (surface_vertex.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "surface_vertex.glsl"
