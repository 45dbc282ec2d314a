// The fixed watertight tessellation limn-render draws with --edge-pixels 0: a port of
// lib/tess/tessellation.cpp (buildTessellation) and lib/topology/ptex.cpp (PtexMap), which it must
// match vertex for vertex and triangle for triangle, because the vertex stage evaluates each vertex
// from its (element, s, t) and the image comparisons with limn-render expect the same triangles.
// Every surface point has one owner (element order), shared points are shared vertices, finer
// neighbours' edge points are stitched into coarser elements (no T-junctions), and with UVs a
// point whose faces give it different UVs gets one vertex per UV, sharing the first's (element,
// s, t) so that every copy evaluates to the same bits.

import { SmoothChartUVs } from './smooth_uvs.mjs';

export const TESS_ONE = 32768;
const NONE = 0xffffffff;

// OpenSubdiv's ptex faces: one per quad, n per n-gon (sub-face k).
export class PtexMap {
  constructor(mesh, R) {
    this.mesh = mesh;
    this.R = R;
    this.face = [];
    this.sub = [];
    for (let f = 0; f < mesh.faceCount; f++) {
      const n = mesh.faceSizes[f];
      if (n === 4) { this.face.push(f); this.sub.push(-1); } else for (let k = 0; k < n; k++) { this.face.push(f); this.sub.push(k); }
    }
    // Undirected edges by vertex pair; any numbering does, keys only need to be equal for equal points.
    this.edges = new Map();
    this.edgeFaces = [];
    this.edgeCorners = []; // per edge and face: the corner the face's side of the edge starts at
    this.vertexFaces = Array.from({ length: mesh.vertexCount }, () => []);
    this.vertexCorners = Array.from({ length: mesh.vertexCount }, () => []); // the vertex's corner in each
    const { faceOffsets: off, faceVertices: fv } = mesh;
    for (let f = 0; f < mesh.faceCount; f++) {
      const n = off[f + 1] - off[f];
      for (let i = 0; i < n; i++) {
        const a = fv[off[f] + i], b = fv[off[f] + ((i + 1) % n)];
        const k = a < b ? a * mesh.vertexCount + b : b * mesh.vertexCount + a;
        let e = this.edges.get(k);
        if (e === undefined) { e = this.edgeFaces.length; this.edges.set(k, e); this.edgeFaces.push([]); this.edgeCorners.push([]); }
        this.edgeFaces[e].push(f);
        this.edgeCorners[e].push(i);
        this.vertexFaces[a].push(f);
        this.vertexCorners[a].push(i);
      }
    }
    // Keys as numbers while they fit in 53 bits (depth <= 9), else strings; kindOf undoes them.
    const bits = Math.ceil(Math.log2(2 * R + 1));
    if (30 + 2 * bits <= 53) {
      const s = 2 ** bits, kindUnit = 2 ** (27 + 2 * bits);
      this.makeKey = (kind, id, a, b) => ((kind * 2 ** 27 + id) * s + a) * s + b;
      this.kindOf = (k) => Math.floor(k / kindUnit);
    } else {
      this.makeKey = (kind, id, a, b) => `${kind},${id},${a},${b}`;
      this.kindOf = (k) => Number(k.split(',')[0]);
    }
  }

  findEdge(a, b) {
    const V = this.mesh.vertexCount;
    return this.edges.get(a < b ? a * V + b : b * V + a);
  }

  faceVerts(f) {
    return this.mesh.faceVertices.subarray(this.mesh.faceOffsets[f], this.mesh.faceOffsets[f + 1]);
  }

  onEdge(a, b, t) {
    if (t === 0) return this.makeKey(1, a, 0, 0);
    if (t === 2 * this.R) return this.makeKey(1, b, 0, 0);
    const e = this.findEdge(a, b);
    if (a > b) t = 2 * this.R - t;
    return this.makeKey(2, e, t, 0);
  }

