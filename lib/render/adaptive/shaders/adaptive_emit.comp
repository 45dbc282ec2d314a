// View-adaptive tessellation, pass 5 of 5: each element writes its vertices and
// triangles at the offsets of adaptive_scan.comp. The draw (and the evaluation pass) then read
// them like the fixed tessellation of lib/tess: a vertex is (element, s, t, own-chart UV).
//
// Boundary: counter-clockwise, per side, per edge piece: the piece's start point (one owner per
// point: its owner's element and corner parameters), then the piece's interior points at the
// piece's rate, named by the *piece owner's* element and parameters (computed from the owner's
// two end parameters and the point's index in the owner's direction). Both sides of a piece so
// write the same (element, s, t) for each shared point, and the evaluation turns those into the
// same bits: watertight to the bit without sharing indices across elements (and with shared
// points, pc.sharePoints, both draw the one slot the owner wrote). A coarse side next
// to two finer patches has two pieces, so level transitions meet point to point (no T-junction).
// Interior (rates mu along s, mv along t, each >= 2): two triangles when both are 2 and the
// boundary is the four corners; otherwise the (mu-1)(mv-1) grid points (i/mu, j/mv) (one centre
// point when both are 2), the (mu-2)(mv-2) grid cells, and per side a zipper strip joining the
// side's boundary points to the grid's outer ring on that side, merged in parameter order
// (deterministic). Across the crease of a single-crease patch the points are graded towards the
// crease (gradedOffset in adaptive_tess.glsl), on its sides (pieces it owns) and in its grid.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "limn_compute.glsl"
#include "adaptive_tess.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Elements { AdaptiveElement e[]; } elements;
layout(std430, binding = 1) buffer Totals { uint t[]; } totals; // [23]: an element cut short
layout(std430, binding = 2) readonly buffer Pieces { uvec4 v[]; } pieces; // pieces, then points
layout(std430, binding = 3) readonly buffer Rates { uint r[]; } rates;
layout(std430, binding = 4) readonly buffer Info { uvec4 v[]; } info; // + per piece, shared points
layout(std430, binding = 5) writeonly buffer TessVertices { uvec4 v[]; } tessVertices;
layout(std430, binding = 6) writeonly buffer Triangles { uint i[]; } triangles;
layout(std430, binding = 7) writeonly buffer TriangleLevels { uint l[]; } triangleLevels;

layout(push_constant) uniform Push {
    LIMN_DISPATCH_HEADER
    layout(offset = 16) uint pointBase; // first point record in `pieces`
    uint triangleCapacity;
    // Smooth UVs: with smoothUV = 1, `pieces` also holds, from domainBase, per element
    // (ptex, u0, v0, size) (floats as bits), from nodeBase the quadtree (4 words a record), from
    // recordBase the records of fvar_eval.glsl (WebGPU allows 8 storage buffers a pass: this
    // pass has them all). fvarCell: fvar_eval.glsl's nudge.
    uint smoothUV;
    float fvarCell;
    uint domainBase, nodeBase, recordBase;
    // Shared points (AdaptiveOptions::sharePoints): vertex slot i < the number of points is point
    // i, written by its owner; a piece's interior points are written once, by the piece's owner,
    // first among its own vertices (at the offset adaptive_counts.comp put after the elements'
    // records in `info`). Every element draws its boundary from those slots; culled ones emit
    // nothing but the points and piece points they own.
    uint sharePoints;
    uint vertexCapacity;
    // Per-pixel normals (AdaptiveOptions::pixelNormals, never with sharePoints): each vertex
    // carries, in place of its UV, the emitting element and its own (s, t) there (1/32768,
    // s | t << 16), so that the fragment stage evaluates the element's normal at the
    // interpolated (s, t) of the triangle's own element (a side point is named by the piece
    // owner's element, which the neighbour's triangles share).
    uint pixelNormals;
} pc;

