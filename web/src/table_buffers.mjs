// The subdivision tables as the contents of GPU buffers (subdivision_draw.cpp), the refusals of
// what would pass WebGPU's 128 MiB storage-buffer limit, and the CPU-built data kept per table.
import { LimnError } from './container.mjs';

// Concatenates stencil tables as subdivision_draw.cpp's appendRows: starts rebased, one row more
// per table; returns the first row of each table.
export function appendRows(tables, withWeights) {
  let rows = 0, entries = 0;
  for (const t of tables) { rows += t.rows + 1; entries += t.index.length; }
  const starts = new Uint32Array(Math.max(rows, 1)), index = new Uint32Array(Math.max(entries, 1));
  const weight = withWeights ? new Float32Array(Math.max(entries, 1)) : null;
  const firstRows = [];
  let r = 0, e = 0;
  for (const t of tables) {
    firstRows.push(r);
    for (let i = 0; i <= t.rows; i++) starts[r++] = e + t.start[i];
    index.set(t.index, e);
    if (withWeights) weight.set(t.weight, e);
    e += t.index.length;
  }
  return { starts, index, weight, firstRows };
}

// subdivision_draw.cpp's checkFixedSize: refuses, before building it, a fixed tessellation
// whose index or vertex buffer would pass WebGPU's 128 MiB storage-buffer limit.
export function checkFixedSize(tables, tessCap) {
  const N = tables.depth, cap = 2 ** Math.floor(Math.log2(Math.max(tessCap, 1)));
  let triangles = 0, points = 0;
  const add = (size, level) => {
    const W = size * 2 ** N, S = Math.min(Math.min(2 ** (N - level), cap), Math.max(W, 1));
    triangles += 2 * S * S;
    points += S * S;
  };
  const pw = tables.patches, pf = new Float32Array(pw.buffer, pw.byteOffset, pw.length);
  for (let i = 0; i < tables.patchCount; i++) add(pf[24 * i + 19], pw[24 * i + 20] & 0xff);
  const qf = new Float32Array(tables.irregular.buffer);
  for (let i = 0; i < tables.irregularCount; i++) add(qf[8 * i + 7], N);
  const limit = 128 * 2 ** 20, indexBytes = triangles * 12, vertexBytes = points * 16;
  if (indexBytes <= limit && vertexBytes <= limit) return;
  throw new LimnError(`the fixed tessellation (--edge-pixels 0) would draw about ${triangles} triangles: GPU buffer ` +
    `'${indexBytes > limit ? 'triangle indices' : 'tessellation vertices'}' would need about ${(Math.max(indexBytes, vertexBytes) / 2 ** 20).toFixed(1)} MiB, ` +
    "over WebGPU's 128 MiB storage-buffer limit; use a lower --tess, or tables of lower depth (limn-tables --depth)", 'input');
}

// subdivision_draw.cpp's checkTableSize: refuses, before anything is built, tables whose own GPU
// buffers would pass WebGPU's 128 MiB storage-buffer limit, whatever the tessellation. The
// patches buffer is counted as uploaded: the regular patches and, after them, the irregular
// faces' quadtree nodes, sub-patches, smooth faces and per-valence basis records (TBLS v3).
export function checkTableSize(tables, face, stencil) {
  const limit = 128 * 2 ** 20;
  const sized = [['table vertices', tables.totalVertices * 16], ['face-point indices', face.index.byteLength],
    ['stencil indices', stencil.index.byteLength], ['limit points', tables.limitCount * 32],
    ['patches', tables.patches.byteLength], ['irregular faces', tables.irregular.byteLength]];
  for (const [name, bytes] of sized) {
    if (bytes > limit) {
      throw new LimnError(`GPU buffer '${name}' would need ${(bytes / 2 ** 20).toFixed(1)} MiB, over WebGPU's 128 MiB storage-buffer ` +
        'limit, whatever the tessellation; use feature-adaptive tables (limn-tables without --uniform) or a lower --depth', 'input');
    }
  }
}

// The CPU-built tessellations of a loaded surface, kept with its tables (they are never written
// after they are built): renderers of one surface with other views, sizes or shades share them.
const builtFor = new WeakMap();
export function cached(tables, key, build) {
  let m = builtFor.get(tables);
  if (!m) builtFor.set(tables, (m = new Map()));
  if (!m.has(key)) m.set(key, build());
  return m.get(key);
}
