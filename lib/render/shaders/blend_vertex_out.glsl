// What both vertex shaders of the blending surface pass on (blend.vert, blend_fetch.vert).
#ifndef LIMN_BLEND_VERTEX_OUT_GLSL
#define LIMN_BLEND_VERTEX_OUT_GLSL

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUV;     // the mesh's texture coordinates, bilinear over the face
layout(location = 3) out vec2 outFaceUV; // (u, v) of the face drawn, for trimming and levels
layout(location = 4) flat out uint outFace;

// Draw vertex d is grid corner (i, j) of its face (blend_draw.h): the face's own (u, v), which
// differs from the owner's at a shared point, is what trimming needs (A.8).
void blendVertexOut(uint d, uint face, vec3 position, vec3 normal, bool hasUVs) {
    uint side = drawData.grid + 1u, local = d % (side * side);
    vec2 uv = vec2(float(local % side), float(local / side)) / float(drawData.grid);
    outWorld = position;
    outNormal = normal;
    outFaceUV = uv;
    outFace = face;
    outUV = vec2(0.0);
    if (hasUVs) {
        vec2 c0 = faceUVs.uv[4u * face], c1 = faceUVs.uv[4u * face + 1u];
        vec2 c2 = faceUVs.uv[4u * face + 2u], c3 = faceUVs.uv[4u * face + 3u];
        outUV = mix(mix(c0, c1, uv.x), mix(c3, c2, uv.x), uv.y);
    }
    gl_Position = pc.viewProj * vec4(position, 1.0);
}

#endif
