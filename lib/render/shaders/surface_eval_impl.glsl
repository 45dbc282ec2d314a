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

// A patch's position and (unnormalized) Du x Dv at patch-local (s, t). The derivatives sum the
// control points relative to P11 (the derivative weights sum to 0, so it is the same sum): in
// float, absolute coordinates cancel catastrophically where the patch is small against its
// distance from the origin and the weights are large (across a sharp single-crease patch: 0.6
// degrees off on catmark_rook and catmark_bishop). The position keeps its sums (same bits).
void patchPoint(Patch pt, float s, float t, out vec3 P, out vec3 n) {
    float bu[4], du[4], bv[4], dv[4];
    patchBasis(pt, s, t, bu, du, bv, dv);
    P = vec3(0.0);
    vec3 Du = vec3(0.0), Dv = vec3(0.0), origin = vertices.p[pt.cv[5]].xyz;
    for (int j = 0; j < 4; ++j) {
        vec3 row = vec3(0.0), rowRel = vec3(0.0), rowDu = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            vec3 c = vertices.p[pt.cv[4 * j + i]].xyz, r = c - origin;
            row += bu[i] * c;
            rowRel += bu[i] * r;
            rowDu += du[i] * r;
        }
        P += bv[j] * row;
        Du += bv[j] * rowDu;
        Dv += dv[j] * rowRel;
    }
    n = cross(Du, Dv);
}

// A smooth irregular face's band-k sub-patch in quadrant q at local (s, t) (lib/subdiv/
// irregular_basis.h): its 16 control points from the basis's weights (header record h: the
// support size M (2n + 8 for a per-valence basis, a boundary configuration's own), corner, the
// basis's first record, its bands, the corner's limit point, its levels below its irregular
// face; then the support points, 16 a record; the basis: per band and quadrant, per support
// point a record of 16 weights). A boundary configuration's weights hold its sub-patches'
// phantom points (2 a - b of support points): its rows sum to 1 as well; so do a decaying-crease
// chain's (TBLS version 8), whose bands may be single-crease patches.
void basisPatchPoint(uint h, uint k, uint q, float s, float t, out vec3 P, out vec3 n) {
    Patch hd = patches.p[h];
    uint M = hd.cv[0];
    uint block = hd.cv[2] + ((k - 1u) * 3u + (q - 1u)) * M;
    // c: the control points (the position's sums, unchanged); r: the same relative to the first
    // support point (each row of weights sums to 1), which the derivatives read, as in
    // patchPoint: absolute coordinates lose the small differences of a small face far from the
    // origin in float (0.6 degrees on catmark_bishop).
    vec3 c[16], r[16];
    for (int j = 0; j < 16; ++j) c[j] = vec3(0.0), r[j] = vec3(0.0);
    vec3 origin = vertices.p[patches.p[h + 1u].cv[0]].xyz;
    for (uint i = 0u; i < M; ++i) {
        vec3 x = vertices.p[patches.p[h + 1u + i / 16u].cv[i % 16u]].xyz, xr = x - origin;
        Patch w = patches.p[block + i];
        for (int j = 0; j < 16; ++j) {
            float wj = uintBitsToFloat(w.cv[j]);
            c[j] += wj * x;
            r[j] += wj * xr;
        }
    }
    float bu[4], du[4], bv[4], dv[4];
    bspline(s, bu, du);
    bspline(t, bv, dv);
    // A decaying-crease chain's band may be a single-crease patch: its crease bits (canonical
    // frame) and sharpness ride on the block's first weight record (0 for a B-spline).
    Patch kind = patches.p[block];
    uint crease = (kind.levelBoundary >> 16) & 0xFu;
    if ((crease & (BOUNDARY_V0 | BOUNDARY_V1)) != 0u)
        creaseBasisAcross(t, (crease & BOUNDARY_V1) != 0u, kind.sharpness, bv, dv);
    if ((crease & (BOUNDARY_U0 | BOUNDARY_U1)) != 0u)
        creaseBasisAcross(s, (crease & BOUNDARY_U1) != 0u, kind.sharpness, bu, du);
    P = vec3(0.0);
    vec3 Du = vec3(0.0), Dv = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        vec3 row = vec3(0.0), rowRel = vec3(0.0), rowDu = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            row += bu[i] * c[4 * j + i];
            rowRel += bu[i] * r[4 * j + i];
            rowDu += du[i] * r[4 * j + i];
        }
        P += bv[j] * row;
        Du += bv[j] * rowDu;
        Dv += dv[j] * rowRel;
    }
    n = cross(Du, Dv);
}

