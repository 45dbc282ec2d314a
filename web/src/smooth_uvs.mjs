// Smooth face-varying UVs from the FVSF chunk (fvar_chunk.mjs): the UV at a point of a ptex face,
// as lib/subdiv/fvar_surface.cpp's uvAt gives it, and per base face the UV of a drawn point, as
// lib/tess/chart_uvs.cpp's ChartUVs keeps it (computed on first use, from the first element
// that asks, so that every element drawing the point in a face gets the same bits).

import { bsplineBasis } from './bspline.mjs';
const bu = new Float64Array(4), bv = new Float64Array(4);

/**
 * The UV at (u, v) of ptex face `ptex`, from the element that contains the point just inside
 * toward (towardU, towardV) (fvar_surface.cpp uvAt; shaders/fvar_eval.glsl walks the same
 * quadtree on the GPU). Patches: the bicubic B-spline of their 16 UV control points; bilinear
 * records (an irregular face's leaves): the blend of their corners' limit UVs. Evaluated in double, from the float
 * records the chunk holds.
 */
export function fvarUV(fvar, ptex, u, v, towardU, towardV) {
  const pu = Math.min(Math.max(u + 1e-6 * (towardU - u), 0), 1), pv = Math.min(Math.max(v + 1e-6 * (towardV - v), 0), 1);
  const { nodes, records: r } = fvar;
  let node = nodes[ptex], ou = 0, ov = 0, size = 1;
  while (node !== 0xffffffff && node < 0x80000000) { // children follow their parent: this ends
    size /= 2;
    const i = pu >= ou + size ? 1 : 0, j = pv >= ov + size ? 1 : 0;
    ou += i * size; ov += j * size;
    node = nodes[node + i + 2 * j];
  }
  if (node === 0xffffffff) throw new Error(`no face-varying element contains ptex face ${ptex} at (${u}, ${v})`);
  const o = 36 * (node - 0x80000000);
  const s = (u - r[o]) / r[o + 2], t = (v - r[o + 1]) / r[o + 2];
  if (r[o + 3] !== 0) { // corners (u0,v0), (u1,v0), (u1,v1), (u0,v1): r[4..5], r[6..7], r[8..9], r[10..11]
    const w = [(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t];
    let x = 0, y = 0;
    for (let c = 0; c < 4; c++) if (w[c] !== 0) { x += w[c] * r[o + 4 + 2 * c]; y += w[c] * r[o + 5 + 2 * c]; }
    return [x, y];
  }
  bsplineBasis(s, bu);
  bsplineBasis(t, bv);
  let x = 0, y = 0;
  for (let j = 0; j < 4; j++) {
    for (let i = 0; i < 4; i++) {
      const w = bv[j] * bu[i], at = o + 4 + 2 * (4 * j + i); // P_ij at 4j + i, two floats each
      x += w * r[at];
      y += w * r[at + 1];
    }
  }
  return [x, y];
}

const NONE = 0xffffffff;

/**
 * ChartUVs (lib/tess/chart_uvs.cpp): per drawn point and base face, the point's smooth UV in that
 * face's chart. Points are kept on the lattice Q = 2R of the ptex faces (R = 2^depth), where a
 * point on a base edge has integer coordinates in a quad and in an n-gon's sub-face alike.
 */
export class SmoothChartUVs {
  /** keys: tessellation.mjs's PtexMap at the tables' resolution R; its class makes the 2R map. */
  constructor(fvar, keys) {
    this.fvar = fvar;
    this.keys = keys;
    this.Q = 2 * keys.R;
    this.keysQ = new keys.constructor(keys.mesh, this.Q);
    this.firstPtex = [];
    for (let p = 0; p < keys.face.length; p++) if (p === 0 || keys.face[p] !== keys.face[p - 1]) this.firstPtex[keys.face[p]] = p;
    this.memo = new Map();
  }

  /** The UV of lattice point (U, V) (of R) of `ptex`, evaluated toward (towardU, towardV) on first use. */
  own(ptex, U, V, towardU, towardV) {
    return this.ownQ(ptex, 2 * U, 2 * V, 2 * towardU, 2 * towardV);
  }

  ownQ(ptex, X, Y, towardX, towardY) {
    const Q = this.Q, key = `${this.keysQ.key(ptex, X, Y)}|${this.keys.face[ptex]}`;
    let uv = this.memo.get(key);
    if (!uv) {
      uv = fvarUV(this.fvar, ptex, X / Q, Y / Q, towardX / Q, towardY / Q).map(Math.fround);
      this.memo.set(key, uv);
    }
    return uv;
  }

  /** A point strictly inside a ptex face, at (u, v) in [0, 1]^2. */
  interior(ptex, u, v) {
    return fvarUV(this.fvar, ptex, u, v, 0.5, 0.5).map(Math.fround);
  }

  /**
   * The distinct UVs of lattice point (U, V) (of R) of `ptex` in every base face that contains
   * it, in increasing face order (paper 000, Figures 8 and 9: what the seam fix averages).
   */
  sides(ptex, U, V) {
    const out = [];
    for (const l of this.locate(ptex, 2 * U, 2 * V)) {
      const uv = this.ownQ(l.ptex, l.X, l.Y, 0.5 * this.Q, 0.5 * this.Q);
      if (!out.some((x) => x[0] === uv[0] && x[1] === uv[1])) out.push(uv);
    }
    return out;
  }

  /**
   * For the element edge from (Ua, Va) to (Ub, Vb) (of R) of `ptex`: per base face along it (one
   * inside a face or on the mesh boundary, two across a base edge; increasing face order), the
   * UVs of its two ends in that face's chart, distinct pairs only.
   */
  edgeSides(ptex, Ua, Va, Ub, Vb) {
    const out = [], ends = [this.locate(ptex, 2 * Ua, 2 * Va), this.locate(ptex, 2 * Ub, 2 * Vb)];
    for (const side of this.locate(ptex, Ua + Ub, Va + Vb)) { // the midpoint: the faces along the edge
      const pair = ends.map((list) => {
        let uv = [0, 0];
        for (const l of list) if (l.face === side.face) uv = this.ownQ(l.ptex, l.X, l.Y, 0.5 * this.Q, 0.5 * this.Q);
        return uv;
      });
      if (!out.some((x) => x[0][0] === pair[0][0] && x[0][1] === pair[0][1] && x[1][0] === pair[1][0] && x[1][1] === pair[1][1])) out.push(pair);
    }
    return out;
  }

  // Where the point at t (of 2Q) from base vertex a toward b lies in face f: its ptex face and (X, Y).
  inFace(f, a, b, t) {
    const fv = this.keys.faceVerts(f), n = fv.length, Q = this.Q, first = this.firstPtex[f];
    let i = 0;
    while (i < n && fv[i] !== a) i++;
    const forward = fv[(i + 1) % n] === b;
    if (n === 4) {
      const cu = [0, 1, 1, 0], cv = [0, 0, 1, 1], j = forward ? (i + 1) % 4 : (i + 3) % 4;
      // t is even for every point on the R lattice: the halves are exact.
      return { face: f, ptex: first, X: (cu[i] * (2 * Q - t) + cu[j] * t) / 2, Y: (cv[i] * (2 * Q - t) + cv[j] * t) / 2 };
    }
    if (t === 0) return { face: f, ptex: first + i, X: 0, Y: 0 };
    if (forward) return t <= Q ? { face: f, ptex: first + i, X: t, Y: 0 } : { face: f, ptex: first + ((i + 1) % n), X: 0, Y: 2 * Q - t };
    return t <= Q ? { face: f, ptex: first + i, X: 0, Y: t } : { face: f, ptex: first + ((i + n - 1) % n), X: 2 * Q - t, Y: 0 };
  }

  // Every base face containing the point (X, Y) (of Q) of ptex face p, in increasing face order.
  locate(p, X, Y) {
    const { keys } = this, Q = this.Q, face = keys.face[p], sub = keys.sub[p], fv = keys.faceVerts(face);
    let a = NONE, b = NONE, t = 0;
    if (sub < 0) {
      if (Y === 0) { a = fv[0]; b = fv[1]; t = 2 * X; } else if (X === Q) { a = fv[1]; b = fv[2]; t = 2 * Y; } else if (Y === Q) { a = fv[3]; b = fv[2]; t = 2 * X; } else if (X === 0) { a = fv[0]; b = fv[3]; t = 2 * Y; }
    } else {
      const n = fv.length, k = sub;
      if (Y === 0) { a = fv[k]; b = fv[(k + 1) % n]; t = X; } else if (X === 0) { a = fv[k]; b = fv[(k + n - 1) % n]; t = Y; }
    }
    if (a === NONE) return [{ face, ptex: p, X, Y }]; // inside the face, or on an n-gon's spokes
    if (t === 2 * Q) { [a, b] = [b, a]; t = 0; }
    const out = [];
    if (t === 0) for (const g of keys.vertexFaces[a]) out.push(this.inFace(g, a, a, 0));
    else for (const g of keys.edgeFaces[keys.findEdge(a, b)].slice(0, 2)) out.push(this.inFace(g, a, b, t));
    // A hole (or a face without a limit surface) has no UV element and is not drawn: nothing
    // there to sample or to agree with (chart_uvs.cpp's locate).
    return out.filter((l) => this.fvar.nodes[l.ptex] !== NONE).sort((x, y) => x.face - y.face);
  }
}

/**
 * subdivision_draw.cpp's smoothSeamRecords: the seam records of SEAM's layout (displacement.mjs
 * computeSeams: per element its corners' UVs in its own chart, each corner's distinct UVs in the
 * faces around it, each edge's distinct end-UV pairs per face along it, in increasing face order)
 * with the smooth UVs of `charts` (a SmoothChartUVs), in element order. Without `full`, the own
 * corners only. Returns { records, uvs, uvCount, own: per element its 4 corner UVs }.
 */
export function smoothSeamRecords(tables, charts, full) {
  const R = 2 ** tables.depth, E = tables.patchCount + tables.irregularCount;
  const records = new Uint32Array(Math.max(E, 1) * 24), rf = new Float32Array(records.buffer), out = [], own = [];
  const pw = tables.patches, pf = new Float32Array(pw.buffer, pw.byteOffset, pw.length);
  const qw = tables.irregular, qf = new Float32Array(qw.buffer, qw.byteOffset, qw.length);
  const add = (e, ptex, u0, v0, size) => {
    const base = 24 * e, U0 = Math.trunc(u0 * R), V0 = Math.trunc(v0 * R), W = Math.trunc(size * R);
    const cu = [U0, U0 + W, U0 + W, U0], cv = [V0, V0, V0 + W, V0 + W];
    own.push([]);
    for (let k = 0; k < 4; k++) {
      const uv = charts.own(ptex, cu[k], cv[k], U0 + 0.5 * W, V0 + 0.5 * W);
      own[e].push(uv);
      rf[base + 2 * k] = uv[0];
      rf[base + 2 * k + 1] = uv[1];
      if (!full) continue;
      const list = charts.sides(ptex, cu[k], cv[k]);
      records[base + 8 + 2 * k] = out.length;
      records[base + 9 + 2 * k] = list.length;
      out.push(...list);
    }
    for (let k = 0; full && k < 4; k++) {
      const pairs = charts.edgeSides(ptex, cu[k], cv[k], cu[(k + 1) % 4], cv[(k + 1) % 4]);
      records[base + 16 + 2 * k] = out.length;
      records[base + 17 + 2 * k] = pairs.length;
      for (const [a, b] of pairs) out.push(a, b);
    }
  };
  for (let i = 0; i < tables.patchCount; i++) add(i, pw[24 * i + 16], pf[24 * i + 17], pf[24 * i + 18], pf[24 * i + 19]);
  for (let i = 0; i < tables.irregularCount; i++) add(tables.patchCount + i, qw[8 * i + 4], qf[8 * i + 5], qf[8 * i + 6], qf[8 * i + 7]);
  return { records: records.subarray(0, E * 24), uvs: Float32Array.from(out.flat()), uvCount: out.length, own };
}