  key(p, U, V) {
    const R = this.R;
    if (U > 0 && U < R && V > 0 && V < R) return this.makeKey(0, p, U, V);
    const f = this.face[p], sub = this.sub[p], fv = this.faceVerts(f);
    if (sub < 0) {
      if (V === 0) return this.onEdge(fv[0], fv[1], 2 * U);
      if (U === R) return this.onEdge(fv[1], fv[2], 2 * V);
      if (V === R) return this.onEdge(fv[3], fv[2], 2 * U);
      return this.onEdge(fv[0], fv[3], 2 * V);
    }
    const n = fv.length, k = sub;
    if (V === 0) return this.onEdge(fv[k], fv[(k + 1) % n], U);
    if (U === 0) return this.onEdge(fv[k], fv[(k + n - 1) % n], V);
    if (U === R && V === R) return this.makeKey(4, f, 0, 0);
    if (U === R) return this.makeKey(3, f, k, V);
    return this.makeKey(3, f, (k + n - 1) % n, U);
  }

  uvAt(f, i) {
    const { uvs, faceOffsets } = this.mesh;
    const j = uvs.indices[faceOffsets[f] + i];
    return [uvs.values[2 * j], uvs.values[2 * j + 1]];
  }

  ownUV(p, u, v) {
    // Allocation-free (it runs for every tessellation vertex): the corners' UVs are read in place.
    const f = this.face[p], sub = this.sub[p], n = this.mesh.faceSizes[f];
    const { uvs, faceOffsets } = this.mesh, ix = uvs.indices, val = uvs.values, o = faceOffsets[f];
    const w0 = (1 - u) * (1 - v), w1 = u * (1 - v), w2 = u * v, w3 = (1 - u) * v;
    if (sub < 0) {
      const a = 2 * ix[o], b = 2 * ix[o + 1], c = 2 * ix[o + 2], d = 2 * ix[o + 3];
      return [w0 * val[a] + w1 * val[b] + w2 * val[c] + w3 * val[d],
        w0 * val[a + 1] + w1 * val[b + 1] + w2 * val[c + 1] + w3 * val[d + 1]];
    }
    const k = sub;
    // Each n-gon's UV sums once (ptex.cpp's centroidUV_): summed per point, an n-gon of thousands
    // of sides cost its square.
    if (!this.uvSums) {
      this.uvSums = new Float64Array(2 * this.mesh.faceCount);
      for (let g = 0; g < this.mesh.faceCount; g++) {
        const og = faceOffsets[g], ng = this.mesh.faceSizes[g];
        if (ng === 4) continue;
        let sx = 0, sy = 0;
        for (let i = 0; i < ng; i++) { const q = 2 * ix[og + i]; sx += val[q]; sy += val[q + 1]; }
        this.uvSums[2 * g] = sx;
        this.uvSums[2 * g + 1] = sy;
      }
    }
    const cx = this.uvSums[2 * f], cy = this.uvSums[2 * f + 1];
    const a = 2 * ix[o + k], b = 2 * ix[o + ((k + 1) % n)], d = 2 * ix[o + ((k + n - 1) % n)];
    const c1x = 0.5 * (val[a] + val[b]), c1y = 0.5 * (val[a + 1] + val[b + 1]);
    const c3x = 0.5 * (val[d] + val[a]), c3y = 0.5 * (val[d + 1] + val[a + 1]);
    return [w0 * val[a] + w1 * c1x + w2 * (cx / n) + w3 * c3x, w0 * val[a + 1] + w1 * c1y + w2 * (cy / n) + w3 * c3y];
  }

