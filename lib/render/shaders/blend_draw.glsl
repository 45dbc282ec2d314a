// The bindings and outputs the blending surface's draw shares between its vertex shaders
// (blend.vert evaluates, blend_fetch.vert reads what blend_eval.comp evaluated) and its fragment
// shader (blend.frag: shading and trimming). Mirrors limn::render::BlendPass's bind group.
#ifndef LIMN_BLEND_DRAW_GLSL
#define LIMN_BLEND_DRAW_GLSL

layout(std430, binding = 0) readonly buffer BlendVertices { BlendVertex v[]; } blendVertices;
layout(std430, binding = 1) readonly buffer BlendFaces { BlendFace f[]; } blendFaces;
// Per grid corner of a drawn face (GpuBlendDrawVertex): point index, the point's owner face and
// i | j << 16, the face drawn. (K+1)² per drawn face, row-major in (i, j).
layout(std430, binding = 2) readonly buffer DrawVertices { uvec4 v[]; } drawVertices;
layout(std430, binding = 3) readonly buffer Positions { vec4 p[]; } positions; // per point
layout(std430, binding = 4) readonly buffer Normals { vec4 n[]; } normals;     // per point
// Mirrors limn::render::BlendDrawData, then the trim atlas (math.md A.8): 8-bit texels, four to a
// word, rows top to bottom, trimWidth texels a row; trimTile = 0 means no trimming.
layout(std430, binding = 5) readonly buffer DrawData {
    uint grid;       // K
    uint weights;    // BLEND_WEIGHTS_*
    uint trimTile;   // R: texels per tile side
    uint trimTilesX; // tiles per atlas row
    uint trimWidth;  // atlas width in texels (trimTilesX * R)
    uint hasUVs;     // 1: faceUVs holds 4 UVs per face
    uint reserved0, reserved1;
    uint texels[];
} drawData;
layout(std430, binding = 6) readonly buffer FaceUVs { vec2 uv[]; } faceUVs; // 4 per face, or none

#endif
