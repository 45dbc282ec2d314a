// View-adaptive tessellation, pass 3 of 5: per element, its interior rates mu along s
// and mv along t (the larger projected size of the two sides running that way, see
// adaptive_rates.comp; 1 when culled, at most tess; at least 2 for the grid below) and how many
// vertices and triangles it will emit (adaptive_emit.comp): B boundary points (every side's
// segments) plus the (mu-1)(mv-1) interior grid points; 2(mu-2)(mv-2) grid triangles plus
// B + 2(mu-2) + 2(mv-2) in the four zipper strips (mu = mv = 2: one centre point fanned to the
// boundary). A flat element, small enough that one segment across it meets the target both ways,
// is only its boundary polygon: B - 2 triangles fanned from a side's middle point, no interior
// point (packed as rates mu = mv = 1; adaptive_emit.comp). Flat: one segment per side and both
// rates <= 2 (B = 4, a small deep patch: two triangles), or every side one or two pieces of one
// segment each within the target and, each way, one of the two sides a single piece (so the
// element spans at most about one target length: a transition patch beside finer ones, which
// drew a centre point and B triangles before; on the paper's sphere at depth 6, 40% of the
// drawn elements). Separate rates per direction matter on
// patches seen at a grazing angle and on long thin ones (a sphere's polar rings): one square
// rate would cut the short direction as finely as the long one.
//
// A flat element's triangles are exactly what is drawn of it, with corners that
// adaptive_rates.comp projected (its pieces' ends): where the host gives the image's sample
// positions (as for adaptive_cull.comp's between-samples test), a fan triangle that holds none
// of them (widened by 1/16 pixel for the two evaluations' rounding and the rasterizer's snapping)
// is left out, and an element none of whose triangles holds one is culled. The cull's test
// takes a patch's whole hull box; this one the drawn triangles, which drops most sub-pixel
// elements that the box keeps, and single triangles of slightly larger ones (on the paper's
// sphere at depth 6, most drawn elements are around its 34 extraordinary vertices, isolated to
// a fraction of a pixel).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "adaptive_tess.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Elements { AdaptiveElement e[]; } elements;
layout(std430, binding = 1) readonly buffer Pieces { uvec4 v[]; } pieces; // side pieces at el.sideFirst
layout(std430, binding = 2) readonly buffer Rates { uint r[]; } rates;
layout(std430, binding = 3) readonly buffer Cull { uint c[]; } cull;
// Per element: m | culled, V, T, over budget; with shared points, after the elements, per edge
// piece (four a record) where its interior points start among its owner's vertices.
layout(std430, binding = 4) writeonly buffer Info { uvec4 v[]; } info;
layout(std430, binding = 5) readonly buffer PieceEnds { vec4 v[]; } pieceEnds; // pixels (adaptive_rates.comp)

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint tess;
    uint vertexLoops; // the emit pass's loop iterations per vertex beyond its own (smooth UVs)
    uint sharePoints; // adaptive_emit.comp's shared points: an element's vertices are its pieces' and its grid
    uint sampleCount; // the sample positions of the image (0: no test), as adaptive_cull.comp's
    uvec2 samples;
    // Whether a flat element may leave out some of its fan triangles; not where the whole
    // surface is read (--mesh-out), which gets every triangle of an element that draws some.
    uint partialFans;
} pc;

vec2 samplePosition(uint s) { return adaptiveSamplePosition(pc.samples, s); }

// Whether triangle (a, b, c) in pixels, widened by `slack` pixels, may hold a sample position:
// a pixel's corner plus one of the pattern's offsets. Large triangles are kept untested.
bool holdsSample(vec2 a, vec2 b, vec2 c) {
    const float slack = 1.0 / 16.0;
    vec2 lo = min(a, min(b, c)) - slack, hi = max(a, max(b, c)) + slack;
    if (!(hi.x - lo.x < 4.0 && hi.y - lo.y < 4.0)) return true; // large, or not finite
    // Edge functions, positive inside for either winding; each widened by slack times the
    // edge's length, so a sample within `slack` of the triangle counts.
    float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    float w = area < 0.0 ? -1.0 : 1.0;
    vec2 v[3] = vec2[3](a, b, c);
    for (uint s = 0u; s < pc.sampleCount; ++s) {
        vec2 off = samplePosition(s);
        vec2 first = ceil(lo - off), last = floor(hi - off);
        for (float y = first.y; y <= last.y; ++y)
            for (float x = first.x; x <= last.x; ++x) {
                vec2 p = vec2(x, y) + off;
                bool inside = true;
                for (int k = 0; k < 3; ++k) {
                    vec2 p0 = v[k], p1 = v[(k + 1) % 3];
                    vec2 d = p1 - p0;
                    float f = w * (d.x * (p.y - p0.y) - d.y * (p.x - p0.x));
                    inside = inside && f >= -slack * length(d);
                }
                if (inside) return true;
            }
    }
    return false;
}

