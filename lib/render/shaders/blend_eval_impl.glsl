// Evaluates the manifold blending surface at (face, u, v) (paper 001, 3.2-3.5 and 4.2; math.md
// A.6; docs/blend.md "Evaluating it" gives the same formula, lib/blend/blend_surface.cpp is the
// CPU reference). Shared by the draw's vertex stage (blend.vert, --eval vertex) and the compute
// pass (blend_eval.comp, --eval compute and --mesh-out), so both compute the same bits.
//
// The including shader declares, before including this file (A.9: per vertex its chart and 9
// coefficients, per face 4 vertex ids and ring indices):
//   buffer BlendVertices { BlendVertex v[]; } blendVertices;
//   buffer BlendFaces    { BlendFace f[]; }   blendFaces;
// Records are read from the buffers where they are used, never copied into local structs or
// arrays first: with the copies (which lavapipe keeps in scratch memory when they are indexed
// dynamically) the pass took about twice as long on lavapipe.
#ifndef LIMN_BLEND_EVAL_IMPL_GLSL
#define LIMN_BLEND_EVAL_IMPL_GLSL

// Coordinate c of the local surface less `origin` (E4), and its x and y derivatives:
// L_c = X·M_c·Y with M_c[b][a] = c_ab, X = (1, x, x²), Y = (1, y, y²), c_00 shifted by origin.
vec3 blendLocalCoordinate(uint vid, uint c, float origin, vec2 z) {
    uint b = 9u * c;
    mat3 M = mat3(blendVertices.v[vid].coef[b] - origin, blendVertices.v[vid].coef[b + 1u],
                  blendVertices.v[vid].coef[b + 2u], blendVertices.v[vid].coef[b + 3u],
                  blendVertices.v[vid].coef[b + 4u], blendVertices.v[vid].coef[b + 5u],
                  blendVertices.v[vid].coef[b + 6u], blendVertices.v[vid].coef[b + 7u],
                  blendVertices.v[vid].coef[b + 8u]);
    vec3 X = vec3(1.0, z.x, z.x * z.x), Y = vec3(1.0, z.y, z.y * z.y);
    vec3 dX = vec3(0.0, 1.0, 2.0 * z.x), dY = vec3(0.0, 1.0, 2.0 * z.y);
    vec3 MY = M * Y;
    return vec3(dot(X, MY), dot(dX, MY), dot(X, M * dY));
}

BlendSample evaluateBlend(uint face, float u, float v, uint weights) {
    // Blend relative to the face's first corner: Σw = 1 and Σ∇w = 0, so the origin drops out of
    // the derivatives, and f32 no longer loses the small derivative sums against rounding errors
    // of the size of the coordinates (the derivatives are of the face's size, the coordinates of
    // the model's). c_00 − origin is one rounding of a face-sized difference.
    uint v0 = blendFaces.f[face].vertex[0];
    vec3 origin = vec3(blendVertices.v[v0].coef[0], blendVertices.v[v0].coef[9],
                       blendVertices.v[v0].coef[18]);
    vec3 S = vec3(0.0), Du = vec3(0.0), Dv = vec3(0.0);
    float W = 0.0, dWu = 0.0, dWv = 0.0;
    uint atVertex = 0xFFFFFFFFu; // the vertex the sample sits on, if any
    for (uint i = 0u; i < 4u; ++i) {
        uint vid = blendFaces.f[face].vertex[i];
        vec2 st = blendCornerCoords(i, u, v);
        vec4 J = blendCornerJacobian(i);
        // Weight w = h(s)h(t) (E3) and its gradient (h'(s)h(t), h(s)h'(t)) · J_i.
        vec2 hs = blendStep(weights, st.x), ht = blendStep(weights, st.y);
        float w = hs.x * ht.x;
        float ws = hs.y * ht.x, wt = hs.x * ht.y;
        float wu = ws * J.x + wt * J.z, wv = ws * J.y + wt * J.w;
        // Chart (E2): z = r^p (cos Φ, sin Φ), Φ = q·atan2(t,s) + jΘ/k, and K = dz/d(u,v).
        vec2 z = vec2(0.0);
        vec4 K = vec4(0.0);
        float r = length(st);
        if (r < kBlendVertexEpsilon) {
            atVertex = vid;
        } else {
            float p = blendVertices.v[vid].p, q = blendVertices.v[vid].q;
            float phi = q * atan(st.y, st.x) + float(blendFaces.f[face].ring[i]) *
                                                   blendVertices.v[vid].theta /
                                                   float(blendVertices.v[vid].k);
            float rp = pow(r, p), c = cos(phi), s = sin(phi);
            float dr = p * rp / r, dth = q * rp;              // |dz/dr|, |dz/dθ|
            float rs = st.x / r, rt = st.y / r;               // dr/ds, dr/dt
            float ts = -st.y / (r * r), tt = st.x / (r * r);  // dθ/ds, dθ/dt
            vec4 Jz = vec4(dr * c * rs - dth * s * ts, dr * c * rt - dth * s * tt,
                           dr * s * rs + dth * c * ts, dr * s * rt + dth * c * tt);
            K = blendMul(Jz, J);
            z = rp * vec2(c, s);
        }
        // Local surface (E4) and its derivatives in the chart, per coordinate.
        vec3 Lc0 = blendLocalCoordinate(vid, 0u, origin.x, z);
        vec3 Lc1 = blendLocalCoordinate(vid, 1u, origin.y, z);
        vec3 Lc2 = blendLocalCoordinate(vid, 2u, origin.z, z);
        vec3 L = vec3(Lc0.x, Lc1.x, Lc2.x), Lx = vec3(Lc0.y, Lc1.y, Lc2.y), Ly = vec3(Lc0.z, Lc1.z, Lc2.z);
        vec3 Lu = Lx * K.x + Ly * K.z, Lv = Lx * K.y + Ly * K.w; // zero at the vertex itself
        S += w * L;
        W += w;
        dWu += wu;
        dWv += wv;
        Du += wu * L + w * Lu;
        Dv += wv * L + w * Lv;
    }
    // E1's normalization and the quotient rule; W is 1 up to rounding (A.4).
    S /= W;
    Du = (Du - dWu * S) / W;
    Dv = (Dv - dWv * S) / W;
    vec3 n;
    if (atVertex != 0xFFFFFFFFu) {
        // At a vertex the true limit normal is c_10 × c_01 of its local surface (A.6).
        n = cross(vec3(blendVertices.v[atVertex].coef[1], blendVertices.v[atVertex].coef[10],
                       blendVertices.v[atVertex].coef[19]),
                  vec3(blendVertices.v[atVertex].coef[3], blendVertices.v[atVertex].coef[12],
                       blendVertices.v[atVertex].coef[21]));
    } else {
        n = cross(Du, Dv);
    }
    float len = length(n);
    BlendSample result;
    result.position = origin + S;
    result.normal = len > 0.0 ? n / len : vec3(0.0);
    return result;
}

#endif