  // The point's UV in every base face containing it, in increasing face order.
  charts(p, U, V) {
    const R = this.R, f = this.face[p], sub = this.sub[p], fv = this.faceVerts(f);
    const u = U / R, v = V / R;
    const inside = U > 0 && U < R && V > 0 && V < R;
    let a = NONE, b = NONE, t = 0;
    if (!inside) {
      if (sub < 0) {
        if (V === 0) { a = fv[0]; b = fv[1]; t = u; } else if (U === R) { a = fv[1]; b = fv[2]; t = v; } else if (V === R) { a = fv[3]; b = fv[2]; t = u; } else { a = fv[0]; b = fv[3]; t = v; }
      } else {
        const n = fv.length, k = sub;
        if (V === 0) { a = fv[k]; b = fv[(k + 1) % n]; t = u / 2; } else if (U === 0) { a = fv[k]; b = fv[(k + n - 1) % n]; t = v / 2; }
      }
    }
    if (a === NONE) return [{ face: f, uv: this.ownUV(p, u, v) }];
    const out = [];
    if (t === 0 || t === 1) {
      const vtx = t === 0 ? a : b;
      // The corner's own UV (ptex.cpp's cornerUV), not a search of each face for the vertex.
      const faces = this.vertexFaces[vtx], corners = this.vertexCorners[vtx];
      for (let j = 0; j < faces.length; j++) out.push({ face: faces[j], uv: this.uvAt(faces[j], corners[j]) });
    } else {
      // Topology's edgeHalfedge and its twin: the first two faces of a (manifold) edge.
      const e = this.findEdge(a, b), faces = this.edgeFaces[e], corners = this.edgeCorners[e];
      for (let j = 0; j < Math.min(2, faces.length); j++) {
        const g = faces[j], i = corners[j], fromA = this.faceVerts(g)[i] === a;
        const next = (i + 1) % this.mesh.faceSizes[g];
        const pa = this.uvAt(g, fromA ? i : next), pb = this.uvAt(g, fromA ? next : i);
        out.push({ face: g, uv: [(1 - t) * pa[0] + t * pb[0], (1 - t) * pa[1] + t * pb[1]] });
      }
    }
    return out.sort((x, y) => x.face - y.face);
  }
}

const f32 = Math.fround;

// A growable typed array: the tessellation has hundreds of thousands of vertices and indices, and
// plain arrays of small arrays spent most of its time in allocation and garbage collection.
class Grow {
  constructor(Type, capacity = 1 << 12) { this.a = new Type(capacity); this.n = 0; }
  push(x) {
    if (this.n === this.a.length) { const b = new this.a.constructor(2 * this.n); b.set(this.a); this.a = b; }
    this.a[this.n++] = x;
  }
  view() { return this.a.subarray(0, this.n); }
}

/**
 * The fixed tessellation of tables (tables_chunk.mjs's decodeTables) for `mesh`, capped at `cap`
 * segments per side. Returns { vertices: Uint32Array (4 words a vertex: element, s | t << 16,
 * u bits, v bits), indices: Uint32Array, triangleLevels: Uint32Array, vertexCount }. `smooth`:
 * the FVSF surface (fvar_chunk.mjs) for smooth face-varying UVs instead of the faces' linear
 * charts (tessellation.cpp with ChartUVs); the vertices split at the same UV seams.
 */
