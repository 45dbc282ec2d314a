// The blending surface's records and the pieces of its evaluation (paper 001, 3.2-3.5; math.md
// A.1-A.6); blend_eval_impl.glsl evaluates a sample with them.
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

#endif
