// Shading and trimming of the blending surface (paper 001, 4.3). Trimming: each face owns one
// R×R tile of a binary trim atlas, tile(f) = (f mod tilesX, f div tilesX) (math.md A.8); the
// fragment's interpolated face (u, v) picks the nearest texel (u to the right, v up, so a tile
// pictures its face with c0 at the bottom left), and the fragment is discarded where the texel is
// below 0.5. `levels` colours each quarter of a face by the vertex whose chart dominates there
// (its nearest corner): regular vertices (4 faces inside, 2 on the boundary, 1 at a corner)
// grey, others by their number of faces k, boundary ones darker.
// The body of blend.frag and blend_per_sample.frag.
#define LIMN_FRAGMENT_STAGE
#include "draw_common.glsl"
#include "blend_eval.glsl"
#include "blend_draw.glsl"

layout(location = 0) LIMN_SMOOTH_IN vec3 inWorld;
layout(location = 1) LIMN_SMOOTH_IN vec3 inNormal;
layout(location = 2) LIMN_SMOOTH_IN vec2 inUV;
layout(location = 3) LIMN_SMOOTH_IN vec2 inFaceUV;
layout(location = 4) flat in uint inFace;
layout(location = 0) out vec4 outColor;

// kShade: the shading mode, fixed in the lit variants (why in draw_common.glsl).

bool trimmedAway(uint face, vec2 uv) {
    uint R = drawData.trimTile;
    if (R == 0u) return false;
    uvec2 tile = uvec2(face % drawData.trimTilesX, face / drawData.trimTilesX);
    uvec2 texel = min(uvec2(clamp(uv, 0.0, 1.0) * float(R)), uvec2(R - 1u));
    uint x = tile.x * R + texel.x, y = tile.y * R + (R - 1u - texel.y); // rows top to bottom
    uint index = y * drawData.trimWidth + x;
    uint value = (drawData.texels[index >> 2] >> (8u * (index & 3u))) & 0xFFu;
    return value < 128u; // 8-bit texel below 0.5
}

vec3 valenceColour(uint face, vec2 uv) {
    uint corner = uv.x < 0.5 ? (uv.y < 0.5 ? 0u : 3u) : (uv.y < 0.5 ? 1u : 2u);
    uint vid = blendFaces.f[face].vertex[corner];
    uint k = blendVertices.v[vid].k, kind = blendVertices.v[vid].kind;
    uint regular = kind == 0u ? 4u : kind == 1u ? 2u : 1u;
    if (k == regular) return vec3(0.72, 0.72, 0.72);
    const vec3 palette[7] = vec3[7](vec3(0.95, 0.55, 0.70), vec3(0.25, 0.45, 0.95),  // k <= 2, 3
                                    vec3(0.40, 0.85, 0.85), vec3(0.95, 0.85, 0.35),  // 4, 5
                                    vec3(0.45, 0.85, 0.45), vec3(0.95, 0.60, 0.30),  // 6, 7
                                    vec3(0.70, 0.50, 0.90));                         // >= 8
    uint slot = clamp(k, 2u, 8u) - 2u;
    vec3 c = palette[slot];
    return kind == 0u ? c : 0.6 * c; // boundary and corner vertices darker
}

void main() {
    if (trimmedAway(inFace, inFaceUV)) discard;
    if (backFaceKey(outColor)) return;
    vec3 n = normalize(inNormal);
    if (kShade == SHADE_NORMAL) {
        outColor = vec4(srgbToLinear(n * 0.5 + 0.5), 1.0);
        return;
    }
    if (kShade == SHADE_UV) {
        outColor = vec4(srgbToLinear(vec3(clamp(inUV, 0.0, 1.0), 0.0)), 1.0);
        return;
    }
    if (kShade == SHADE_LEVELS) {
        outColor = vec4(levelsLight(srgbToLinear(valenceColour(inFace, inFaceUV)), n, inWorld), 1.0);
        return;
    }
    outColor = vec4(lightRig(baseColour(), n, inWorld), 1.0); // two-sided: trimmed surfaces show their back
}