uint fvarNode(uint i) { return pieces.v[pc.nodeBase + i / 4u][i % 4u]; }
vec4 fvarRecord(uint i) { return uintBitsToFloat(pieces.v[pc.recordBase + i]); }
#include "fvar_eval.glsl"

AdaptiveElement el;
uint elIndex, vBase, tNext, level;

// The emitting element's own-chart UV at its (s, t): smooth (the face-varying surface at the
// point, from inside this element) or bilinear in its corners' UVs (rule "all").
vec2 uvAt(float s, float t) {
    if (pc.smoothUV != 0u) {
        uvec4 q = pieces.v[pc.domainBase + elIndex];
        vec3 d = uintBitsToFloat(q.yzw);
        vec2 at = d.xy + vec2(s, t) * d.z, centre = d.xy + vec2(0.5 * d.z);
        return fvarUV(q.x, at, centre, pc.fvarCell);
    }
    return mix(mix(el.uv[0], el.uv[1], s), mix(el.uv[3], el.uv[2], s), t);
}

// This element's (s, t) at parameter x (1/32768) along side k.
vec2 sideParam(uint k, float x) {
    float p = x / 32768.0;
    if (k == 0u) return vec2(p, 0.0);
    if (k == 1u) return vec2(1.0, p);
    if (k == 2u) return vec2(1.0 - p, 1.0);
    return vec2(0.0, 1.0 - p);
}

// A vertex of this element: the point (element, st) drawn, at this element's own (s, t) = own
// (its UV there, or with per-pixel normals the element and own (s, t) themselves).
void vertex(uint local, uint element, uint st, vec2 own) {
    uvec2 extra;
    if (pc.pixelNormals != 0u) {
        uvec2 q = uvec2(clamp(own, 0.0, 1.0) * 32768.0 + 0.5);
        extra = uvec2(elIndex, q.x | (q.y << 16));
    } else {
        extra = floatBitsToUint(uvAt(own.x, own.y));
    }
    tessVertices.v[vBase + local] = uvec4(element, st, extra);
}

// A triangle of vertex slots (absolute), and of this element's own vertices (local).
void triSlots(uint a, uint b, uint c) {
    triangles.i[3u * tNext] = a;
    triangles.i[3u * tNext + 1u] = b;
    triangles.i[3u * tNext + 2u] = c;
    triangleLevels.l[tNext] = level;
    ++tNext;
}
void tri(uint a, uint b, uint c) { triSlots(vBase + a, vBase + b, vBase + c); }

// Point j of r along a piece from st a to st b (integers, so every side computes the same).
uint lerpST(uint a, uint b, uint j, uint r) {
    int sa = int(a & 0xFFFFu), sb = int(b & 0xFFFFu), ta = int(a >> 16), tb = int(b >> 16);
    int s = sa + ((sb - sa) * int(j)) / int(r), t = ta + ((tb - ta) * int(j)) / int(r);
    return uint(s) | (uint(t) << 16);
}

// Point j of r along a piece whose owner is a single-crease patch and which runs across its
// crease: graded towards the crease end (gradedOffset), from the owner's record alone, so both
// users write the same (element, st). `along` is the point's fraction of the piece in the
// owner's direction. Other pieces: lerpST, along = -1 (the caller keeps its even fractions).
uint pieceST(uvec4 piece, uint j, uint r, out float along) {
    along = -1.0;
    uint c = elements.e[piece.x].crease, a = piece.y, b = piece.z;
    bool runsS = (a & 0xFFFFu) != (b & 0xFFFFu);
    if (c == 0u || runsS != creaseAcrossS(c)) return lerpST(a, b, j, r);
    uint sh = runsS ? 0u : 16u;
    uint ca = (a >> sh) & 0xFFFFu, cb = (b >> sh) & 0xFFFFu;
    uint D = max(ca, cb) - min(ca, cb);
    bool fromA = creaseAtZero(c) ? ca < cb : ca > cb; // the piece starts at its crease end
    uint off = fromA ? gradedOffset(D, j, r) : D - gradedOffset(D, r - j, r);
    uint x = cb > ca ? ca + off : ca - off;
    along = float(off) / float(D);
    return (a & ~(0xFFFFu << sh)) | (x << sh);
}

