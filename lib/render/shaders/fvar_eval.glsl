// Smooth face-varying UVs on the GPU: the UV surface of lib/subdiv/fvar_surface.h
// (FaceVaryingSurface::gpu) at (u, v) of a ptex face. A quadtree per ptex face finds the UV
// element containing the point just inside the drawing element (toward `inside`, by `nudge`,
// 2^-21: far below the finest UV element, 2^-16, so a point on an element's edge picks the
// element on the drawing side and a point inside stays in its own, up to an extrapolation of
// at most 2^-21 across an edge where the pieces join C2); a patch is a bicubic B-spline of 16 UV control points (paper 000, eq. 1; phantoms baked
// in), a bilinear record the blend of its corners' limit UVs. An irregular face is stored as
// the pieces of its surface (docs/irregular.md: sub-patches, and leaves within 2^-K of an
// extraordinary corner, exact at their corners), so this walk reaches the sub-patch there.
// The includer defines where the data lives:
//   uint fvarNode(uint i);    // word i of FaceVaryingSurface::Gpu::nodes
//   vec4 fvarRecord(uint i);  // records[i]
#ifndef LIMN_FVAR_EVAL_GLSL
#define LIMN_FVAR_EVAL_GLSL

void fvarBasis(float t, out float b[4]) {
    float s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    b[0] = s * s * s / 6.0;
    b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    b[3] = t3 / 6.0;
}

vec2 fvarUV(uint ptex, vec2 uv, vec2 inside, float nudge) {
    vec2 probe = clamp(uv + sign(inside - uv) * nudge, vec2(0.0), vec2(1.0));
    vec2 o = vec2(0.0);
    float size = 1.0;
    uint v = fvarNode(ptex);
    for (int depth = 0; depth < 24 && v != 0xFFFFFFFFu && (v & 0x80000000u) == 0u; ++depth) {
        size *= 0.5;
        uvec2 c = uvec2(probe.x >= o.x + size ? 1u : 0u, probe.y >= o.y + size ? 1u : 0u);
        o += vec2(c) * size;
        v = fvarNode(v + c.x + 2u * c.y);
    }
    if (v == 0xFFFFFFFFu || (v & 0x80000000u) == 0u) return vec2(0.0); // a hole
    uint r = 9u * (v & 0x7FFFFFFFu);
    vec4 h = fvarRecord(r);
    float s = (uv.x - h.x) / h.z, t = (uv.y - h.y) / h.z;
    if (h.w != 0.0) { // an irregular face: its corners' limit UVs
        vec4 a = fvarRecord(r + 1u), b = fvarRecord(r + 2u);
        return mix(mix(a.xy, a.zw, s), mix(b.zw, b.xy, s), t);
    }
    float bu[4], bv[4];
    fvarBasis(s, bu);
    fvarBasis(t, bv);
    vec2 x = vec2(0.0);
    for (uint j = 0u; j < 4u; ++j)
        for (uint i = 0u; i < 4u; i += 2u) {
            vec4 p = fvarRecord(r + 1u + (4u * j + i) / 2u); // P_ij, P_(i+1)j
            x += bv[j] * (bu[i] * p.xy + bu[i + 1u] * p.zw);
        }
    return x;
}

#endif
