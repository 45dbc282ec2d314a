// View-adaptive tessellation, pass 4 of 5: one workgroup of 256 turns every element's
// vertex and triangle counts into offsets (an exclusive prefix sum: each invocation sums a
// contiguous chunk, a Hillis-Steele scan of the chunk sums in shared memory, then each chunk is
// walked again). Integer sums in a fixed order: the same offsets every run, no atomics. Visible
// elements' triangles come first (the draw draws those), culled ones after them (only --mesh-out
// reads them). Writes the indirect draw and dispatch arguments and the totals.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "adaptive_tess.glsl"
layout(local_size_x = 256) in;

layout(std430, binding = 0) buffer Info { uvec4 v[]; } info;  // in: m | culled, V, T; out: offsets
layout(std430, binding = 1) writeonly buffer Totals { uint t[]; } totals;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint elementCount;
    uint vertexCapacity;
    uint triangleCapacity;
    uint rowGroups;     // dispatch rows for the evaluation pass (65535 groups)
    uint evalGroupSize; // its workgroup size
    uint vertexBase;    // the first element vertex: the shared points' slots come first
} pc;

shared uint sumV[256], sumTv[256], sumTc[256];
shared uint overBudget; // an element over adaptive_counts.comp's loop budget: an overflow

// Sums saturate at 2^31 - 1, above any capacity (128 MiB buffers), so that a view asking for
// more than 32 bits of vertices or triangles (at --tess 4096, a few hundred elements at full
// rate) is reported as an overflow instead of wrapping around into small, overlapping offsets.
// Every element's own counts are below 2^26 (adaptive_counts.comp: rates of at most 4096).
const uint kSaturated = 0x7FFFFFFFu;
uint satAdd(uint a, uint b) { return a >= kSaturated - min(b, kSaturated) ? kSaturated : a + b; }

void main() {
    uint lid = gl_LocalInvocationID.x;
    uint n = pc.elementCount;
    uint chunk = (n + 255u) / 256u;
    uint begin = min(lid * chunk, n), end = min(begin + chunk, n);
    uint v = 0u, tv = 0u, tc = 0u, over = 0u;
    if (lid == 0u) overBudget = 0u;
    barrier();
    for (uint e = begin; e < end; ++e) {
        uvec4 x = info.v[e];
        over |= x.w;
        v = satAdd(v, x.y);
        if ((x.x & ADAPTIVE_CULLED) != 0u) tc = satAdd(tc, x.z); else tv = satAdd(tv, x.z);
    }
    sumV[lid] = v, sumTv[lid] = tv, sumTc[lid] = tc;
    if (over != 0u) atomicOr(overBudget, 1u);
    barrier();
    for (uint d = 1u; d < 256u; d <<= 1u) {
        uint a = 0u, b = 0u, c = 0u;
        if (lid >= d) a = sumV[lid - d], b = sumTv[lid - d], c = sumTc[lid - d];
        barrier();
        sumV[lid] = satAdd(sumV[lid], a), sumTv[lid] = satAdd(sumTv[lid], b), sumTc[lid] = satAdd(sumTc[lid], c);
        barrier();
    }
    uint totalV = satAdd(pc.vertexBase, sumV[255]), totalTv = sumTv[255], totalTc = sumTc[255];
    // Exclusive offsets from the previous chunk's inclusive sums (no subtraction: saturated).
    uint ov = satAdd(pc.vertexBase, lid == 0u ? 0u : sumV[lid - 1u]), otv = lid == 0u ? 0u : sumTv[lid - 1u];
    uint otc = satAdd(totalTv, lid == 0u ? 0u : sumTc[lid - 1u]);
    for (uint e = begin; e < end; ++e) {
        uvec4 x = info.v[e];
        bool culled = (x.x & ADAPTIVE_CULLED) != 0u;
        uint to = culled ? otc : otv;
        uint fits = (x.w == 0u && (ov <= pc.vertexCapacity && x.y <= pc.vertexCapacity - ov) && (to <= pc.triangleCapacity && x.z <= pc.triangleCapacity - to)) ? 1u : 0u;
        info.v[e] = uvec4(x.x, ov, to, x.z | (fits << 31));
        ov = satAdd(ov, x.y);
        if (culled) otc = satAdd(otc, x.z); else otv = satAdd(otv, x.z);
    }
    if (lid == 0u) {
        uint drawn = min(totalTv, pc.triangleCapacity);
        uint evaluated = min(totalV, pc.vertexCapacity);
        uint groups = (evaluated + pc.evalGroupSize - 1u) / pc.evalGroupSize;
        // drawIndexedIndirect: indexCount, instanceCount, firstIndex, vertexOffset, firstInstance
        totals.t[0] = 3u * drawn, totals.t[1] = 1u, totals.t[2] = 0u, totals.t[3] = 0u, totals.t[4] = 0u;
        // drawIndirect (--shade levels pulls its indices): vertexCount, instanceCount, first, first
        totals.t[5] = 3u * drawn, totals.t[6] = 1u, totals.t[7] = 0u, totals.t[8] = 0u;
        // dispatchIndirect of the evaluation pass
        totals.t[9] = min(groups, pc.rowGroups);
        totals.t[10] = groups == 0u ? 0u : (groups + pc.rowGroups - 1u) / pc.rowGroups;
        totals.t[11] = 1u;
        totals.t[12] = totalV, totals.t[13] = totalTv, totals.t[14] = totalTc;
        totals.t[15] = (overBudget != 0u || totalV > pc.vertexCapacity || satAdd(totalTv, totalTc) > pc.triangleCapacity) ? 1u : 0u;
        totals.t[16] = min(satAdd(totalTv, totalTc), pc.triangleCapacity);
        totals.t[17] = evaluated;
        // drawIndirect of --wire (wire_triangles.vert): two line vertices per triangle edge
        totals.t[18] = 6u * drawn, totals.t[19] = 1u, totals.t[20] = 0u, totals.t[21] = 0u;
        totals.t[22] = overBudget;
        totals.t[23] = 0u; // set by adaptive_emit.comp where an element's emit stops short
    }
}