export function buildTessellation(mesh, tables, cap, splitUVSeams = false, smooth = null) {
  cap = 2 ** Math.floor(Math.log2(Math.max(cap, 1)));
  const withUV = mesh.uvs !== null && mesh.uvs !== undefined;
  const N = tables.depth, R = 2 ** N;
  const keys = new PtexMap(mesh, R);
  const P = tables.patchCount;
  const pw = tables.patches, pf = new Float32Array(pw.buffer, pw.byteOffset, pw.length);
  const qw = tables.irregular, qf = new Float32Array(qw.buffer, qw.byteOffset, qw.length);
  const elements = [];
  const add = (ptex, u0, v0, size, level) => {
    const W = size * R;
    elements.push({ ptex, U0: u0 * R, V0: v0 * R, W, S: Math.min(Math.min(2 ** (N - level), cap), W) });
  };
  for (let i = 0; i < P; i++) add(pw[24 * i + 16], pf[24 * i + 17], pf[24 * i + 18], pf[24 * i + 19], pw[24 * i + 20] & 0xff);
  for (let i = 0; i < tables.irregularCount; i++) add(qw[8 * i + 4], qf[8 * i + 5], qf[8 * i + 6], qf[8 * i + 7], N);

  const vElement = new Grow(Uint32Array), vST = new Grow(Uint32Array), uvs = new Grow(Float32Array), geometry = new Grow(Uint32Array);
  const owner = new Map(), onUVSeam = new Map(), copies = new Map();
  const charts = smooth ? new SmoothChartUVs(smooth, keys) : null;
  const uvOf = (e, U, V) => {
    if (charts) return charts.own(e.ptex, U, V, e.U0 + 0.5 * e.W, e.V0 + 0.5 * e.W);
    const q = keys.ownUV(e.ptex, U / R, V / R); q[0] = f32(q[0]); q[1] = f32(q[1]); return q;
  };
  const seamPoint = (e, U, V, k) => {
    let s = onUVSeam.get(k);
    if (s === undefined) {
      s = false;
      if (keys.kindOf(k) !== 0) {
        const charts = keys.charts(e.ptex, U, V);
        const c0 = charts[0].uv.map(f32);
        for (const c of charts) s ||= f32(c.uv[0]) !== c0[0] || f32(c.uv[1]) !== c0[1];
      }
      onUVSeam.set(k, s);
    }
    return s;
  };
  const push = (ei, st, uv, geom) => {
    vElement.push(ei); vST.push(st); geometry.push(geom);
    if (withUV) { uvs.push(uv[0]); uvs.push(uv[1]); }
    return vElement.n - 1;
  };
  // Points inside a ptex face (most of them) are owned through an array, the rest by key.
  // (An array only while it is small: deep tables have few points in a huge lattice.)
  const side = R - 1, slots = keys.face.length * side * side;
  const interiorOwner = slots <= 2 ** 26 ? new Int32Array(Math.max(slots, 1)).fill(-1) : new Map();
  const getInterior = interiorOwner instanceof Map ? (k) => interiorOwner.get(k) ?? -1 : (k) => interiorOwner[k];
  const setInterior = interiorOwner instanceof Map ? (k, v) => interiorOwner.set(k, v) : (k, v) => { interiorOwner[k] = v; };
  const vertexFor = (ei, U, V, create) => {
    const e = elements[ei];
    const inside = U > 0 && U < R && V > 0 && V < R;
    const k = inside ? (e.ptex * side + U - 1) * side + V - 1 : keys.key(e.ptex, U, V);
    let first = inside ? getInterior(k) : owner.get(k);
    if (first === undefined || first < 0) {
      if (!create) return NONE;
      const unit = TESS_ONE / e.W;
      first = vElement.n;
      if (inside) setInterior(k, first); else owner.set(k, first);
      push(ei, ((U - e.U0) * unit) | (((V - e.V0) * unit) << 16), withUV ? uvOf(e, U, V) : null, first);
    }
    if (inside || !splitUVSeams || !seamPoint(e, U, V, k)) return first;
    const uv = uvOf(e, U, V);
    if (uvs.a[2 * first] === uv[0] && uvs.a[2 * first + 1] === uv[1]) return first;
    const ck = `${k}|${uv[0]}|${uv[1]}`;
    let c = copies.get(ck);
    if (c === undefined) {
      c = push(vElement.a[first], vST.a[first], uv, first);
      copies.set(ck, c);
    }
    return c;
  };

  for (let ei = 0; ei < elements.length; ei++) {
    const e = elements[ei], step = e.W / e.S;
    for (let j = 0; j <= e.S; j++) for (let i = 0; i <= e.S; i++) vertexFor(ei, e.U0 + i * step, e.V0 + j * step, true);
  }

  const indices = new Grow(Uint32Array, 1 << 14), triangleLevels = new Grow(Uint32Array), outline = new Grow(Uint32Array);
  for (let ei = 0; ei < elements.length; ei++) {
    const e = elements[ei], S = e.S, step = e.W / S;
    const find = (U, V) => vertexFor(ei, U, V, false);
    const edgePoints = (side, from, to) => {
      const pts = [];
      for (let x = from; x <= to; x++) {
        let U, V;
        if (side === 0) { U = e.U0 + x; V = e.V0; } else if (side === 1) { U = e.U0 + e.W; V = e.V0 + x; } else if (side === 2) { U = e.U0 + e.W - x; V = e.V0 + e.W; } else { U = e.U0; V = e.V0 + e.W - x; }
        const id = find(U, V);
        if (id !== NONE) pts.push(id);
      }
      return pts;
    };
    const sides = [0, 1, 2, 3].map((side) => edgePoints(side, 0, e.W));
    const stitched = sides.map((pts) => pts.length !== S + 1);
    // The element's outline (limn-render --wire): consecutive points along each side.
    for (const pts of sides) for (let k = 0; k + 1 < pts.length; k++) { outline.push(pts[k]); outline.push(pts[k + 1]); }
    const grid = (i, j) => find(e.U0 + i * step, e.V0 + j * step);
    const first = indices.n;
    const tri = (a, b, c) => { indices.push(a); indices.push(b); indices.push(c); };
    for (let j = 0; j < S; j++) {
      for (let i = 0; i < S; i++) {
        const onB = [j === 0 && stitched[0], i + 1 === S && stitched[1], j + 1 === S && stitched[2], i === 0 && stitched[3]];
        if (!onB[0] && !onB[1] && !onB[2] && !onB[3]) {
          const a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
          tri(a, b, c);
          tri(a, c, d);
          continue;
        }
        const ring = [];
        const x0 = i * step, x1 = (i + 1) * step, y0 = j * step, y1 = (j + 1) * step;
        if (j === 0) ring.push(...edgePoints(0, x0, x1).slice(0, -1)); else ring.push(grid(i, j));
        if (i + 1 === S) ring.push(...edgePoints(1, y0, y1).slice(0, -1)); else ring.push(grid(i + 1, j));
        if (j + 1 === S) ring.push(...edgePoints(2, e.W - x1, e.W - x0).slice(0, -1)); else ring.push(grid(i + 1, j + 1));
        if (i === 0) ring.push(...edgePoints(3, e.W - y1, e.W - y0).slice(0, -1)); else ring.push(grid(i, j + 1));
        if (S === 1) {
          const cu = (e.U0 + 0.5 * e.W) / R, cv = (e.V0 + 0.5 * e.W) / R;
          const centre = push(ei, (TESS_ONE / 2) | ((TESS_ONE / 2) << 16), withUV ? (charts ? charts.interior(e.ptex, cu, cv) : keys.ownUV(e.ptex, cu, cv).map(f32)) : null, vElement.n);
          for (let r = 0; r < ring.length; r++) tri(centre, ring[r], ring[(r + 1) % ring.length]);
          continue;
        }
        const apex = i + 1 < S && j + 1 < S ? grid(i + 1, j + 1) : i > 0 && j + 1 < S ? grid(i, j + 1) : i > 0 && j > 0 ? grid(i, j) : grid(i + 1, j);
        const a = ring.indexOf(apex);
        for (let r = 1; r + 1 < ring.length; r++) tri(apex, ring[(a + r) % ring.length], ring[(a + r + 1) % ring.length]);
      }
    }
    const level = ei < P ? pw[24 * ei + 20] & 0xff : 255;
    for (let t = first; t < indices.n; t += 3) triangleLevels.push(level);
  }

  const n = vElement.n;
  const vertices = new Uint32Array(Math.max(n, 1) * 4);
  const vf = new Float32Array(vertices.buffer);
  for (let i = 0; i < n; i++) {
    vertices[4 * i] = vElement.a[i];
    vertices[4 * i + 1] = vST.a[i];
    if (withUV) { vf[4 * i + 2] = uvs.a[2 * i]; vf[4 * i + 3] = uvs.a[2 * i + 1]; }
  }
  return { vertices, vertexCount: n, indices: indices.view().slice(), triangleLevels: triangleLevels.view().slice(), geometry: Array.from(geometry.view()), outline: outline.view(), smoothCharts: charts };
}
