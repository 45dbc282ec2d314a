// The control mesh's fragment stage (mesh_fragment.glsl), every shading mode.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "mesh_fragment.glsl"
