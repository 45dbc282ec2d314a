// The subdivision surface's vertex stage (paper 000, 4.3): each vertex of the watertight
// tessellation is evaluated here, from its owning patch's 16 control points (bicubic B-spline,
// eq. 1) or its irregular face's limit points. With DRAW_PULL_INDICES the draw is non-indexed
// and this stage reads the index buffer itself, so it knows its triangle (for --shade levels;
// gl_PrimitiveID would need the Geometry capability, which WebGPU does not have).
// The body of surface.vert and surface_pixel.vert.
#include "draw_common.glsl"
#include "surface_eval.glsl"

layout(std430, binding = 0) readonly buffer Vertices { vec4 p[]; } vertices;
layout(std430, binding = 1) readonly buffer Patches { Patch p[]; } patches;
layout(std430, binding = 2) readonly buffer Irregulars { IrregularFace f[]; } irregulars;
layout(std430, binding = 3) readonly buffer Limits { vec4 v[]; } limits;
layout(std430, binding = 4) readonly buffer TessVertices { uvec4 v[]; } tessVertices; // element, st, u, v
layout(std430, binding = 5) readonly buffer Triangles { uint i[]; } triangles;
layout(std430, binding = 6) readonly buffer TriangleLevels { uint l[]; } triangleLevels;

#include "surface_eval_impl.glsl"

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUV;
layout(location = 3) flat out uint outLevel;

#ifdef LIMN_PIXEL_NORMALS
// Per-pixel normals (surface_pixel.vert): the triangle's own element, a
// smooth patch, hands its control net to the fragment stage as flat inputs (from the provoking
// vertex; every vertex of an element's triangles is its own, adaptive_emit.comp): the 15 control
// points relative to the 16th (cv[5], the origin patchPoint's derivatives use) and its boundary
// mask, 12 vec4 (WebGPU's 16 inter-stage variables with the four above). The fragment stage then
// evaluates the normal from these alone: storage-buffer reads indexed per fragment cost lavapipe
// a scalar load per lane, twice the whole frame (spot, 1920x1080).
layout(location = 4) flat out vec4 outNet0;
layout(location = 5) flat out vec4 outNet1;
layout(location = 6) flat out vec4 outNet2;
layout(location = 7) flat out vec4 outNet3;
layout(location = 8) flat out vec4 outNet4;
layout(location = 9) flat out vec4 outNet5;
layout(location = 10) flat out vec4 outNet6;
layout(location = 11) flat out vec4 outNet7;
layout(location = 12) flat out vec4 outNet8;
layout(location = 13) flat out vec4 outNet9;
layout(location = 14) flat out vec4 outNet10;
layout(location = 15) flat out vec4 outNet11;

// The 15 points r[i] (i != 5) in order, x, y, z each (45 floats), then 16 (a smooth patch; 0:
// none, the fragment stage interpolates the normal). Written out: an array indexed by anything but a loop counter becomes
// per-lane scratch memory on lavapipe.
void writeNet(uint element) {
    vec3 r[16];
    for (int i = 0; i < 16; ++i) r[i] = vec3(0.0);
    uint mask = 0u;
    if (element < pc.patchCount) {
        Patch pt = patches.p[element];
        if (((pt.levelBoundary >> 16) & 0xFu) == 0u) {
            vec3 origin = vertices.p[pt.cv[5]].xyz;
            for (int i = 0; i < 16; ++i) r[i] = vertices.p[pt.cv[i]].xyz - origin;
            // Phantom points beyond boundary edges (foldPhantom's P_-1 = 2 P_0 - P_1) put into
            // the net, columns then rows as the two bases fold, so the fragment stage sums the
            // plain B-spline basis.
            uint b = (pt.levelBoundary >> 8) & 0xFu;
            for (int j = 0; j < 4; ++j) {
                if ((b & BOUNDARY_U0) != 0u) r[4 * j] = 2.0 * r[4 * j + 1] - r[4 * j + 2];
                if ((b & BOUNDARY_U1) != 0u) r[4 * j + 3] = 2.0 * r[4 * j + 2] - r[4 * j + 1];
            }
            for (int i = 0; i < 4; ++i) {
                if ((b & BOUNDARY_V0) != 0u) r[i] = 2.0 * r[4 + i] - r[8 + i];
                if ((b & BOUNDARY_V1) != 0u) r[12 + i] = 2.0 * r[8 + i] - r[4 + i];
            }
            mask = 16u;
        }
    }
    outNet0 = vec4(r[0], r[1].x);
    outNet1 = vec4(r[1].yz, r[2].xy);
    outNet2 = vec4(r[2].z, r[3]);
    outNet3 = vec4(r[4], r[6].x);
    outNet4 = vec4(r[6].yz, r[7].xy);
    outNet5 = vec4(r[7].z, r[8]);
    outNet6 = vec4(r[9], r[10].x);
    outNet7 = vec4(r[10].yz, r[11].xy);
    outNet8 = vec4(r[11].z, r[12]);
    outNet9 = vec4(r[13], r[14].x);
    outNet10 = vec4(r[14].yz, r[15].xy);
    outNet11 = vec4(r[15].z, uintBitsToFloat(mask), 0.0, 0.0);
}
#endif

void main() {
    uint vi = uint(gl_VertexIndex);
    uint level = 0u;
    if ((pc.flags & DRAW_PULL_INDICES) != 0u) {
        level = triangleLevels.l[vi / 3u];
        vi = triangles.i[vi];
    }
    SurfaceSample s = evaluateTessVertex(vi, pc.patchCount);
    outWorld = s.position;
    outNormal = s.normal;
    uvec2 extra = tessVertices.v[vi].zw;
    outUV = uintBitsToFloat(extra);
    outLevel = level;
#ifdef LIMN_PIXEL_NORMALS
    // The tessellation vertex carries its triangle's element and own (s, t) (1/32768) in place
    // of the UV (adaptive_emit.comp).
    outUV = vec2(extra.y & 0xFFFFu, extra.y >> 16) / 32768.0;
    outLevel = extra.x;
    writeNet(extra.x);
#endif
    gl_Position = pc.viewProj * vec4(s.position, 1.0);
}
