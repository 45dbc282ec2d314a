// The view-adaptive tessellation (limn-render's default, --edge-pixels P > 0): a port of
// lib/tess/edge_pieces.cpp (the topology, built once on the CPU from the tables alone) and
// lib/render/adaptive_tess.cpp (the five compute passes per frame: cull, rates, counts, scan,
// emit; the draw then reads the tessellation through one indirect draw).
import { PtexMap, TESS_ONE } from './tessellation.mjs';
import { LimnError } from './container.mjs';

const NO_ELEMENT = 0xffffffff;
const pack = (s, t) => (s | (t << 16)) >>> 0;
const MAX_BUFFER = 128 * 2 ** 20;
export const TOTALS_WORDS = 24;
export const INDEXED_DRAW_ARGS = 0, DRAW_ARGS = 20, DISPATCH_ARGS = 36, WIRE_DRAW_ARGS = 72;
export const ROW_GROUPS = 65535, EVAL_GROUP_SIZE = 64;

function sidePoint(d, k, x) {
  if (k === 0) return [d.U0 + x, d.V0];
  if (k === 1) return [d.U0 + d.W, d.V0 + x];
  if (k === 2) return [d.U0 + d.W - x, d.V0 + d.W];
  return [d.U0, d.V0 + d.W - x];
}

function sideST(d, k, x) {
  const p = x * (TESS_ONE / d.W), q = TESS_ONE - p;
  if (k === 0) return pack(p, 0);
  if (k === 1) return pack(TESS_ONE, p);
  if (k === 2) return pack(q, TESS_ONE);
  return pack(0, q);
}

/**
 * buildEdgePieces: elements, side pieces, pieces and points, as lib/tess/edge_pieces.cpp. With
 * `smoothOwn` (smooth_uvs.mjs smoothSeamRecords' `own`), the elements' corner UVs are the smooth
 * UVs in their own chart, as subdivision_draw.cpp sets them.
 */
export function buildEdgePieces(mesh, tables, smoothOwn = null) {
  const N = tables.depth;
  if (N + 1 > 16) throw new Error(`view-adaptive tessellation supports tables up to depth 15, these have depth ${N}`);
  const R = 2 ** N;
  const keys = new PtexMap(mesh, R), halfKeys = new PtexMap(mesh, 2 * R);
  const withUV = !!mesh.uvs;
  const domains = [], elements = [], points = [], pieces = [], sidePieces = [];
  const pw = tables.patches, pf = new Float32Array(pw.buffer, pw.byteOffset, pw.length);
  const qw = tables.irregular, qf = new Float32Array(qw.buffer, qw.byteOffset, qw.length);
  const add = (ptex, u0, v0, size, level) => {
    const d = { ptex, U0: u0 * R, V0: v0 * R, W: size * R };
    domains.push(d);
    const e = { sideFirst: [0, 0, 0, 0], sideCount: [0, 0, 0, 0], cornerUV: [[0, 0], [0, 0], [0, 0], [0, 0]], level };
    if (withUV) {
      const cu = [0, 1, 1, 0], cv = [0, 0, 1, 1];
      for (let c = 0; c < 4; c++) {
        const U = d.U0 + cu[c] * d.W, V = d.V0 + cv[c] * d.W;
        e.cornerUV[c] = smoothOwn ? smoothOwn[elements.length][c] : keys.ownUV(ptex, U / R, V / R).map(Math.fround);
      }
    }
    elements.push(e);
  };
  for (let i = 0; i < tables.patchCount; i++) add(pw[24 * i + 16], pf[24 * i + 17], pf[24 * i + 18], pf[24 * i + 19], pw[24 * i + 20] & 0xff);
  for (let i = 0; i < tables.irregularCount; i++) add(qw[8 * i + 4], qf[8 * i + 5], qf[8 * i + 6], qf[8 * i + 7], 255);

  const pointOf = new Map();
  for (let ei = 0; ei < domains.length; ei++) {
    for (let k = 0; k < 4; k++) {
      const [U, V] = sidePoint(domains[ei], k, 0);
      const key = keys.key(domains[ei].ptex, U, V);
      if (!pointOf.has(key)) { pointOf.set(key, points.length); points.push({ owner: ei, st: sideST(domains[ei], k, 0) }); }
    }
  }
  const pieceOf = new Map();
  for (let ei = 0; ei < domains.length; ei++) {
    const d = domains[ei], e = elements[ei];
    for (let k = 0; k < 4; k++) {
      e.sideFirst[k] = sidePieces.length;
      let a = 0;
      let aPoint = pointOf.get(keys.key(d.ptex, ...sidePoint(d, k, 0)));
      const stack = [];
      let x0 = 0, x1 = d.W;
      for (;;) {
        if (x1 - x0 >= 2) {
          const m = (x0 + x1) / 2;
          if (pointOf.has(keys.key(d.ptex, ...sidePoint(d, k, m)))) { stack.push(x1); x1 = m; continue; }
        }
        const b = x1;
        const [U, V] = sidePoint(d, k, b), [Ua, Va] = sidePoint(d, k, a);
        const bPoint = pointOf.get(keys.key(d.ptex, U, V));
        const mid = halfKeys.key(d.ptex, Ua + U, Va + V);
        let piece = pieceOf.get(mid);
        const inserted = piece === undefined;
        if (inserted) {
          piece = pieces.length;
          pieceOf.set(mid, piece);
          let uvLength = 0;
          if (withUV) {
            const p = keys.ownUV(d.ptex, Ua / R, Va / R), q = keys.ownUV(d.ptex, U / R, V / R);
            uvLength = Math.fround(Math.hypot(p[0] - q[0], p[1] - q[1]));
          }
          pieces.push({ owner: ei, ownerStart: sideST(d, k, a), ownerEnd: sideST(d, k, b), users: [ei, NO_ELEMENT], startPoint: aPoint, endPoint: bPoint, span: (b - a) * (TESS_ONE / d.W), uvLength });
        } else {
          const pc = pieces[piece];
          if (pc.users[1] === NO_ELEMENT && pc.users[0] !== ei) pc.users[1] = ei;
        }
        const pc = pieces[piece];
        sidePieces.push({ piece, startPoint: aPoint, reversed: pc.owner === ei && inserted ? 0 : pc.startPoint === aPoint ? 0 : 1, from: a * (TESS_ONE / d.W), to: b * (TESS_ONE / d.W) });
        a = b; aPoint = bPoint;
        if (stack.length === 0) break;
        x0 = x1; x1 = stack.pop();
      }
      e.sideCount[k] = sidePieces.length - e.sideFirst[k];
    }
  }
  return { elements, sidePieces, pieces, points };
}