// Where st (a point of the piece, in its owner's 1/32768) lies along the piece from its first
// end (0) to its second (1).
float pieceFraction(uvec4 piece, uint st) {
    uint a = piece.y, b = piece.z;
    uint sh = (a & 0xFFFFu) != (b & 0xFFFFu) ? 0u : 16u;
    int ca = int((a >> sh) & 0xFFFFu), cb = int((b >> sh) & 0xFFFFu), cx = int((st >> sh) & 0xFFFFu);
    return float(cx - ca) / float(cb - ca);
}

// Interior grid coordinate i of m along one direction, graded towards a crease at 0 or at 1.
uint gridCoord(uint i, uint m, bool graded, bool atZero) {
    if (!graded) return (i * 32768u) / m;
    return atZero ? gradedOffset(32768u, i, m) : 32768u - gradedOffset(32768u, m - i, m);
}

// Ring point x along side k of the interior grid (the zipper strips' other side), as a local
// vertex. Not a loop over the two a zipper step needs: every loop iteration counts against
// lavapipe's limit (adaptive_counts.comp's budget).
uint ringPoint(uint k, uint x, uint mu, uint mv, uint grid) {
    uint gi, gj;
    if (k == 0u) gi = 1u + x, gj = 1u;
    else if (k == 1u) gi = mu - 1u, gj = 1u + x;
    else if (k == 2u) gi = mu - 1u - x, gj = mv - 1u;
    else gi = 1u, gj = mv - 1u - x;
    return grid + (gj - 1u) * (mu - 1u) + (gi - 1u);
}

// Shared points: the vertex slot of boundary point x of side k (x = the side's point count: the
// next side's first point), for x = 0, 1, 2, ... in turn. A point's own slot, or one of a piece's
// interior points in its owner's vertices; the side's current piece is kept across calls.
uint curPiece, curStart, curRate, curBase;
uvec4 curSide;
void loadSidePiece(uint k) {
    curSide = pieces.v[el.sideFirst[k] + curPiece];
    curRate = rates.r[curSide.x] & 0xFFFFu;
    uint owner = pieces.v[2u * curSide.x].x;
    curBase = info.v[owner].y + info.v[pc.limnCount + curSide.x / 4u][curSide.x % 4u];
}
uint sharedSlot(uint k, uint x, uint total) {
    if (x == total) return pieces.v[el.sideFirst[(k + 1u) & 3u]].y;
    if (x == 0u) curPiece = 0u, curStart = 0u, loadSidePiece(k);
    else if (x >= curStart + curRate) curStart += curRate, ++curPiece, loadSidePiece(k);
    uint i = x - curStart;
    if (i == 0u) return curSide.y;
    return curBase + ((curSide.z & 1u) != 0u ? curRate - i : i) - 1u;
}

