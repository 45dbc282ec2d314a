// Evaluates one tessellation vertex of the subdivision surface: the bicubic B-spline of its
// patch (paper 000, eq. 1) with phantom rows beyond boundary edges (math.md C.4), or its
// irregular face's surface (its sub-patches, docs/irregular.md). Shared by the draw's vertex shader and the
// --mesh-out compute pass, so both compute the same surface with the same code.
#ifndef LIMN_SURFACE_EVAL_GLSL
#define LIMN_SURFACE_EVAL_GLSL

// Mirrors limn::render::GpuPatch.
struct Patch {
    uint cv[16];
    uint ptex;
    float u0, v0, size;
    uint levelBoundary; // level | boundary mask << 8 | crease edge bit << 16
    float sharpness;    // of a single-crease patch's crease
    uint pad1, pad2;
};
// Mirrors limn::render::GpuIrregularFace.
struct IrregularFace {
    uint corner[4];
    uint ptex;
    float u0, v0, size;
};

// An irregular face's quadtree node (Patches buffer, after the drawn patches): per quadrant a
// code, its kind in the top two bits (lib/subdiv/tables.h, kNode*), the index below an absolute
// index into the Patches buffer (sub-patch, node) or the Irregulars buffer (leaf).
#define IRREGULAR_KIND 0xC0000000u
#define IRREGULAR_SUBPATCH 0x00000000u
#define IRREGULAR_NODE 0x40000000u
#define IRREGULAR_LEAF 0x80000000u
#define IRREGULAR_BASIS 0xC0000000u // a smooth face's header (all four codes of a root alike)
#define IRREGULAR_NONE 0xFFFFFFFFu

#define BOUNDARY_V0 1u
#define BOUNDARY_U1 2u
#define BOUNDARY_V1 4u
#define BOUNDARY_U0 8u

void bspline(float t, out float b[4], out float d[4]) {
    float t2 = t * t, t3 = t2 * t, s = 1.0 - t;
    b[0] = s * s * s / 6.0;
    b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    b[3] = t3 / 6.0;
    d[0] = -s * s / 2.0;
    d[1] = (9.0 * t2 - 12.0 * t) / 6.0;
    d[2] = (-9.0 * t2 + 6.0 * t + 3.0) / 6.0;
    d[3] = t2 / 2.0;
}

// Folds the phantom point of a boundary end into the basis: P_-1 = 2 P_0 - P_1 means its
// weight moves as +2 to P_0 and -1 to P_1.
void foldPhantom(inout float b[4], bool atStart, bool atEnd) {
    if (atStart) {
        b[1] += 2.0 * b[0];
        b[2] -= b[0];
        b[0] = 0.0;
    }
    if (atEnd) {
        b[2] += 2.0 * b[3];
        b[1] -= b[3];
        b[3] = 0.0;
    }
}

// A single-crease patch's basis across its crease (Nießner, Loop and Greiner 2012), as
// creaseBasis in lib/subdiv/evaluate.h: the limit of a cubic B-spline curve Q0..Q3 whose vertex
// Q1 is semi-sharp, on the segment Q1 (t = 0) to Q2, by halving toward Q1 until the sharpness
// has decayed (edge points are midpoints, the crease vertex blends itself and its smooth rule by
// min(s, 1)); past t = 1/2 or after the decay the segment is a uniform B-spline.
void creaseBasis(float t, float sharpness, out float b[4], out float d[4]) {
    vec4 M[4] = vec4[4](vec4(1, 0, 0, 0), vec4(0, 1, 0, 0), vec4(0, 0, 1, 0), vec4(0, 0, 0, 1));
    float s = sharpness, scale = 1.0;
    for (int i = 0; i < 12 && s > 0.0; ++i) { // sharpness < 10 (TBLS): at most 10
        bool left = t < 0.5;
        float w = min(s, 1.0);
        vec4 e01 = 0.5 * (M[0] + M[1]), e12 = 0.5 * (M[1] + M[2]), e23 = 0.5 * (M[2] + M[3]);
        vec4 crease = w * M[1] + (1.0 - w) * (M[0] + 6.0 * M[1] + M[2]) / 8.0;
        vec4 v2 = (M[1] + 6.0 * M[2] + M[3]) / 8.0;
        if (left) {
            M[0] = e01, M[1] = crease, M[2] = e12, M[3] = v2;
        } else {
            M[0] = crease, M[1] = e12, M[2] = v2, M[3] = e23;
        }
        s -= 1.0;
        scale *= 2.0;
        t = left ? 2.0 * t : 2.0 * t - 1.0;
        if (!left) break;
    }
    float bt[4], dt[4];
    bspline(t, bt, dt);
    vec4 B = bt[0] * M[0] + bt[1] * M[1] + bt[2] * M[2] + bt[3] * M[3];
    vec4 D = scale * (dt[0] * M[0] + dt[1] * M[1] + dt[2] * M[2] + dt[3] * M[3]);
    for (int k = 0; k < 4; ++k) b[k] = B[k], d[k] = D[k];
}

// The crease basis across a single-crease patch's crease at x, mirrored when the crease is at
// the far end (x = 1): the points reversed, the derivative negated.
void creaseBasisAcross(float x, bool atEnd, float sharpness, out float b[4], out float d[4]) {
    float cb[4], cd[4];
    creaseBasis(atEnd ? 1.0 - x : x, sharpness, cb, cd);
    for (int k = 0; k < 4; ++k) {
        b[k] = atEnd ? cb[3 - k] : cb[k];
        d[k] = atEnd ? -cd[3 - k] : cd[k];
    }
}

struct SurfaceSample {
    vec3 position;
    vec3 normal;
    uint ptex;
    vec2 uv;     // ptex coordinates
    uint level;  // patch level, or 255 for an irregular face
};

#endif
