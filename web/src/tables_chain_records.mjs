// TBLS version 8's decaying-crease chains (formats/tbls.md, "Decaying-crease chains";
// lib/subdiv/tables_chain_records.cpp and crease_basis.cpp's expandCreaseChain): a basis record
// of configuration code 2 holds a chain's bands (programs shared across the chunk's chains, three
// quadrant kinds each) and its end, expanded here to the K x 48 x M weights limn-tables computes,
// bit for bit (double sums in program order, phantoms 2 a - b, a regular end's patch split
// band by band, a smooth end's bands its named per-valence basis's program run again, each
// weight rounded to float once), plus per band and quadrant the crease bits and sharpness. Every
// field is checked as the C++ reader checks it.
import { MAX_STENCIL_WEIGHT, Stream } from './tables_stream.mjs';
import { readDictionaryProgram } from './tables_program_dictionary.mjs';

const MAX_DEPTH = 16;
const MAX_BASIS_VALENCE = 64;
const MAX_ROWS_PER_POINT = 3, MAX_ENTRIES_PER_ROW = 16;
const MAX_SUPPORT = 4 * 2 * MAX_BASIS_VALENCE + 16;
const INFINITE_SHARPNESS = 10; // kInfiniteSharpness (lib/topology)
const NONE = 0xffffffff;
const U0 = 8, U1 = 2, V0 = 1, V1 = 4; // PatchBoundary bits (lib/subdiv/tables.h)

function readChainProgram(r, what) {
  const support = r.u32(), next = r.u32();
  if (support < 4 || support > MAX_SUPPORT || next > MAX_SUPPORT) r.fail(`${what} has a bad support size`);
  const palette = r.array(Float32Array, r.u32(`${what} palette size`), `${what} palette`);
  for (const x of palette) if (!(Math.abs(x) <= MAX_STENCIL_WEIGHT)) r.fail(`${what} has a bad weight`);
  const s = new Stream(r, what);
  const rows = s.varint();
  if (rows === 0 || rows > MAX_ROWS_PER_POINT * support) s.fail(`bad row count ${rows}`);
  const maxEntries = rows * MAX_ENTRIES_PER_ROW;
  const start = [0], source = [], weight = [], averaged = [];
  for (let row = 0; row < rows; row++) {
    const head = s.varint(), length = Math.floor(head / 2);
    if (length === 0 || length > maxEntries - source.length) s.fail(`row ${row} has a bad length`);
    const avg = head % 2;
    for (let e = 0; e < length; e++) {
      const x = s.varint();
      if (x >= support + row) s.fail(`row ${row} reads neither a support point nor an earlier row`);
      source.push(x);
      if (avg) { weight.push(1); continue; }
      const slot = s.varint();
      if (slot >= palette.length) s.fail('a weight is not in the palette');
      weight.push(palette[slot]);
    }
    start.push(source.length);
    averaged.push(avg);
  }
  const controlRow = Array.from({ length: 48 }, () => {
    const v = s.varint();
    if (v > rows) s.fail('a control point names a missing row');
    return v === 0 ? NONE : v - 1;
  });
  const nextSupport = Array.from({ length: next }, () => {
    const v = s.varint();
    if (v >= rows) s.fail('a support point names a missing row');
    return v;
  });
  s.finish();
  return { support, rows, start, source, weight, averaged, controlRow, nextSupport };
}

function checkKind(r, bits, sharpness, what) {
  const boundary = bits & 15, crease = (bits >>> 4) & 15;
  if (bits >>> 8 || (crease & (crease - 1)) || (crease & boundary) ||
      !(sharpness >= 0 && sharpness <= INFINITE_SHARPNESS) || (crease && sharpness === 0)) {
    r.fail(`${what} has a bad patch kind`);
  }
  return { boundary, crease, sharpness };
}

function readKind(r, what) {
  const bits = r.u32(), sharpness = r.f32();
  return checkKind(r, bits, sharpness, what);
}

// Version 9: a varint boundary | crease << 4 | how << 8; the sharpness 0 (how 0), the previous
// band's in that quadrant less 1 (1, in float: Math.fround), the previous band's (2) or 4 raw bytes (3).
function readCompactKind(r, s, previous, what) {
  const code = s.varint();
  if (code >= 1024) r.fail(`${what} has a bad patch kind`);
  const how = code >>> 8;
  const sharpness = how === 0 ? 0 : how === 1 ? Math.fround(previous - 1) : how === 2 ? previous : s.rawFloat();
  return checkKind(r, code & 0xff, sharpness, what);
}

