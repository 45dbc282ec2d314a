// Evaluates one tessellation vertex of the subdivision surface: the bicubic B-spline of its
// patch (paper 000, eq. 1) with phantom rows beyond boundary edges (math.md C.4), or the bilinear
// blend of its irregular face's limit points. Shared by the draw's vertex shader and the
// --mesh-out compute pass, so both compute the same surface with the same code.
#ifndef LIMN_SURFACE_EVAL_GLSL
#define LIMN_SURFACE_EVAL_GLSL

// Mirrors limn::render::GpuPatch.
struct Patch {
    uint cv[16];
    uint ptex;
    float u0, v0, size;
    uint levelBoundary; // level | boundary mask << 8
    uint pad0, pad1, pad2;
};
// Mirrors limn::render::GpuIrregularFace.
struct IrregularFace {
    uint corner[4];
    uint ptex;
    float u0, v0, size;
};

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

struct SurfaceSample {
    vec3 position;
    vec3 normal;
    uint ptex;
    vec2 uv;     // ptex coordinates
    uint level;  // patch level, or 255 for an irregular face
};

#endif
