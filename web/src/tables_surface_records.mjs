// TBLS version 5's records of the irregular faces' surface (formats/tbls.md, "Per-valence bases
// as programs, and compact per-face records"; lib/subdiv/tables_surface_records.cpp): each basis
// as its one-level program, expanded here to the weights limn-tables computes, bit for bit; the
// quadtree nodes and the smooth faces as varint streams. Every count and index is checked as the
// C++ reader checks it.
import { MAX_STENCIL_WEIGHT, Stream } from './tables_stream.mjs';
import { readChainBasis } from './tables_chain_records.mjs';
import { readDictionaryProgram } from './tables_program_dictionary.mjs';

const MAX_DEPTH = 16;
const MAX_BASIS_VALENCE = 64; // kMaxBasisValence (lib/subdiv/tables.h)
// A program has 2n + 17 rows of about five entries; these bound a hostile one's expansion.
const MAX_ROWS_PER_POINT = 2, MAX_ENTRIES_PER_ROW = 16;
const NODE_NONE = 0xffffffff, NODE_INDEX = (1 << 30) - 1;

// lib/subdiv/irregular_basis.cpp's expandIrregularBasis: per band, every row the sum of its
// entries in order, in double (JS numbers; no fused multiply-add), an averaged row divided by its
// count, each weight rounded to float once (Float32Array's store rounds to nearest even, as
// static_cast<float>); the next band reads the rows of the next support.
// `M`: the support size (2n + 8 for a per-valence basis; FVSF version 3's boundary
// configurations store theirs).
export function expandBasis(p, M, levels) {
  const T = p.averaged.length;
  let input = new Float64Array(M * M), next = new Float64Array(M * M);
  for (let i = 0; i < M; i++) input[i * M + i] = 1;
  const values = new Float64Array(T * M);
  const weights = new Float32Array(levels * 48 * M);
  for (let band = 0; band < levels; band++) {
    values.fill(0);
    for (let r = 0; r < T; r++) {
      const o = r * M;
      for (let e = p.start[r]; e < p.start[r + 1]; e++) {
        const s = p.source[e], from = s < M ? input : values, at = (s < M ? s : s - M) * M;
        if (p.averaged[r]) {
          for (let c = 0; c < M; c++) values[o + c] += from[at + c];
        } else {
          const w = p.weight[e];
          for (let c = 0; c < M; c++) values[o + c] += w * from[at + c];
        }
      }
      if (p.averaged[r]) {
        const d = p.start[r + 1] - p.start[r];
        for (let c = 0; c < M; c++) values[o + c] /= d;
      }
    }
    for (let j = 0; j < 48; j++) weights.set(values.subarray(p.controlRow[j] * M, p.controlRow[j] * M + M), (band * 48 + j) * M);
    for (let i = 0; i < M; i++) next.set(values.subarray(p.nextSupport[i] * M, p.nextSupport[i] * M + M), i * M);
    [input, next] = [next, input];
  }
  return weights;
}

// One basis: u32 valence, u32 levels, the program's weight palette, then its stream.
export function readBasisProgram(r, index, earlier) {
  const what = `irregular basis ${index}`;
  const valence = r.u32(), levels = r.u32();
  if (valence < 3 || valence > MAX_BASIS_VALENCE || levels < 1 || levels > MAX_DEPTH) {
    r.fail(`${what} has a bad valence or level count (valence 3 to ${MAX_BASIS_VALENCE}, 1 to ${MAX_DEPTH} levels)`);
  }
  if (earlier.some((b) => b.valence === valence)) r.fail(`${what} repeats valence ${valence}`);
  const M = 2 * valence + 8;
  const weights = expandBasis(readProgram(r, what, M, 0), M, levels);
  // Sums of bounded weights can still grow past any bound.
  for (const x of weights) if (!(Math.abs(x) <= MAX_STENCIL_WEIGHT)) r.fail(`${what} has a bad weight`);
  return { valence, levels, support: M, weights };
}