/** The GPU buffers' contents and capacities of AdaptiveTess's constructor. */
export function adaptiveData(ep, tables, options) {
  const tess = options.tess;
  const elements = new Uint32Array(Math.max(ep.elements.length, 1) * 20);
  const ef = new Float32Array(elements.buffer);
  let maxV = 0, maxT = 0;
  ep.elements.forEach((e, i) => {
    let B = 0;
    for (let k = 0; k < 4; k++) {
      elements[20 * i + k] = e.sideFirst[k];
      elements[20 * i + 4 + k] = e.sideCount[k];
      for (let p = 0; p < e.sideCount[k]; p++) B += Math.max(1, Math.min(tess, ep.pieces[ep.sidePieces[e.sideFirst[k] + p].piece].span));
      ef[20 * i + 8 + 2 * k] = e.cornerUV[k][0];
      ef[20 * i + 9 + 2 * k] = e.cornerUV[k][1];
    }
    elements[20 * i + 16] = e.level;
    elements[20 * i + 17] = i < tables.patchCount ? (tables.patches[24 * i + 20] >>> 16) & 0xf : 0;
    const m = tess;
    maxV += B + (m <= 2 ? 1 : (m - 1) * (m - 1));
    maxT += m <= 2 ? B : 2 * (m - 2) * (m - 2) + B + 4 * (m - 2);
  });
  const limitV = MAX_BUFFER / 16, limitT = Math.floor(MAX_BUFFER / 12);
  let shared = 0;
  if (options.sharePoints && ep.points.length < limitV / 2) { shared = ep.points.length; maxV += shared; }
  const budgetV = (options.maxVertices || limitV) + shared, budgetT = options.maxTriangles || limitT;
  const capV = Math.max(1, Math.min(maxV, budgetV, limitV)), capT = Math.max(1, Math.min(maxT, budgetT, limitT));
  const words = [];
  const uvBits = new Uint32Array(new Float32Array(1).buffer);
  const bitsOf = (f) => { new Float32Array(uvBits.buffer)[0] = f; return uvBits[0]; };
  for (const p of ep.pieces) words.push(p.owner, p.ownerStart, p.ownerEnd, p.span, p.users[0], p.users[1], bitsOf(p.uvLength), 0);
  const pointBase = words.length / 4;
  for (const q of ep.points) words.push(q.owner, q.st, 0, 0);
  // Smooth UVs (options.smooth, the FVSF surface): per element its ptex domain, then the UV
  // quadtree four nodes a word group, then the records, for the emit pass (adaptive_tess.cpp).
  let domainBase = 0, nodeBase = 0, recordBase = 0;
  if (options.smooth) {
    domainBase = words.length / 4;
    const pw = tables.patches, qw = tables.irregular;
    for (let i = 0; i < tables.patchCount; i++) words.push(pw[24 * i + 16], pw[24 * i + 17], pw[24 * i + 18], pw[24 * i + 19]);
    for (let i = 0; i < tables.irregularCount; i++) words.push(qw[8 * i + 4], qw[8 * i + 5], qw[8 * i + 6], qw[8 * i + 7]);
    nodeBase = words.length / 4;
    const { nodes, records } = options.smooth;
    for (let i = 0; i < nodes.length; i += 4) for (let k = 0; k < 4; k++) words.push(i + k < nodes.length ? nodes[i + k] : 0xffffffff);
    recordBase = words.length / 4;
    for (const w of new Uint32Array(records.buffer, records.byteOffset, records.length)) words.push(w);
  }
  const sideBase = words.length / 4;
  // z: bit 0 reversed, bit 1 the piece owner's side (the first naming the piece), which writes the
  // piece's shared points (adaptive_tess.cpp).
  const registered = new Uint8Array(ep.pieces.length);
  for (const s of ep.sidePieces) {
    words.push(s.piece, s.startPoint, s.reversed | (registered[s.piece] ? 0 : 2), (s.from | (s.to << 16)) >>> 0);
    registered[s.piece] = 1;
  }
  for (let i = 0; i < ep.elements.length; i++) for (let k = 0; k < 4; k++) elements[20 * i + k] += sideBase;
  if (words.length * 4 > MAX_BUFFER) throw new LimnError(`the view-adaptive tessellation's edge pieces would need ${(words.length / 2 ** 18).toFixed(1)} MiB, over WebGPU's 128 MiB storage-buffer limit`, 'input');
  return { elements, pieces: Uint32Array.from(words), capV, capT, shared, pointBase, domainBase, nodeBase, recordBase, smooth: !!options.smooth, elementCount: ep.elements.length, pieceCount: ep.pieces.length };
}

