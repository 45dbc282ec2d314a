// limn-render's framing hull (renderer.cpp surfaceSamples), evaluated as it evaluates it: on the
// CPU in double, with lib/subdiv/evaluate.cpp's sums in their order, so that the auto-framed
// camera is limn-render's to the bit. Each patch at (s, t) in {0, 1/2, 1}^2, then every limit
// point. (The GPU's float evaluation moved the camera by a float step; on the car at depth 6 that
// turned one flat element's sample test and drew a triangle more than limn-render.)
import { bsplineBasis } from './bspline.mjs';

const PATCH_WORDS = 24;
const BOUNDARY_V0 = 1, BOUNDARY_U1 = 2, BOUNDARY_V1 = 4, BOUNDARY_U0 = 8; // lib/subdiv/tables.h PatchBoundary

// evaluateVertices: the control points, then every level's face, edge and vertex points.
function evaluateVertices(tables, control) {
  const V = new Float64Array(3 * tables.totalVertices);
  V.set(control.subarray(0, 3 * tables.levels[0].count));
  for (let l = 1; l < tables.levels.length; l++) {
    let out = tables.levels[l].first;
    const faces = tables.facePoints[l - 1];
    for (let r = 0; r < faces.rows; r++) {
      let x = 0, y = 0, z = 0;
      for (let i = faces.start[r]; i < faces.start[r + 1]; i++) { const v = 3 * faces.index[i]; x += V[v]; y += V[v + 1]; z += V[v + 2]; }
      const n = faces.start[r + 1] - faces.start[r];
      V[3 * out] = x / n; V[3 * out + 1] = y / n; V[3 * out + 2] = z / n;
      out++;
    }
    for (const table of [tables.edgePoints[l - 1], tables.vertexPoints[l - 1]]) {
      for (let r = 0; r < table.rows; r++, out++) apply(table, r, V, V, 3 * out);
    }
  }
  return V;
}

// A stencil row's weighted sum of V into out[at..at+2].
function apply(table, row, V, out, at) {
  let x = 0, y = 0, z = 0;
  for (let i = table.start[row]; i < table.start[row + 1]; i++) {
    const w = table.weight[i], v = 3 * table.index[i];
    x += w * V[v]; y += w * V[v + 1]; z += w * V[v + 2];
  }
  out[at] = x; out[at + 1] = y; out[at + 2] = z;
}

// evaluate.cpp's creaseBasis (positions only): the crease curve's rules applied until the segment
// leaves the crease vertex or the sharpness has decayed, then the uniform B-spline.
function creaseBasis(t, sharpness) {
  let M = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], s = sharpness;
  const step = (left) => {
    const w = Math.min(s, 1);
    const crease = [(1 - w) / 8, w + ((1 - w) * 6) / 8, (1 - w) / 8, 0];
    const e01 = [0.5, 0.5, 0, 0], e12 = [0, 0.5, 0.5, 0], e23 = [0, 0, 0.5, 0.5], v2 = [0, 1 / 8, 6 / 8, 1 / 8];
    const rows = left ? [e01, crease, e12, v2] : [crease, e12, v2, e23];
    const N = [0, 1, 2, 3].map(() => [0, 0, 0, 0]);
    for (let r = 0; r < 4; r++) for (let c = 0; c < 4; c++) for (let k = 0; k < 4; k++) N[r][c] += rows[r][k] * M[k][c];
    M = N;
    s -= 1;
    t = left ? 2 * t : 2 * t - 1;
  };
  while (s > 0 && t < 0.5) step(true);
  if (s > 0) step(false);
  const bt = bsplineBasis(t), b = [0, 0, 0, 0];
  for (let c = 0; c < 4; c++) for (let k = 0; k < 4; k++) b[c] += bt[k] * M[k][c];
  return b;
}

function directionBasis(crease, sharpness, x, lowBit, highBit) {
  if (!(crease & (lowBit | highBit))) return bsplineBasis(x);
  const atEnd = (crease & highBit) !== 0;
  const cb = creaseBasis(atEnd ? 1 - x : x, sharpness);
  return atEnd ? [cb[3], cb[2], cb[1], cb[0]] : cb;
}

// Per loaded surface: a renderer made again for the same surface (the viewer's new size or
// tessellation) does not evaluate it again (the car at depth 6 takes 0.25 s).
const hulls = new WeakMap();

/** The framing hull's points ([x, y, z] each) of a loaded surface ({mesh, tables}), as limn-render's. */
export function surfaceSamples(surface) {
  if (!hulls.has(surface)) hulls.set(surface, evaluateSamples(surface.mesh, surface.tables));
  return hulls.get(surface);
}

function evaluateSamples(mesh, tables) {
  const V = evaluateVertices(tables, mesh.positions);
  const words = tables.patches, floats = new Float32Array(words.buffer, words.byteOffset, words.length);
  const points = [], params = [0, 0.5, 1], uniform = params.map((t) => bsplineBasis(t));
  const P = new Float64Array(48); // P[i][j] at 3 (4 j + i)
  // gatherControlPoints' phantom point: 2 a - b, into P[at].
  const mirror = (at, a, b) => { for (let c = 0; c < 3; c++) P[3 * at + c] = 2 * P[3 * a + c] - P[3 * b + c]; };
  for (let p = 0; p < tables.patchCount; p++) {
    const base = PATCH_WORDS * p, packed = words[base + 20];
    const boundary = (packed >>> 8) & 0xff, crease = (packed >>> 16) & 0xff, sharpness = floats[base + 21];
    // gatherControlPoints: phantom columns, then phantom rows over all columns.
    for (let k = 0; k < 16; k++) { const v = 3 * words[base + k]; P[3 * k] = V[v]; P[3 * k + 1] = V[v + 1]; P[3 * k + 2] = V[v + 2]; }
    for (let j = 0; j < 4; j++) {
      if (boundary & BOUNDARY_U0) mirror(4 * j, 4 * j + 1, 4 * j + 2);
      if (boundary & BOUNDARY_U1) mirror(4 * j + 3, 4 * j + 2, 4 * j + 1);
    }
    for (let i = 0; i < 4; i++) {
      if (boundary & BOUNDARY_V0) mirror(i, 4 + i, 8 + i);
      if (boundary & BOUNDARY_V1) mirror(12 + i, 8 + i, 4 + i);
    }
    const bases = (lowBit, highBit) => (crease & (lowBit | highBit)) ? params.map((x) => directionBasis(crease, sharpness, x, lowBit, highBit)) : uniform;
    const bus = bases(BOUNDARY_U0, BOUNDARY_U1), bvs = bases(BOUNDARY_V0, BOUNDARY_V1);
    for (const bu of bus) {
      for (const bv of bvs) {
        let x = 0, y = 0, z = 0;
        for (let j = 0; j < 4; j++) {
          for (let i = 0; i < 4; i++) { const w = bu[i] * bv[j], q = 3 * (4 * j + i); x += w * P[q]; y += w * P[q + 1]; z += w * P[q + 2]; }
        }
        points.push([x, y, z]);
      }
    }
  }
  const limit = [0, 0, 0];
  for (let i = 0; i < tables.limitCount; i++) { apply(tables.limitPosition, i, V, limit, 0); points.push([...limit]); }
  return points;
}