void emitElement(uint e) {
    uvec4 inf = info.v[e];
    uvec2 rates2 = adaptiveRates(inf.x);
    uint mu = rates2.x, mv = rates2.y;
    uint T = inf.w & 0x7FFFFFFFu;
    vBase = inf.y;
    tNext = inf.z;
    bool share = pc.sharePoints != 0u;
    uint owned = 0u; // shared points: this element's vertices that are its pieces' points
    if (share) {
        // The points and the pieces' interior points this element owns, into their slots
        // (before the capacity test: other elements draw them; an owner comes before every
        // other user of its pieces, so their vertices fit where the owner's do).
        el = elements.e[e];
        elIndex = e;
        for (uint k = 0u; k < 4u; ++k)
            for (uint p = 0u; p < el.sideCount[k]; ++p) {
                uvec4 sp = pieces.v[el.sideFirst[k] + p];
                uvec4 point = pieces.v[pc.pointBase + sp.y];
                float from = float(sp.w & 0xFFFFu), to = float(sp.w >> 16);
                if (point.x == e) {
                    vec2 st = sideParam(k, from);
                    vec2 uv = uvAt(st.x, st.y);
                    tessVertices.v[sp.y] = uvec4(point.x, point.y, floatBitsToUint(uv.x), floatBitsToUint(uv.y));
                }
                if ((sp.z & 2u) == 0u) continue; // not the piece's owner side
                uint r = rates.r[sp.x] & 0xFFFFu;
                if (vBase + owned + r - 1u > pc.vertexCapacity) break; // an overflow (the host warns)
                uvec4 piece = pieces.v[2u * sp.x];
                for (uint i = 1u; i < r; ++i) {
                    float along;
                    uint ownerST = pieceST(piece, i, r, along);
                    if (along < 0.0 && pc.smoothUV != 0u) along = pieceFraction(piece, ownerST);
                    vec2 st = sideParam(k, from + (to - from) * (along < 0.0 ? float(i) / float(r) : along));
                    vec2 uv = uvAt(st.x, st.y);
                    tessVertices.v[vBase + owned + i - 1u] = uvec4(e, ownerST, floatBitsToUint(uv.x), floatBitsToUint(uv.y));
                }
                owned += r - 1u;
            }
        if ((inf.x & ADAPTIVE_CULLED) != 0u) return;
    }
    if ((inf.w >> 31) == 0u) {
        // Over capacity (the host warns): the part of its triangle range that exists is
        // degenerate, so the draw reads nothing stale.
        for (uint i = 0u; i < T && tNext + i < pc.triangleCapacity; ++i) {
            triangles.i[3u * (tNext + i)] = 0u;
            triangles.i[3u * (tNext + i) + 1u] = 0u;
            triangles.i[3u * (tNext + i) + 2u] = 0u;
            triangleLevels.l[tNext + i] = 0u;
        }
        return;
    }
    el = elements.e[e];
    elIndex = e;
    level = el.level;

    // The boundary loop. With shared points only its length (the slots are the owners'); a
    // flat element keeps its points' slots (at most 8: two pieces of one segment a side).
    bool sharedFlat = share && mu == 1u;
    uint slots[8];
    uint sideStart[4], sideTotal[4];
    uint B = 0u;
    for (uint k = 0u; k < 4u; ++k) {
        sideStart[k] = B;
        for (uint p = 0u; p < el.sideCount[k]; ++p) {
            uvec4 sp = pieces.v[el.sideFirst[k] + p];
            if (sharedFlat) {
                slots[min(B, 7u)] = sp.y;
                ++B;
                continue;
            }
            uint r = rates.r[sp.x] & 0xFFFFu;
            if (share) {
                B += r;
                continue;
            }
            uvec4 piece = pieces.v[2u * sp.x];
            uvec4 point = pieces.v[pc.pointBase + sp.y];
            float from = float(sp.w & 0xFFFFu), to = float(sp.w >> 16);
            vec2 st = sideParam(k, from);
            vertex(B++, point.x, point.y, st);
            for (uint i = 1u; i < r; ++i) {
                uint j = (sp.z & 1u) != 0u ? r - i : i;
                float along;
                uint ownerST = pieceST(piece, j, r, along);
                // Smooth UVs at the point drawn: its fraction of the piece as rounded to the
                // owner's 1/32768 (a surface, unlike rule "all"'s bilinear charts, would show the
                // difference, up to 2^-15 of an element).
                if (along < 0.0 && pc.smoothUV != 0u) along = pieceFraction(piece, ownerST);
                float f = along < 0.0 ? float(i) / float(r) : ((sp.z & 1u) != 0u ? 1.0 - along : along);
                st = sideParam(k, from + (to - from) * f);
                vertex(B++, piece.x, ownerST, st);
            }
        }
        sideTotal[k] = B - sideStart[k];
    }

    if (mu == 1u) { // flat (adaptive_counts.comp): its boundary polygon, the fan's drawn triangles
        uint apex = adaptiveFanApex(sideStart, sideTotal), fan = mv;
        for (uint i = 1u; i + 1u < B; ++i) {
            if (((fan >> (i - 1u)) & 1u) == 0u) continue; // covers no sample
            uint a = apex, b = (apex + i) % B, c = (apex + i + 1u) % B;
            if (sharedFlat) triSlots(slots[a], slots[b], slots[c]);
            else tri(a, b, c);
        }
        return;
    }
    // Interior grid points (i, j), 1 <= i <= mu-1, 1 <= j <= mv-1, at grid + (j-1)(mu-1) + (i-1)
    // (after the boundary, or with shared points after the owned pieces' points). Across a
    // single-crease patch's crease the grid is graded towards it, like its sides.
    uint grid = share ? owned : B;
    bool gradeS = el.crease != 0u && creaseAcrossS(el.crease), gradeT = el.crease != 0u && !gradeS;
    bool atZero = creaseAtZero(el.crease);
    for (uint j = 1u; j < mv; ++j)
        for (uint i = 1u; i < mu; ++i) {
            uint s = gridCoord(i, mu, gradeS, atZero), t = gridCoord(j, mv, gradeT, atZero);
            vec2 f = vec2(gradeS ? float(s) / 32768.0 : float(i) / float(mu),
                          gradeT ? float(t) / 32768.0 : float(j) / float(mv));
            if (pc.smoothUV != 0u) f = vec2(float(s), float(t)) / 32768.0; // the point drawn
            vertex(grid + (j - 1u) * (mu - 1u) + (i - 1u), e, s | (t << 16), f);
        }
    for (uint j = 1u; j + 1u < mv; ++j)
        for (uint i = 1u; i + 1u < mu; ++i) {
            uint a = grid + (j - 1u) * (mu - 1u) + (i - 1u);
            tri(a, a + 1u, a + mu);
            tri(a, a + mu, a + mu - 1u);
        }
    // Zipper strips: side k's boundary points against the grid's outer ring on that side (sides
    // 0 and 2 run along s, mu - 2 ring steps; sides 1 and 3 along t, mv - 2).
    for (uint k = 0u; k < 4u; ++k) {
        uint na = sideTotal[k], nb = (k & 1u) == 0u ? mu - 2u : mv - 2u, ia = 0u, jb = 0u;
        uint a0 = share ? sharedSlot(k, 0u, na) : vBase + sideStart[k];
        while (ia < na || jb < nb) {
            uint g0 = vBase + ringPoint(k, jb, mu, mv, grid), g1 = vBase + ringPoint(k, jb + 1u, mu, mv, grid);
            bool advanceA = jb == nb || (ia < na && (2u * ia + 1u) * nb <= (2u * jb + 1u) * na);
            if (advanceA) {
                uint a1 = share ? sharedSlot(k, ia + 1u, na) : vBase + (sideStart[k] + ia + 1u) % B;
                triSlots(a0, a1, g0);
                a0 = a1;
                ++ia;
            } else {
                triSlots(a0, g1, g0);
                ++jb;
            }
        }
    }
}

void main() {
    uint e = limnInvocationIndex(pc.limnRowInvocations);
    if (e >= pc.limnCount) return;
    emitElement(e);
    // An element that fits has written all its T triangles, unless lavapipe's loop limit ended
    // its loops early (adaptive_counts.comp's budget estimates them, and the estimate has been
    // short: close views at --tess 2048 left unwritten, (0, 0, 0) triangles in --mesh-out with
    // no warning). Then the frame is reported like an overflow: the host warns, --mesh-out
    // refuses.
    uvec4 inf = info.v[e];
    if ((inf.w >> 31) != 0u && tNext != inf.z + (inf.w & 0x7FFFFFFFu)) atomicOr(totals.t[23], 1u);
}
