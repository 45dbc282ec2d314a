// Evaluates the manifold blending surface at (face, u, v) (paper 001, 3.2-3.5 and 4.2; math.md
// A.6; docs/blend.md "Evaluating it" gives the same formula, lib/blend/blend_surface.cpp is the
// CPU reference). Shared by the draw's vertex stage (blend.vert, --eval vertex) and the compute
// pass (blend_eval.comp, --eval compute and --mesh-out), so both compute the same bits.
//
// The caller fetches the face record and its four corners' vertex records (A.9: per face 4 vertex
// ids and ring indices, per vertex its chart and 9 coefficients):
//   BlendFace bf = blendFaces.f[face];
//   BlendVertex V[4] = BlendVertex[4](blendVertices.v[bf.vertex[0]], ..., [bf.vertex[3]]);
#ifndef LIMN_BLEND_EVAL_GLSL
#define LIMN_BLEND_EVAL_GLSL

// Mirror the BLND records (formats/limn.md section 7) and limn::render::GpuBlend{Vertex,Face}.
struct BlendVertex {
    uint k;        // faces around the vertex
    uint kind;     // 0 interior, 1 boundary, 2 corner (A.7)
    float theta;   // total chart angle Θ
    float p, q;    // chart exponents (A.3, eq. E2)
    float coef[27]; // coef[9c + a + 3b] = coordinate c of c_ab (A.5, eq. E4)
};
struct BlendFace {
    uint vertex[4]; // corners c0..c3
    uint ring[4];   // ring index j of the face at each corner's vertex (A.2)
};

#define BLEND_WEIGHTS_CUBIC 0u
#define BLEND_WEIGHTS_QUINTIC 1u

// Within this distance of a corner (in corner coordinates) the sample is the vertex itself: f32
// cannot follow the chart Jacobian's r^(q-1) closer in (A.6; docs/blend.md, precision notes).
const float kBlendVertexEpsilon = 1e-6;

struct BlendSample {
    vec3 position;
    vec3 normal; // unit, or zero where the surface is degenerate
};

// h(x) and h'(x) of the Hermite step (A.4, eq. E3).
vec2 blendStep(uint weights, float x) {
    x = clamp(x, 0.0, 1.0);
    float x2 = x * x;
    if (weights == BLEND_WEIGHTS_QUINTIC) {
        float omx = 1.0 - x;
        return vec2(1.0 - x2 * x * (10.0 - 15.0 * x + 6.0 * x2), -30.0 * x2 * omx * omx);
    }
    return vec2(1.0 - x2 * (3.0 - 2.0 * x), -6.0 * x * (1.0 - x));
}

// Corner coordinates (s, t) of corner i (A.1) and J_i = d(s,t)/d(u,v) as (m00, m01, m10, m11),
// rows ds, dt.
vec2 blendCornerCoords(uint i, float u, float v) {
    if (i == 0u) return vec2(u, v);
    if (i == 1u) return vec2(v, 1.0 - u);
    if (i == 2u) return vec2(1.0 - u, 1.0 - v);
    return vec2(1.0 - v, u);
}
vec4 blendCornerJacobian(uint i) {
    if (i == 0u) return vec4(1.0, 0.0, 0.0, 1.0);
    if (i == 1u) return vec4(0.0, 1.0, -1.0, 0.0);
    if (i == 2u) return vec4(-1.0, 0.0, 0.0, -1.0);
    return vec4(0.0, -1.0, 1.0, 0.0);
}
vec4 blendMul(vec4 a, vec4 b) { // row-major 2x2 product
    return vec4(a.x * b.x + a.y * b.z, a.x * b.y + a.y * b.w, a.z * b.x + a.w * b.z,
                a.z * b.y + a.w * b.w);
}

BlendSample evaluateBlend(BlendFace bf, BlendVertex corners[4], float u, float v, uint weights) {
    // Blend relative to the face's first corner: Σw = 1 and Σ∇w = 0, so the origin drops out of
    // the derivatives, and f32 no longer loses the small derivative sums against rounding errors
    // of the size of the coordinates (the derivatives are of the face's size, the coordinates of
    // the model's). c_00 − origin is one rounding of a face-sized difference.
    vec3 origin = vec3(corners[0].coef[0], corners[0].coef[9], corners[0].coef[18]);
    vec3 S = vec3(0.0), Du = vec3(0.0), Dv = vec3(0.0);
    float W = 0.0, dWu = 0.0, dWv = 0.0;
    int atVertex = -1;
    for (uint i = 0u; i < 4u; ++i) {
        BlendVertex V = corners[i];
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
            atVertex = int(i);
        } else {
            float phi = V.q * atan(st.y, st.x) + float(bf.ring[i]) * V.theta / float(V.k);
            float rp = pow(r, V.p), c = cos(phi), s = sin(phi);
            float dr = V.p * rp / r, dth = V.q * rp;             // |dz/dr|, |dz/dθ|
            float rs = st.x / r, rt = st.y / r;                   // dr/ds, dr/dt
            float ts = -st.y / (r * r), tt = st.x / (r * r);      // dθ/ds, dθ/dt
            vec4 Jz = vec4(dr * c * rs - dth * s * ts, dr * c * rt - dth * s * tt,
                           dr * s * rs + dth * c * ts, dr * s * rt + dth * c * tt);
            K = blendMul(Jz, J);
            z = rp * vec2(c, s);
        }
        // Local surface (E4), less the origin: L_c = X·M_c·Y with M_c[b][a] = c_ab (c_00 − origin_c),
        // X = (1, x, x²), Y = (1, y, y²).
        vec3 X = vec3(1.0, z.x, z.x * z.x), Y = vec3(1.0, z.y, z.y * z.y);
        vec3 dX = vec3(0.0, 1.0, 2.0 * z.x), dY = vec3(0.0, 1.0, 2.0 * z.y);
        vec3 L, Lx, Ly;
        for (int c = 0; c < 3; ++c) {
            mat3 M = mat3(V.coef[9 * c + 0] - origin[c], V.coef[9 * c + 1], V.coef[9 * c + 2],
                          V.coef[9 * c + 3], V.coef[9 * c + 4], V.coef[9 * c + 5],
                          V.coef[9 * c + 6], V.coef[9 * c + 7], V.coef[9 * c + 8]);
            vec3 MY = M * Y;
            L[c] = dot(X, MY);
            Lx[c] = dot(dX, MY);
            Ly[c] = dot(X, M * dY);
        }
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
    if (atVertex >= 0) {
        // At a vertex the true limit normal is c_10 × c_01 of its local surface (A.6).
        BlendVertex V = corners[atVertex];
        n = cross(vec3(V.coef[1], V.coef[10], V.coef[19]), vec3(V.coef[3], V.coef[12], V.coef[21]));
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
