// The subdivision surface's fragment stage (surface_fragment.glsl), shaded once per pixel and
// primitive: for devices without sampleRateShading.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "surface_fragment.glsl"
