// The colour texture (--texture, a mesh file's base colour texture), shared by the subdivision
// surface's and the control mesh's fragment stages: each defines LIMN_TEXTURE_BINDING, its
// binding, before including this.
#ifndef LIMN_TEXTURE_SAMPLE_GLSL
#define LIMN_TEXTURE_SAMPLE_GLSL

// sRGB RGBA8 texels packed in uints, rows top to bottom (image row
// = (1 - v) * height), filtered bilinearly in linear light with wrap-around.
layout(std430, binding = LIMN_TEXTURE_BINDING) readonly buffer Texture { uint width; uint height; uint rgba[]; } tex;

vec3 texel(uint x, uint y) {
    uint c = tex.rgba[y * tex.width + x];
    return srgbToLinear(vec3(c & 255u, (c >> 8) & 255u, (c >> 16) & 255u) / 255.0);
}

uint wrap(float i, uint n) {
    int k = int(i) % int(n);
    return uint(k < 0 ? k + int(n) : k);
}

vec3 sampleTexture(vec2 uv) {
    float x = uv.x * float(tex.width) - 0.5, y = (1.0 - uv.y) * float(tex.height) - 0.5;
    float x0 = floor(x), y0 = floor(y);
    float fx = x - x0, fy = y - y0;
    uint ix0 = wrap(x0, tex.width), ix1 = wrap(x0 + 1.0, tex.width);
    uint iy0 = wrap(y0, tex.height), iy1 = wrap(y0 + 1.0, tex.height);
    vec3 top = mix(texel(ix0, iy0), texel(ix1, iy0), fx);
    vec3 bottom = mix(texel(ix0, iy1), texel(ix1, iy1), fx);
    return mix(top, bottom, fy);
}

#endif
