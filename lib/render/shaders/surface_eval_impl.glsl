// The evaluation itself. The including shader declares, before including this file:
//   buffer Vertices      { vec4 p[]; }          vertices;     // all table vertices
//   buffer Patches       { Patch p[]; }         patches;
//   buffer Irregulars    { IrregularFace f[]; } irregulars;
//   buffer Limits        { vec4 v[]; }          limits;       // position, normal pairs
//   buffer TessVertices  { uvec2 v[]; }         tessVertices; // element, s | t << 16
// and a uint `patchCount`. A shader that evaluates elements directly (adaptive_rates.comp)
// defines LIMN_NO_TESS_VERTICES and calls evaluateElement.
#ifndef LIMN_SURFACE_EVAL_IMPL_GLSL
#define LIMN_SURFACE_EVAL_IMPL_GLSL

// A patch's basis at (s, t) and its derivatives: the bicubic B-spline's (paper 000, eq. 1),
// phantom rows folded in at boundaries, the crease basis across a single crease.
void patchBasis(Patch pt, float s, float t, out float bu[4], out float du[4], out float bv[4],
                out float dv[4]) {
    uint mask = (pt.levelBoundary >> 8) & 0xFu;
    bspline(s, bu, du);
    bspline(t, bv, dv);
    foldPhantom(bu, (mask & BOUNDARY_U0) != 0u, (mask & BOUNDARY_U1) != 0u);
    foldPhantom(du, (mask & BOUNDARY_U0) != 0u, (mask & BOUNDARY_U1) != 0u);
    foldPhantom(bv, (mask & BOUNDARY_V0) != 0u, (mask & BOUNDARY_V1) != 0u);
    foldPhantom(dv, (mask & BOUNDARY_V0) != 0u, (mask & BOUNDARY_V1) != 0u);
    uint crease = (pt.levelBoundary >> 16) & 0xFu; // a single-crease patch: never a boundary
    if ((crease & (BOUNDARY_V0 | BOUNDARY_V1)) != 0u)
        creaseBasisAcross(t, (crease & BOUNDARY_V1) != 0u, pt.sharpness, bv, dv);
    if ((crease & (BOUNDARY_U0 | BOUNDARY_U1)) != 0u)
        creaseBasisAcross(s, (crease & BOUNDARY_U1) != 0u, pt.sharpness, bu, du);
}

// `element` (a patch index, or patchCount + an irregular face), at `st` = s | t << 16 in 1/32768.
SurfaceSample evaluateElement(uint element, uint st, uint patchCount) {
    uvec2 tv = uvec2(element, st);
    float s = float(tv.y & 0xFFFFu) / 32768.0, t = float(tv.y >> 16) / 32768.0;
    SurfaceSample r;
    if (tv.x < patchCount) {
        Patch pt = patches.p[tv.x];
        float bu[4], du[4], bv[4], dv[4];
        patchBasis(pt, s, t, bu, du, bv, dv);
        vec3 P = vec3(0.0), Du = vec3(0.0), Dv = vec3(0.0);
        for (int j = 0; j < 4; ++j) {
            vec3 row = vec3(0.0), rowDu = vec3(0.0), rowDv = vec3(0.0);
            for (int i = 0; i < 4; ++i) {
                vec3 c = vertices.p[pt.cv[4 * j + i]].xyz;
                row += bu[i] * c;
                rowDu += du[i] * c;
            }
            P += bv[j] * row;
            Du += bv[j] * rowDu;
            Dv += dv[j] * row;
        }
        vec3 n = cross(Du, Dv);
        r.position = P;
        r.normal = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0);
        r.ptex = pt.ptex;
        r.uv = vec2(pt.u0, pt.v0) + pt.size * vec2(s, t);
        r.level = pt.levelBoundary & 0xFFu;
    } else {
        IrregularFace q = irregulars.f[tv.x - patchCount];
        float w[4] = float[4]((1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t);
        vec3 P = vec3(0.0), N = vec3(0.0);
        for (int k = 0; k < 4; ++k) {
            P += w[k] * limits.v[2 * q.corner[k]].xyz;
            N += w[k] * limits.v[2 * q.corner[k] + 1].xyz;
        }
        r.position = P;
        r.normal = dot(N, N) > 0.0 ? normalize(N) : vec3(0.0);
        r.ptex = q.ptex;
        r.uv = vec2(q.u0, q.v0) + q.size * vec2(s, t);
        r.level = 255u;
    }
    return r;
}

// The positions of one element at three parameters (st as in evaluateElement), its control
// points or limit points read once (adaptive_rates.comp samples each edge piece three times: on
// lavapipe the repeated reads were most of that pass). The same sums, in the same order, as
// evaluateElement's positions.
void elementPositions3(uint element, uint st[3], uint patchCount, out vec3 P[3]) {
    if (element < patchCount) {
        Patch pt = patches.p[element];
        vec3 c[16];
        for (int k = 0; k < 16; ++k) c[k] = vertices.p[pt.cv[k]].xyz;
        for (int q = 0; q < 3; ++q) {
            float s = float(st[q] & 0xFFFFu) / 32768.0, t = float(st[q] >> 16) / 32768.0;
            float bu[4], du[4], bv[4], dv[4];
            patchBasis(pt, s, t, bu, du, bv, dv);
            vec3 p = vec3(0.0);
            for (int j = 0; j < 4; ++j) {
                vec3 row = vec3(0.0);
                for (int i = 0; i < 4; ++i) row += bu[i] * c[4 * j + i];
                p += bv[j] * row;
            }
            P[q] = p;
        }
    } else {
        IrregularFace f = irregulars.f[element - patchCount];
        vec3 c[4];
        for (int k = 0; k < 4; ++k) c[k] = limits.v[2 * f.corner[k]].xyz;
        for (int q = 0; q < 3; ++q) {
            float s = float(st[q] & 0xFFFFu) / 32768.0, t = float(st[q] >> 16) / 32768.0;
            float w[4] = float[4]((1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t);
            vec3 p = vec3(0.0);
            for (int k = 0; k < 4; ++k) p += w[k] * c[k];
            P[q] = p;
        }
    }
}

#ifndef LIMN_NO_TESS_VERTICES
SurfaceSample evaluateTessVertex(uint vi, uint patchCount) {
    uvec2 tv = tessVertices.v[vi].xy;
    return evaluateElement(tv.x, tv.y, patchCount);
}
#endif

#endif
