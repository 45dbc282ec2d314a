// Smooth face-varying UVs from the FVSF chunk (fvar_chunk.mjs): the UV at a point of a ptex face,
// as lib/subdiv/fvar_surface.cpp's uvAt gives it, and per base face the UV of a drawn point, as
// lib/tess/chart_uvs.cpp's ChartUVs keeps it (computed on first use, from the first element
// that asks, so that every element drawing the point in a face gets the same bits).

// The uniform cubic B-spline basis at t (paper 000, eq. 1).
function basis(t, b) {
  const s = 1 - t, t2 = t * t, t3 = t2 * t;
  b[0] = (s * s * s) / 6;
  b[1] = (3 * t3 - 6 * t2 + 4) / 6;
  b[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
  b[3] = t3 / 6;
}
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
  basis(s, bu);
  basis(t, bv);
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

/** ChartUVs: per drawn point and base face, the point's smooth UV in that face's chart. */
export class SmoothChartUVs {
  /** keys: tessellation.mjs's PtexMap at the tables' resolution R. */
  constructor(fvar, keys) {
    this.fvar = fvar;
    this.keys = keys;
    this.memo = new Map();
  }

  /** The UV of lattice point (U, V) (of R) of `ptex`, evaluated toward (towardU, towardV) on first use. */
  own(ptex, U, V, towardU, towardV) {
    const { keys } = this, R = keys.R;
    const key = `${keys.key(ptex, U, V)}|${keys.face[ptex]}`;
    let uv = this.memo.get(key);
    if (!uv) {
      uv = fvarUV(this.fvar, ptex, U / R, V / R, towardU / R, towardV / R).map(Math.fround);
      this.memo.set(key, uv);
    }
    return uv;
  }

  /** A point strictly inside a ptex face, at (u, v) in [0, 1]^2. */
  interior(ptex, u, v) {
    return fvarUV(this.fvar, ptex, u, v, 0.5, 0.5).map(Math.fround);
  }
}