// Which of a flat element's B - 2 fan triangles (adaptiveFanApex) hold a sample, from its
// boundary points' pixels (at most 8: two pieces of one segment a side); all of them where a
// point has no pixels.
uint drawnFan(AdaptiveElement el, uint B) {
    uint all = adaptiveWholeFan(B);
    if (pc.sampleCount == 0u) return all;
    vec2 px[8];
    uint sideStart[4], sideTotal[4], n = 0u;
    for (uint k = 0u; k < 4u; ++k) {
        sideStart[k] = n;
        for (uint p = 0u; p < el.sideCount[k] && n < 8u; ++p) {
            uvec4 sp = pieces.v[el.sideFirst[k] + p];
            vec4 ends = pieceEnds.v[sp.x];
            px[n++] = (sp.z & 1u) != 0u ? ends.zw : ends.xy; // where this side's piece starts
        }
        sideTotal[k] = n - sideStart[k];
    }
    for (uint i = 0u; i < n; ++i)
        if (!(abs(px[i].x) < 1e6 && abs(px[i].y) < 1e6)) return all;
    uint apex = adaptiveFanApex(sideStart, sideTotal), fan = 0u;
    for (uint i = 0u; i + 2u < B; ++i)
        if (holdsSample(px[apex], px[(apex + i + 1u) % B], px[(apex + i + 2u) % B])) fan |= 1u << i;
    return fan;
}

// lavapipe (llvmpipe) ends every loop of a shader invocation once all its loops together have
// run 65535 iterations (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, shared by every loop of a
// shader); an element whose emit (adaptive_emit.comp: one invocation) ran past that wrote only
// part of its triangles, leaving holes in close views at --tess 256 and more. So an element's
// interior rates are lowered until its estimated loop count fits kEmitLoopBudget (with room for
// the SIMD lanes running in step); one whose boundary alone does not fit is flagged in info.w,
// and the scan reports the frame as an overflow (the host warns: raise --max-error or
// --edge-pixels, or lower --tess). Other GPUs have no such limit; the cap keeps one invocation's
// work bounded there too.
const uint kEmitLoopBudget = 24576u;
uint emitLoops(uint B, uint mu, uint mv) {
    uint grid = (mu - 1u) * (mv - 1u), cells = (mu - 2u) * (mv - 2u);
    return B * (2u + pc.vertexLoops) + grid * (1u + pc.vertexLoops) + cells + 2u * mu + 3u * mv + 16u;
}

void main() {
    uint e = limnInvocationIndex(pc.limnRowInvocations);
    if (e >= pc.limnCount) return;
    AdaptiveElement el = elements.e[e];
    uint B = 0u, most[2] = uint[2](1u, 1u); // along s (sides 0, 2), along t (sides 1, 3)
    bool flatSides = true, singleSide[2] = bool[2](false, false);
    uint owned = 0u; // shared points: the interior points of the pieces this element owns
    for (int k = 0; k < 4; ++k) {
        uint side = 0u, size = 0u;
        for (uint p = 0u; p < el.sideCount[k]; ++p) {
            uvec4 sp = pieces.v[el.sideFirst[k] + p];
            uint r = rates.r[sp.x];
            if (pc.sharePoints != 0u && (sp.z & 2u) != 0u) { // the owner's side of the piece
                info.v[pc.limnCount + sp.x / 4u][sp.x % 4u] = owned;
                owned += (r & 0xFFFFu) - 1u;
            }
            side += r & 0xFFFFu;
            size += r >> 16;
            flatSides = flatSides && r == (1u | (1u << 16));
        }
        B += side;
        most[k & 1] = max(most[k & 1], size);
        singleSide[k & 1] = singleSide[k & 1] || el.sideCount[k] == 1u;
        flatSides = flatSides && el.sideCount[k] <= 2u;
    }
    bool culled = cull.c[e] != 0u;
    uint cap = max(pc.tess, 1u);
    uint mu = culled ? 2u : clamp(most[0], 2u, max(cap, 2u));
    uint mv = culled ? 2u : clamp(most[1], 2u, max(cap, 2u));
    for (uint k = 0u; k < 64u && emitLoops(B, mu, mv) > kEmitLoopBudget && (mu > 2u || mv > 2u); ++k) {
        if (mu >= mv) mu = max(2u, mu - max(1u, mu / 4u));
        else mv = max(2u, mv - max(1u, mv / 4u));
    }
    uint overBudget = emitLoops(B, mu, mv) > kEmitLoopBudget ? 1u : 0u;
    bool flatElement = (B == 4u && mu == 2u && mv == 2u) ||
                (!culled && flatSides && singleSide[0] && singleSide[1]);
    uint fan = 0u;
    if (flatElement && !culled) {
        fan = drawnFan(el, B);
        if (fan == 0u) culled = true, mu = 2u, mv = 2u, flatElement = B == 4u; // nothing drawn
        else if (pc.partialFans == 0u) fan = adaptiveWholeFan(B);
    }
    if (flatElement && culled) fan = adaptiveWholeFan(B); // emitted whole for --mesh-out
    uint V = B + (flatElement ? 0u : (mu - 1u) * (mv - 1u));
    uint T = flatElement ? uint(bitCount(fan)) : 2u * (mu - 2u) * (mv - 2u) + B + 2u * (mu - 2u) + 2u * (mv - 2u);
    if (pc.sharePoints != 0u) {
        // Its boundary is drawn from shared slots: the points', and each piece's interior
        // points written once, by the piece's owner (adaptive_emit.comp), also when the owner
        // itself is culled or flat (a piece next to a drawn element has a rate above 1).
        V = owned + (flatElement || culled ? 0u : (mu - 1u) * (mv - 1u));
        if (culled) T = 0u; // drawn by nobody, and nothing reads the whole surface
    }
    uint packed = flatElement ? adaptivePackFlat(fan) : adaptivePackRates(mu, mv);
    info.v[e] = uvec4(packed | (culled ? ADAPTIVE_CULLED : 0u), V, T, overBudget);
}