// A smooth irregular face at st (1/32768 units), lib/subdiv/evaluate.cpp's evaluateSmooth: turned
// so that its extraordinary corner is at (0, 0), the band from the halvings of max(s, t), the
// corner itself its limit point, within 2^-K of it the bilinear blend of that and three band-K
// points.
void smoothPoint(uint h, uint st, out vec3 P, out vec3 n) {
    Patch hd = patches.p[h];
    uint S = st & 0xFFFFu, T = st >> 16, corner = hd.cv[1], K = hd.cv[3];
    uint a = corner == 0u ? S : corner == 1u ? T : corner == 2u ? 32768u - S : 32768u - T;
    uint c = corner == 0u ? T : corner == 1u ? 32768u - S : corner == 2u ? 32768u - T : S;
    vec3 evP = limits.v[2u * hd.cv[4]].xyz, evN = limits.v[2u * hd.cv[4] + 1u].xyz;
    if (a == 0u && c == 0u) {
        P = evP, n = evN;
        return;
    }
    uint k = 1u;
    while (max(a, c) < 16384u && k < K) a *= 2u, c *= 2u, ++k;
    if (max(a, c) >= 16384u) {
        uint qu = a >= 16384u ? 1u : 0u, qv = c >= 16384u ? 1u : 0u;
        uint q = qv == 0u ? 1u : qu == 1u ? 2u : 3u;
        basisPatchPoint(h, k, q, float(2u * a - qu * 32768u) / 32768.0, float(2u * c - qv * 32768u) / 32768.0, P, n);
        return;
    }
    vec3 P1, P2, P3, n1, n2, n3;
    basisPatchPoint(h, k, 1u, 0.0, 0.0, P1, n1);
    basisPatchPoint(h, k, 2u, 0.0, 0.0, P2, n2);
    basisPatchPoint(h, k, 3u, 0.0, 0.0, P3, n3);
    float x = float(a) / 16384.0, y = float(c) / 16384.0;
    float w[4] = float[4]((1.0 - x) * (1.0 - y), x * (1.0 - y), x * y, (1.0 - x) * y);
    P = w[0] * evP + w[1] * P1 + w[2] * P2 + w[3] * P3;
    n = w[0] * evN + w[1] * normalize(n1) + w[2] * normalize(n2) + w[3] * normalize(n3);
}

// The surface of irregular face `face` at st = s | t << 16 (1/32768 units) (docs/irregular.md,
// lib/subdiv/evaluate.h's evaluateIrregular): its quadtree, whose root is patches.p[patchCount
// + face] (a node's four child codes in cv[0..3]), is walked by halving (s, t), exactly in these
// fixed-point units, to the regular sub-patch there; within 2^-K of an extraordinary corner (a
// leaf), or for tables without quadtrees, the bilinear blend of the corner limit points. The
// normal's sign is the patch's (the sub-patches' axes are the face's).
void irregularPoint(uint face, uint st, uint patchCount, out vec3 P, out vec3 n) {
    uint S = st & 0xFFFFu, T = st >> 16;
    if ((S == 0u || S == 32768u) && (T == 0u || T == 32768u)) { // a corner: its limit point, as the fixed grids draw it
        uint k = S == 0u ? (T == 0u ? 0u : 3u) : (T == 0u ? 1u : 2u);
        uint c = irregulars.f[face].corner[k];
        P = limits.v[2u * c].xyz, n = limits.v[2u * c + 1u].xyz;
        return;
    }
    uint node = patchCount + face, leaf = face, ls = S, lt = T;
    for (int k = 0; k < 17; ++k) {
        uint c = (S >= 16384u ? 1u : 0u) | (T >= 16384u ? 2u : 0u);
        uint code = patches.p[node].cv[c];
        if (code == IRREGULAR_NONE) break;
        uint halvedS = 2u * S - ((c & 1u) != 0u ? 32768u : 0u);
        uint halvedT = 2u * T - ((c & 2u) != 0u ? 32768u : 0u);
        if ((code & IRREGULAR_KIND) == IRREGULAR_BASIS) {
            // A root that is a smooth face reads its own (s, t); a smooth face below a node (a
            // decayed crease) the quadrant's.
            uint h = code & ~IRREGULAR_KIND;
            smoothPoint(h, patches.p[h].cv[5] == 0u ? (S | T << 16) : (halvedS | halvedT << 16), P, n);
            return;
        }
        S = halvedS;
        T = halvedT;
        uint kind = code & IRREGULAR_KIND, index = code & ~IRREGULAR_KIND;
        if (kind == IRREGULAR_SUBPATCH) {
            patchPoint(patches.p[index], float(S) / 32768.0, float(T) / 32768.0, P, n);
            return;
        }
        if (kind == IRREGULAR_LEAF) {
            leaf = index, ls = S, lt = T;
            break;
        }
        node = index;
    }
    IrregularFace q = irregulars.f[leaf];
    float s = float(ls) / 32768.0, t = float(lt) / 32768.0;
    float w[4] = float[4]((1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t);
    P = vec3(0.0);
    n = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        P += w[k] * limits.v[2 * q.corner[k]].xyz;
        n += w[k] * limits.v[2 * q.corner[k] + 1].xyz;
    }
}