/** The five passes' dispatches (name, element count, push words) for a view, as AdaptiveTess::record. */
export function adaptivePushes(data, tables, options, view) {
  const f32 = (x) => { const b = new Float32Array([x]); return new Uint32Array(b.buffer)[0]; };
  const samples = Math.min(options.samplePositions.length, 4);
  const packed = [0, 0];
  for (let k = 0; k < samples; k++) {
    const [x, y] = options.samplePositions[k].map((c) => Math.min(Math.max(Math.fround(c * 256), 0), 255));
    packed[k >> 1] = (packed[k >> 1] | ((Math.trunc(x) | (Math.trunc(y) << 8)) << (16 * (k % 2)))) >>> 0;
  }
  const vp = view.viewProj.map(f32);
  const cull = [...vp, f32(view.eye[0]), f32(view.eye[1]), f32(view.eye[2]), f32(view.facing), tables.patchCount,
    ((options.cull ? 1 : 0) | (samples << 8)) >>> 0, f32(view.width), f32(view.height), packed[0], packed[1]];
  const rates = [...vp, f32(0.5 * view.width), f32(0.5 * view.height), f32(options.edgePixels), options.tess, tables.patchCount, f32(options.texelsPerUV ?? 0), f32(options.maxError ?? 0),
    f32(options.interiorError ?? 0)];
  // Smooth UVs: the emit pass's quadtree walk per vertex (adaptive_tess.cpp kFvarLoopsPerVertex).
  const counts = [options.tess, data.smooth ? 12 : 0, data.shared ? 1 : 0, samples, packed[0], packed[1], options.evaluated ? 0 : 1];
  const scan = [data.elementCount, data.capV, data.capT, ROW_GROUPS, EVAL_GROUP_SIZE, data.shared];
  // fvarCell 2^-21: 1/32 of the finest cell at depth 16, above float's step at 1.
  const emit = [data.pointBase, data.capT, data.smooth ? 1 : 0, data.smooth ? f32(2 ** -21) : 0, data.domainBase, data.nodeBase, data.recordBase, data.shared ? 1 : 0, data.capV,
    options.pixelNormals ? 1 : 0]; // per-pixel normals: each vertex its triangle's element and (s, t)
  return [
    ['adaptive_cull.comp', data.elementCount, cull],
    ['adaptive_rates.comp', data.pieceCount, rates],
    ['adaptive_counts.comp', data.elementCount, counts],
    ['adaptive_scan.comp', 1, scan],
    ['adaptive_emit.comp', data.elementCount, emit],
  ];
}

/** subdivision_draw.cpp's surfaceOrientation: the sign of the control mesh's signed volume. */
export function surfaceOrientation(mesh) {
  const P = mesh.positions, V = mesh.vertexCount;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < V; i++) for (let c = 0; c < 3; c++) { lo[c] = Math.min(lo[c], P[3 * i + c]); hi[c] = Math.max(hi[c], P[3 * i + c]); }
  const ctr = [0, 1, 2].map((c) => 0.5 * (lo[c] + hi[c]));
  const at = (v) => [P[3 * v] - ctr[0], P[3 * v + 1] - ctr[1], P[3 * v + 2] - ctr[2]];
  let volume = 0, scale = 0;
  for (let f = 0; f < mesh.faceCount; f++) {
    const first = mesh.faceOffsets[f], n = mesh.faceOffsets[f + 1] - first;
    const a = at(mesh.faceVertices[first]);
    for (let k = 1; k + 1 < n; k++) {
      const b = at(mesh.faceVertices[first + k]), e = at(mesh.faceVertices[first + k + 1]);
      const det = a[0] * (b[1] * e[2] - b[2] * e[1]) + a[1] * (b[2] * e[0] - b[0] * e[2]) + a[2] * (b[0] * e[1] - b[1] * e[0]);
      volume += det / 6;
      scale += Math.abs(det) / 6;
    }
  }
  return volume > 1e-6 * scale ? 1 : volume < -1e-6 * scale ? -1 : 0;
}