// A basis with its configuration (FVSF version 3, TBLS version 7; tables_surface_records.cpp's
// readConfigurationBasis): u32 valence, u32 configuration (0 interior, else 1 | corner << 1 |
// position << 2), u32 support size, u32 levels, then its program; its expanded weights in [0, 1]
// (interior: Catmull-Clark's smooth weights are convex) or [-4, 5] (a boundary configuration's
// phantom points, 2 a - b; corners 4 a - 2 b - 2 c + d).
// TBLS version 8 (`chains`: the programs its chains brought so far): configuration 2 is a
// decaying-crease chain (tables_chain_records.mjs).
// TBLS version 9 (`dictionary`, tables_program_dictionary.mjs): the program in a stream after the
// header, its rows through the chunk's dictionary; a chain's fields as varints.
export function readConfigurationBasis(r, what, earlier, chains = null, dictionary = null) {
  const valence = r.u32(), code = r.u32(), M = r.u32(), levels = r.u32();
  if (chains && code === 2) return readChainBasis(r, what, valence, M, levels, earlier, chains, dictionary);
  const boundary = (code & 1) !== 0, position = code >>> 2;
  if (valence < 1 || valence > MAX_BASIS_VALENCE || levels < 1 || levels > MAX_DEPTH ||
      (boundary && position >= valence) || (!boundary && (code !== 0 || valence < 3 || valence === 4 || M !== 2 * valence + 8)) ||
      M < 4 || M > 2 * MAX_BASIS_VALENCE + 8) {
    r.fail(`${what} has a bad configuration, support size or level count`);
  }
  if (earlier.some((x) => !x.chain && x.valence === valence && x.code === code)) r.fail(`${what} repeats a configuration`);
  // A boundary sub-patch has at most 7 phantom points, each one row.
  const phantomRows = boundary ? 21 : 0;
  let program;
  if (dictionary) {
    const s = new Stream(r, what);
    program = readDictionaryProgram(s, M, MAX_ROWS_PER_POINT * M + phantomRows, M, false, dictionary);
    s.finish();
  } else {
    program = readProgram(r, what, M, phantomRows);
  }
  const weights = expandBasis(program, M, levels);
  const [lo, hi] = boundary ? [-4, 5] : [0, 1];
  for (const w of weights) if (!(w >= lo && w <= hi)) r.fail(`${what} has a weight outside [${lo}, ${hi}]`);
  return { valence, code, boundary, levels, support: M, weights, program };
}

// A program alone (u32 palette size, the palette, the stream) over M support points, with
// `phantomRows` more rows than TBLS allows (FVSF version 3's boundary configurations); the C++
// readProgram's checks.
export function readProgram(r, what, M, phantomRows) {
  const palette = r.array(Float32Array, r.u32(`${what} palette size`), `${what} palette`);
  for (const x of palette) if (!(Math.abs(x) <= MAX_STENCIL_WEIGHT)) r.fail(`${what} has a bad weight`);
  const s = new Stream(r, what);
  const rows = s.varint();
  if (rows === 0 || rows > MAX_ROWS_PER_POINT * M + phantomRows) s.fail(`bad row count ${rows}`);
  const maxEntries = rows * MAX_ENTRIES_PER_ROW;
  const start = new Uint32Array(rows + 1), averaged = new Uint8Array(rows);
  const source = new Uint32Array(maxEntries), weight = new Float32Array(maxEntries);
  let n = 0;
  for (let row = 0; row < rows; row++) {
    const head = s.varint(), length = Math.floor(head / 2);
    if (length === 0 || length > maxEntries - n) s.fail(`row ${row} has a bad length`);
    averaged[row] = head % 2;
    for (let e = 0; e < length; e++, n++) {
      const x = s.varint();
      if (x >= M + row) s.fail(`row ${row} reads neither a support point nor an earlier row`);
      source[n] = x;
      if (averaged[row]) { weight[n] = 1; continue; }
      const slot = s.varint();
      if (slot >= palette.length) s.fail('a weight is not in the palette');
      weight[n] = palette[slot];
    }
    start[row + 1] = n;
  }
  const rowIndex = () => {
    const x = s.varint();
    if (x >= rows) s.fail('a control point or support point names a missing row');
    return x;
  };
  const controlRow = Uint32Array.from({ length: 48 }, rowIndex);
  const nextSupport = Uint32Array.from({ length: M }, rowIndex);
  s.finish();
  return { start, source, weight, averaged, controlRow, nextSupport };
}