// The 16 control points (P[i + 4 j] = P_{i,j}, M columns each) of a band's patch, phantoms folded.
function patchWeights(rowsOf, boundary, values, M) {
  const P = new Float64Array(16 * M);
  for (let j = 0; j < 16; j++) if (rowsOf[j] !== NONE) P.set(values.subarray(rowsOf[j] * M, rowsOf[j] * M + M), j * M);
  const phantom = (o, a, b) => { for (let i = 0; i < M; i++) P[o * M + i] = 2 * P[a * M + i] + -1 * P[b * M + i]; };
  for (let j = 0; j < 4; j++) {
    if (boundary & U0) phantom(4 * j, 4 * j + 1, 4 * j + 2);
    if (boundary & U1) phantom(4 * j + 3, 4 * j + 2, 4 * j + 1);
  }
  for (let i = 0; i < 4; i++) {
    if (boundary & V0) phantom(i, i + 4, i + 8);
    if (boundary & V1) phantom(i + 12, i + 8, i + 4);
  }
  return P;
}

const HALF = [[[0.5, 0.5, 0, 0], [0.125, 0.75, 0.125, 0], [0, 0.5, 0.5, 0], [0, 0.125, 0.75, 0.125]],
  [[0.125, 0.75, 0.125, 0], [0, 0.5, 0.5, 0], [0, 0.125, 0.75, 0.125], [0, 0, 0.5, 0.5]]];

function splitPatch(P, hu, hv, M) {
  const T = new Float64Array(16 * M), Q = new Float64Array(16 * M);
  for (let b = 0; b < 4; b++)
    for (let i = 0; i < 4; i++)
      for (let a = 0; a < 4; a++) {
        const w = HALF[hu][i][a];
        if (w === 0) continue;
        const o = (i + 4 * b) * M, x = (a + 4 * b) * M;
        for (let k = 0; k < M; k++) T[o + k] += w * P[x + k];
      }
  for (let j = 0; j < 4; j++)
    for (let i = 0; i < 4; i++)
      for (let b = 0; b < 4; b++) {
        const w = HALF[hv][j][b];
        if (w === 0) continue;
        const o = (i + 4 * j) * M, x = (i + 4 * b) * M;
        for (let k = 0; k < M; k++) Q[o + k] += w * T[x + k];
      }
  return Q;
}

function expandChain(chain, K, M, endBasis) {
  const weights = new Float32Array(K * 48 * M);
  const crease = new Uint8Array(K * 3), sharpness = new Float32Array(K * 3);
  const store = (k, q, P) => weights.set(P, ((k - 1) * 3 + q) * 16 * M);
  let cur = new Float64Array(M * M), S = M, P = null, k = 0, values = null;
  for (let i = 0; i < M; i++) cur[i * M + i] = 1;
  // One band: program p over the support `cur`, its quadrants' patches stored with `kinds`, the
  // next band's support into `cur` (`values` keeps the band's rows).
  const runBand = (p, kinds) => {
    k++;
    values = new Float64Array(p.averaged.length * M);
    for (let r = 0; r < p.averaged.length; r++) {
      const o = r * M;
      for (let e = p.start[r]; e < p.start[r + 1]; e++) {
        const s = p.source[e], from = s < S ? cur : values, at = (s < S ? s : s - S) * M;
        const w = p.averaged[r] ? 1 : p.weight[e];
        for (let c = 0; c < M; c++) values[o + c] += w * from[at + c];
      }
      if (p.averaged[r]) {
        const d = p.start[r + 1] - p.start[r];
        for (let c = 0; c < M; c++) values[o + c] /= d;
      }
    }
    for (let q = 0; q < 3; q++) {
      store(k, q, patchWeights(p.controlRow.slice(16 * q, 16 * q + 16), kinds[q].boundary, values, M));
      crease[(k - 1) * 3 + q] = kinds[q].crease;
      sharpness[(k - 1) * 3 + q] = kinds[q].sharpness;
    }
    const next = new Float64Array(p.nextSupport.length * M);
    p.nextSupport.forEach((row, i) => next.set(values.subarray(row * M, row * M + M), i * M));
    cur = next;
    S = p.nextSupport.length;
  };
  chain.bands.forEach((band, index) => {
    runBand(band.program, band.kinds);
    if (index === chain.bands.length - 1 && chain.end === 2) P = patchWeights(chain.centreRow, chain.centreKind.boundary, values, M);
  });
  if (chain.end === 2) {
    for (++k; k <= K; k++) {
      store(k, 0, splitPatch(P, 1, 0, M));
      store(k, 1, splitPatch(P, 1, 1, M));
      store(k, 2, splitPatch(P, 0, 1, M));
      P = splitPatch(P, 0, 0, M);
    }
  } else if (chain.end === 1) {
    // The crease has decayed: the smooth face's valence program again and again on the end's
    // support (crease_chain_expand.cpp), each weight rounded to float once.
    const smooth = [0, 1, 2].map(() => ({ boundary: 0, crease: 0, sharpness: 0 }));
    while (k < K) runBand(endBasis.program, smooth);
  }
  return { weights, crease, sharpness };
}

