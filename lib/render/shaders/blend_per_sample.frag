// The blending surface's fragment stage (blend_fragment.glsl), each covered sample shaded on
// its own (draw_common.glsl, LIMN_SMOOTH_IN), where the device can (DeviceLimits::sampleRateShading).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LIMN_PER_SAMPLE
#include "blend_fragment.glsl"