// The quadtree nodes: per node a varint (its first code << 1 | all four equal), then the other
// three codes unless equal; a code is 0 (none) or 1 + kind + 4 * zigzag(index - next[kind]).
export function readNodeStream(r, count) {
  const s = new Stream(r, 'irregular nodes');
  if (count > s.size) s.fail(`count ${count} is too large`);
  const next = [0, 0, 0, 0];
  const code = (z) => {
    if (z === 0) return NODE_NONE;
    const kind = (z - 1) % 4, d = Math.floor((z - 1) / 4);
    const x = next[kind] + (d % 2 === 1 ? -(d + 1) / 2 : d / 2);
    if (x < 0 || x > NODE_INDEX) s.fail('a child index out of range');
    next[kind] = x + 1;
    return (kind * 2 ** 30 + x) >>> 0;
  };
  const codes = new Uint32Array(count * 4);
  for (let i = 0; i < count; i++) {
    const head = s.varint();
    codes[4 * i] = code(Math.floor(head / 2));
    for (let q = 1; q < 4; q++) codes[4 * i + q] = head % 2 ? codes[4 * i] : code(s.varint());
  }
  s.finish();
  return codes;
}

// The smooth faces: basis << 2 | corner, then `first` as a difference from the end of the
// previous face's points.
export function readSmoothFaces(r, count, bases) {
  const s = new Stream(r, 'smooth irregular faces');
  if (count > Math.floor(s.size / 2)) s.fail(`count ${count} is too large`);
  const faces = [];
  let end = 0;
  for (let i = 0; i < count; i++) {
    const head = s.varint(), basis = Math.floor(head / 4);
    if (basis >= bases.length) s.fail(`face ${i} names a missing basis`);
    const first = s.after(end, "a face's first point");
    faces.push({ basis, corner: head % 4, first });
    end = Math.min(first + bases[basis].support, 0xffffffff);
  }
  s.finish();
  return faces;
}

// The smooth points: runs of points at one level N + j (0 <= j < K; below N, the supports of
// smooth faces in the quadtrees), each a varint j, a varint count >= 1, then per point a varint
// c + 3 * zigzag(v - last[c]), c its class at that level (face, edge or vertex points) and
// last[c] the previous point of that class in the run (the class's first at first). `levels`
// are the chunk's levels 0..D.
export function readSmoothPoints(r, count, levels, depth, D) {
  const s = new Stream(r, 'smooth irregular points');
  if (count > s.size) s.fail(`count ${count} is too large`);
  const deepest = Math.min(depth + Math.max(D - depth, 1) - 1, levels.length - 1);
  const points = new Uint32Array(count);
  for (let i = 0; i < count;) {
    const j = s.varint(), n = s.varint();
    if (j > deepest - depth) s.fail(`a run at level N + ${j} (levels N to N + ${deepest - depth})`);
    if (n === 0 || n > count - i) s.fail(`a run of ${n} points (${count - i} left)`);
    const L = levels[depth + j];
    const range = [L.first, L.first + L.facePoints, L.first + L.facePoints + L.edgePoints, L.first + L.count];
    const last = range.slice(0, 3);
    for (const end = i + n; i < end; i++) {
      const z = s.varint(), c = z % 3, d = Math.floor(z / 3);
      const x = last[c] + (d % 2 === 1 ? -(d + 1) / 2 : d / 2);
      if (!(x >= range[c] && x < range[c + 1])) s.fail("a point is not at its run's level");
      points[i] = last[c] = x;
    }
  }
  s.finish();
  return points;
}