// After the record's u32 valence, code (2), support M and levels K (read by the caller).
// Version 9 (`dictionary`): the fields as varints of one stream, a new program as its next-support
// count and its rows through the chunk's dictionary, the kinds compact.
export function readChainBasis(r, what, valence, M, K, earlier, programs, dictionary = null) {
  const s = dictionary ? new Stream(r, what) : null;
  const number = () => {
    if (!s) return r.u32();
    const x = s.varint();
    if (x > 0xffffffff) s.fail('a number out of range');
    return x;
  };
  const previous = [0, 0, 0];
  const kind = (q, name) => {
    const k = s ? readCompactKind(r, s, previous[q], name) : readKind(r, name);
    previous[q] = k.sharpness;
    return k;
  };
  const end = number();
  const endIndex = end === 1 ? number() : NONE;
  const bands = number();
  if (end > 2 || bands < 1 || bands > K || K < 1 || K > MAX_DEPTH || M < 4 || M > MAX_SUPPORT ||
      (end === 1 && (valence < 3 || valence === 4 || valence > MAX_BASIS_VALENCE || bands === K)) ||
      (end !== 1 && valence !== 0) || (end === 0 && bands !== K)) {
    r.fail(`${what} has a bad end, band count, valence or support size`);
  }
  let endBasis = null;
  if (end === 1) {
    if (endIndex >= earlier.length) r.fail(`${what}'s smooth end names a missing basis`);
    endBasis = earlier[endIndex];
    if (endBasis.chain || endBasis.boundary || endBasis.valence !== valence || endBasis.levels < K - bands) {
      r.fail(`${what}'s smooth end names basis ${endIndex}, not valence ${valence}'s with ${K - bands} bands`);
    }
  }
  const chain = { end, bands: [] };
  let support = M;
  for (let j = 0; j < bands; j++) {
    const band = `${what} band ${j + 1}`;
    const index = number();
    if (index > programs.length) r.fail(`${band} names a missing program`);
    if (index === programs.length && s) { // over this band's support
      const next = s.varint();
      if (next > MAX_SUPPORT) s.fail(`${band} has a bad support size`);
      programs.push({ ...readDictionaryProgram(s, support, MAX_ROWS_PER_POINT * support, next, true, dictionary), support });
    } else if (index === programs.length) {
      programs.push(readChainProgram(r, `${band} program`));
    }
    const program = programs[index];
    if (program.support !== support) r.fail(`${band}'s program reads ${program.support} points, not the band's ${support}`);
    chain.bands.push({ program, kinds: [kind(0, band), kind(1, band), kind(2, band)] });
    support = program.nextSupport.length;
  }
  if (end === 1 ? support !== 2 * valence + 8 : support !== 0) r.fail(`${what}'s last band has a bad next support for its end`);
  if (end === 2) {
    const last = chain.bands[bands - 1].program;
    previous[0] = 0;
    chain.centreKind = kind(0, `${what} end`);
    if (chain.centreKind.crease) r.fail(`${what}'s regular end has a crease`);
    // 0: no row (a boundary phantom, made from the rows beside it), as the control rows store it.
    chain.centreRow = Array.from({ length: 16 }, () => {
      const v = number();
      if (v > last.rows) r.fail(`${what}'s regular end names a missing row`);
      return v === 0 ? NONE : v - 1;
    });
  }
  if (s) s.finish();
  const { weights, crease, sharpness } = expandChain(chain, K, M, endBasis);
  for (const x of weights) if (!(Math.abs(x) <= MAX_STENCIL_WEIGHT)) r.fail(`${what} has a bad weight`);
  return { valence: 0, code: 2, chain: true, boundary: false, levels: K, support: M, weights, crease, sharpness };
}