// `element` (a patch index, or patchCount + an irregular face), at `st` = s | t << 16 in 1/32768.
SurfaceSample evaluateElement(uint element, uint st, uint patchCount) {
    float s = float(st & 0xFFFFu) / 32768.0, t = float(st >> 16) / 32768.0;
    SurfaceSample r;
    vec3 P, n;
    if (element < patchCount) {
        Patch pt = patches.p[element];
        patchPoint(pt, s, t, P, n);
        r.ptex = pt.ptex;
        r.uv = vec2(pt.u0, pt.v0) + pt.size * vec2(s, t);
        r.level = pt.levelBoundary & 0xFFu;
    } else {
        IrregularFace q = irregulars.f[element - patchCount];
        irregularPoint(element - patchCount, st, patchCount, P, n);
        r.ptex = q.ptex;
        r.uv = vec2(q.u0, q.v0) + q.size * vec2(s, t);
        r.level = 255u;
    }
    r.position = P;
    r.normal = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0);
    return r;
}

// The positions of one element at the first `count` of five parameters (st as in
// evaluateElement), a patch's control points read once (adaptive_rates.comp samples each edge
// piece three or five times: on lavapipe the repeated reads were most of that pass). The same
// sums, in the same order, as evaluateElement's positions. N: the (unnormalized) normals there,
// for a test of which way the surface faces (a patch's from absolute coordinates).
void elementPositions5(uint element, uint st[5], uint count, uint patchCount, out vec3 P[5], out vec3 N[5]) {
    for (int q = 0; q < 5; ++q) P[q] = vec3(0.0), N[q] = vec3(0.0);
    if (element < patchCount) {
        Patch pt = patches.p[element];
        vec3 c[16];
        for (int k = 0; k < 16; ++k) c[k] = vertices.p[pt.cv[k]].xyz;
        for (uint q = 0u; q < count; ++q) {
            float s = float(st[q] & 0xFFFFu) / 32768.0, t = float(st[q] >> 16) / 32768.0;
            float bu[4], du[4], bv[4], dv[4];
            patchBasis(pt, s, t, bu, du, bv, dv);
            vec3 p = vec3(0.0), Du = vec3(0.0), Dv = vec3(0.0);
            for (int j = 0; j < 4; ++j) {
                vec3 row = vec3(0.0), rowDu = vec3(0.0);
                for (int i = 0; i < 4; ++i) row += bu[i] * c[4 * j + i], rowDu += du[i] * c[4 * j + i];
                p += bv[j] * row;
                Du += bv[j] * rowDu;
                Dv += dv[j] * row;
            }
            P[q] = p;
            N[q] = cross(Du, Dv);
        }
    } else {
        for (uint q = 0u; q < count; ++q) irregularPoint(element - patchCount, st[q], patchCount, P[q], N[q]);
    }
}

#ifndef LIMN_NO_TESS_VERTICES
SurfaceSample evaluateTessVertex(uint vi, uint patchCount) {
    uvec2 tv = tessVertices.v[vi].xy;
    return evaluateElement(tv.x, tv.y, patchCount);
}
#endif

#endif
