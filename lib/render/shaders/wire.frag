#version 450
#extension GL_GOOGLE_include_directive : require
#include "draw_common.glsl"

layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(pc.wireColor.rgb, 1.0); }
