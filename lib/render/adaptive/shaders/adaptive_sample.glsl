// The displacement map's bilinear sample with wrap-around, as displace.comp takes it (texel
// centres at half integers, v = 0 at the bottom row). The including shader declares
//   buffer Map { uint width; uint height; float v[]; } map;
#ifndef LIMN_ADAPTIVE_SAMPLE_GLSL
#define LIMN_ADAPTIVE_SAMPLE_GLSL

uint wrapTexel(float i, uint n) {
    int k = int(i) % int(n);
    return uint(k < 0 ? k + int(n) : k);
}
float texelAt(uint x, uint y) { return map.v[y * map.width + x]; }
float sampleMap(vec2 uv) {
    precise float x = uv.x * float(map.width) - 0.5;
    precise float y = (1.0 - uv.y) * float(map.height) - 0.5;
    precise float fx0 = floor(x), fy0 = floor(y);
    precise float fx = x - fx0, fy = y - fy0;
    uint x0 = wrapTexel(fx0, map.width), x1 = wrapTexel(fx0 + 1.0, map.width);
    uint y0 = wrapTexel(fy0, map.height), y1 = wrapTexel(fy0 + 1.0, map.height);
    precise float top = texelAt(x0, y0) + fx * (texelAt(x1, y0) - texelAt(x0, y0));
    precise float bottom = texelAt(x0, y1) + fx * (texelAt(x1, y1) - texelAt(x0, y1));
    precise float value = top + fy * (bottom - top);
    return value;
}

#endif
