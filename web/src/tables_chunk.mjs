// The TBLS chunk (formats/limn.md, section 7; versions 1 to 9) as the WebGPU runtime reads it:
// every count, index and stencil entry checked as lib/subdiv/tables_chunk.cpp checks it, so that
// nothing out of range reaches the GPU; the irregular faces' quadtrees packed as the shaders read
// them. loadLimn (chunks.mjs) calls decodeTables after MESH and TAGS.
import { Fnv64, LimnError, bytesOf, chunkReader } from './container.mjs';
import { MAX_STENCIL_WEIGHT, Stream, readCompactStencils, readLevels } from './tables_stream.mjs';
import { readBasisProgram, readConfigurationBasis, readNodeStream, readSmoothFaces, readSmoothPoints } from './tables_surface_records.mjs';
import { programDictionary } from './tables_program_dictionary.mjs';

const MAX_DEPTH = 16;
const INFINITE_SHARPNESS = 10;
const MAX_STENCIL_VALENCE = 32767;
const MAX_BASIS_WEIGHT_BYTES = 128 * 2 ** 20; // WebGPU's storage-buffer limit, which the bases' weights share
const MAX_BASIS_VALENCE = 64; // kMaxBasisValence: version 4 bases go no higher (lib/subdiv/tables.h)
// An irregular face's quadtree node codes (lib/subdiv/tables.h): the kind in the top two bits.
const NODE_SUBPATCH = 0, NODE_CHILD = 1 << 30, NODE_LEAF = (2 << 30) >>> 0, NODE_BASIS = (3 << 30) >>> 0;
const NODE_NONE = 0xffffffff, NODE_INDEX = (1 << 30) - 1;

// The hash TBLS records (lib/subdiv/tables.cpp topologyHash).
export function topologyHash(mesh, tags, options) {
  const h = new Fnv64();
  h.update(bytesOf(mesh.faceOffsets)).update(bytesOf(mesh.faceVertices));
  h.update(new Uint8Array([options.boundary, options.creaseMethod, options.triangles, options.fvar]));
  const w = new DataView(new ArrayBuffer(12));
  for (const c of tags?.creases ?? []) {
    w.setUint32(0, c.v0, true); w.setUint32(4, c.v1, true); w.setFloat32(8, c.sharpness, true);
    h.update(new Uint8Array(w.buffer, 0, 12));
  }
  for (const c of tags?.corners ?? []) {
    w.setUint32(0, c.vertex, true); w.setFloat32(4, c.sharpness, true);
    h.update(new Uint8Array(w.buffer, 0, 8));
  }
  h.update(bytesOf(tags?.holes ?? new Uint32Array(0)));
  w.setUint32(0, mesh.vertexCount, true);
  h.update(new Uint8Array(w.buffer, 0, 4));
  return h.value;
}

// `skipEmpty` (version 9): a table of no rows is not stored.
function readStencils(r, what, rows, weights, lo0, hi0, lo1 = 0, hi1 = 0, compact = false, skipEmpty = false) {
  if (skipEmpty && rows === 0) {
    const empty = { rows: 0, start: new Uint32Array(1), index: new Uint32Array(0), weight: weights ? new Float32Array(0) : null };
    return checkStencils(r, empty, what, weights, lo0, hi0, lo1, hi1);
  }
  const n = r.u32(), entries = r.u32(), hasWeights = r.u32();
  const fourth = r.u32(); // version 4: the palette's size; before: reserved
  if (!compact && fourth !== 0) r.fail(`${what}: reserved field is not zero`);
  if (n !== rows) r.fail(`${what}: ${n} rows, expected ${rows}`);
  if (hasWeights !== (weights ? 1 : 0)) r.fail(`${what}: weight flag is wrong`);
  const { start, index, weight } = compact ? readCompactStencils(r, what, rows, entries, weights, fourth) : {
    start: r.array(Uint32Array, rows + 1, `${what} starts`),
    index: r.array(Uint32Array, entries, `${what} indices`),
    weight: weights ? r.array(Float32Array, entries, `${what} weights`) : null,
  };
  return checkStencils(r, { rows, start, index, weight }, what, weights, lo0, hi0, lo1, hi1);
}

// The checks of a stencil table read or expanded (a repeated level's) from the chunk.
function checkStencils(r, table, what, weights, lo0, hi0, lo1 = 0, hi1 = 0) {
  const { rows, start, index, weight } = table;
  const entries = index.length;
  if (start[0] !== 0 || start[rows] !== entries) r.fail(`${what}: row starts do not span the ${entries} entries`);
  for (let i = 0; i < rows; i++) {
    if (start[i + 1] < start[i] || start[i + 1] - start[i] > 65536) r.fail(`${what}: row ${i} has a bad length`);
    if (!weights && start[i + 1] === start[i]) r.fail(`${what}: face point ${i} is empty`);
  }
  for (let i = 0; i < entries; i++) {
    const x = index[i];
    if (!((x >= lo0 && x < hi0) || (x >= lo1 && x < hi1))) r.fail(`${what}: entry ${i} reads vertex ${x} outside the levels it may read`);
    if (weights && !(Math.abs(weight[i]) <= MAX_STENCIL_WEIGHT)) r.fail(`${what}: entry ${i} has weight ${weight[i]}; a stencil weight must be finite and within +-1e6`);
  }
  return table;
}

// Version 6's repeated level (tables_stream.cpp's shiftedStencilTable): the previous level's
// table with each source moved one level on; a source of level l - 2 (below parentFirst) by
// parentFirst - grandFirst, one of level l - 1 by first - parentFirst. The same weights.
function shiftedStencils(previous, grandFirst, parentFirst, first) {
  const index = previous.index.map((x) => x + (x < parentFirst ? parentFirst - grandFirst : first - parentFirst));
  return { rows: previous.rows, start: previous.start.slice(), index, weight: previous.weight ? previous.weight.slice() : null };
}

export const ptexCount = (mesh) => mesh.faceSizes.reduce((n, s) => n + (s === 4 ? 1 : s), 0);

export function decodeTables(chunk, mesh, tags) {
  if (chunk.version > 9) throw new LimnError(`version ${chunk.version} is newer than this reader reads (1 to 9); upgrade limn`, 'chunk TBLS');
  const r = chunkReader(chunk, 9);
  const patchWords = chunk.version >= 2 ? 22 : 21;
  const compact = chunk.version >= 4; // compact stencil tables, patch records, bases and points
  const programs = chunk.version >= 5; // bases as programs, compact nodes and smooth faces
  const depth = r.u32('depth');
  if (depth > MAX_DEPTH) r.fail(`depth ${depth} is out of range`);
  const flags = r.u32('flags');
  if (flags > 1) r.fail('unknown flags');
  const options = { boundary: r.u8(), creaseMethod: r.u8(), triangles: r.u8(), fvar: r.u8() };
  if (options.boundary > 2 || options.creaseMethod > 1 || options.triangles > 1 || options.fvar > 5) r.fail('scheme option out of range');
  // Version 3: the levels refined beyond depth under the irregular faces; before: reserved.
  const extra = r.u32('irregular levels');
  if (chunk.version < 3 && extra !== 0) r.fail('reserved field is not zero');
  if (extra > MAX_DEPTH - depth || (extra && (flags & 1))) r.fail(`irregular levels ${extra} out of range`);
  const D = depth + extra;
  const hash = r.u64('topology hash');
  if (hash !== topologyHash(mesh, tags, options)) {
    throw new LimnError('the subdivision tables were built for a different mesh topology or tags; re-run limn-tables', 'chunk TBLS');
  }
  const totalVertices = r.u32(), P = r.u32('patch count'), Q = r.u32('irregular count'), L = r.u32('limit count');
  const levels = [], v9 = chunk.version >= 9;
  let sum = 0;
  readLevels(r, D + 1, v9).forEach((lv, l) => {
    if (lv.first !== sum) r.fail(`level ${l} does not start where the previous ends`);
    lv.count = lv.facePoints + lv.edgePoints + lv.vertexPoints;
    sum += lv.count;
    if (sum > totalVertices) r.fail('level vertex counts exceed the total');
    levels.push(lv);
  });
  if (sum !== totalVertices) r.fail('level vertex counts do not add up to the total');
  if (levels[0].count !== mesh.vertexCount) r.fail(`level 0 has ${levels[0].count} vertices, the mesh ${mesh.vertexCount}`);
  const facePoints = [], edgePoints = [], vertexPoints = [];
  // Version 6: bit l (2..D) set when level l's stencil tables are level l - 1's, shifted.
  const repeats = chunk.version >= 6 ? r.u32('repeated levels') : 0;
  if ((repeats & ~(((2 ** (D + 1)) - 1) & ~3)) !== 0) r.fail(`repeated levels ${repeats} name a level without a previous one`);
  for (let l = 1; l <= D; l++) {
    const p = levels[l - 1], c = levels[l];
    const end = p.first + p.count, faceEnd = c.first + c.facePoints;
    if ((repeats >>> l) & 1) {
      if (p.facePoints !== c.facePoints || p.edgePoints !== c.edgePoints || p.vertexPoints !== c.vertexPoints) {
        r.fail(`level ${l} repeats level ${l - 1} but has other point counts`);
      }
      const g = levels[l - 2].first, shift = (t) => shiftedStencils(t[t.length - 1], g, p.first, c.first);
      facePoints.push(checkStencils(r, shift(facePoints), `level ${l} face points`, false, p.first, end));
      edgePoints.push(checkStencils(r, shift(edgePoints), `level ${l} edge points`, true, p.first, end, c.first, faceEnd));
      vertexPoints.push(checkStencils(r, shift(vertexPoints), `level ${l} vertex points`, true, p.first, end, c.first, faceEnd));
      continue;
    }
    facePoints.push(readStencils(r, `level ${l} face points`, c.facePoints, false, p.first, end, 0, 0, compact, v9));
    edgePoints.push(readStencils(r, `level ${l} edge points`, c.edgePoints, true, p.first, end, c.first, faceEnd, compact, v9));
    vertexPoints.push(readStencils(r, `level ${l} vertex points`, c.vertexPoints, true, p.first, end, c.first, faceEnd, compact, v9));
  }
  const ptex = ptexCount(mesh), R = 2 ** depth;
  const squares = [];
  const dyadic = (x, most) => Number.isFinite(x) && Number.isInteger(x * 2 ** most);
  // Sub-patches and leaves (drawn = false) lie inside the irregular faces, down to level D.
  const checkDomain = (p, u0, v0, size, what, drawn = true) => {
    if (p >= ptex) r.fail(`${what} refers to ptex face ${p} that does not exist`);
    const most = drawn ? depth : D;
    if (!(size > 0) || !dyadic(size, most) || !dyadic(u0, most) || !dyadic(v0, most) || u0 < 0 || v0 < 0 || u0 + size > 1 || v0 + size > 1) {
      r.fail(`${what} has a domain outside its ptex face or finer than the tables' depth`);
    }
    if (!drawn) return;
    const W = size * R, U0 = u0 * R, V0 = v0 * R;
    if ((W & (W - 1)) !== 0 || U0 % W !== 0 || V0 % W !== 0) r.fail(`${what} has a domain that is not a cell of its ptex face's quadtree`);
    squares.push({ ptex: p, W, U0, V0 });
  };
  // GPU layout: 24 words a patch (surface_eval.glsl's Patch: cv[16], ptex, u0, v0, size, packed,
  // sharpness, 2 words of padding).
  const W = 24;
  // Reads one patch record into w (24 words) / f (its float view).
  // Version 4's records come from a stream (tables_chunk.cpp's writePatches): control points as
  // differences from P11 (0 stays 0), P11 and ptex from the previous record's, the domain in
  // units of 2^-16, the packed word, the sharpness only for single-crease patches.
  let stream = null, lastCorner = 0, lastPtex = 0;
  const readPatch = (w, f, what, drawn, domains) => {
    let packed, sharpness;
    if (stream) {
      w[5] = lastCorner = stream.after(lastCorner, 'a control point');
      for (let k = 0; k < 16; k++) {
        if (k === 5) continue;
        const z = stream.varint();
        const d = z - 1;
        const x = z === 0 ? 0 : w[5] + (d % 2 === 1 ? -(d + 1) / 2 : d / 2);
        if (x < 0 || x > 0xffffffff) stream.fail(`${what}: a control point out of range`);
        w[k] = x;
      }
      if (domains) w[16] = lastPtex = stream.after(lastPtex, 'a ptex face');
      for (let k = 17; k < 20 && domains; k++) {
        const u = stream.varint();
        if (u > 65536) stream.fail(`${what}: a domain outside its ptex face`);
        f[k] = u / 65536;
      }
      packed = stream.varint();
      if (packed > 0xffffff) stream.fail(`${what}: bad level or boundary mask`);
    } else {
      for (let k = 0; k < 16; k++) w[k] = r.u32();
      w[16] = r.u32(); f[17] = r.f32(); f[18] = r.f32(); f[19] = r.f32();
      packed = r.u32();
    }
    w[20] = packed;
    const level = packed & 0xff, boundary = (packed >>> 8) & 0xff, crease = (packed >>> 16) & 0xff;
    if ((packed >>> 24) !== 0 || boundary > 15 || (drawn ? level > depth : level <= depth || level > D)) r.fail(`${what}: bad level or boundary mask`);
    if (stream) sharpness = crease ? stream.rawFloat() : 0;
    else sharpness = chunk.version >= 2 ? r.f32() : 0;

    f[21] = sharpness;
    const oneBit = crease !== 0 && (crease & (crease - 1)) === 0 && crease <= 8;
    if (crease ? !(oneBit && boundary === 0 && sharpness > 0 && sharpness < INFINITE_SHARPNESS) : sharpness !== 0) {
      r.fail(`${what}: bad crease edge or sharpness`);
    }
    const lv = levels[level];
    for (let k = 0; k < 16; k++) {
      const cv = w[k];
      if (cv >= totalVertices || (cv !== 0 && (cv < lv.first || cv >= lv.first + lv.count))) r.fail(`${what} has a control point outside its level`);
    }
    if (domains) checkDomain(w[16], f[17], f[18], f[19], what, drawn);
  };
  // Reads `count` patch records (24 GPU words each); at least 20 bytes a record in a stream, 17
  // without the domain (v6's sub-patches: assignSubPatchDomains sets it from the quadtrees).
  const readPatches = (count, what, drawn) => {
    const domains = drawn || chunk.version < 6;
    if (compact) {
      stream = new Stream(r, `${what}es`);
      if (count > Math.floor(stream.size / (domains ? 20 : 17))) r.fail(`${what} count ${count} is too large`);
      lastCorner = lastPtex = 0;
    } else if (count > Math.floor(r.remaining / (4 * patchWords))) {
      r.fail(`${what} count ${count} is too large`);
    }
    const out = new Uint32Array(count * W);
    for (let i = 0; i < count; i++) {
      const w = out.subarray(W * i, W * i + W);
      readPatch(w, new Float32Array(w.buffer, w.byteOffset, W), `${what} ${i}`, drawn, domains);
    }
    if (stream) stream.finish();
    stream = null;
    return out;
  };
  const patchRecords = readPatches(P, 'patch', true);

  const readFace = (q, qf, what, drawn) => {
    for (let k = 0; k < 4; k++) {
      const c = r.u32();
      if (c >= L) r.fail(`${what} refers to a missing limit point`);
      q[k] = c;
    }
    q[4] = r.u32(); qf[5] = r.f32(); qf[6] = r.f32(); qf[7] = r.f32();
    checkDomain(q[4], qf[5], qf[6], qf[7], what, drawn);
  };
  const readFaces = (n, what, drawn) => {
    const out = new Uint32Array(n * 8), of = new Float32Array(out.buffer);
    for (let i = 0; i < n; i++) readFace(out.subarray(8 * i, 8 * i + 8), of.subarray(8 * i, 8 * i + 8), `${what} ${i}`, drawn);
    return out;
  };
  if (Q > Math.floor(r.remaining / 32)) r.fail('irregular face count is too large');
  const irregularFaces = readFaces(Q, 'irregular face', true);
  const v3 = chunk.version >= 3 ? readIrregularSurface(r, { readPatches, readFaces, compact, programs, depth, levels, Q, D, version: chunk.version, irregularFaces }) : null;
  // The domains tile every ptex face exactly once, or not at all (lib/subdiv/tables_chunk.cpp).
  squares.sort((a, b) => a.ptex - b.ptex);
  for (let first = 0, end = 0; first < squares.length; first = end) {
    const p = squares[first].ptex;
    const present = new Set();
    let area = 0;
    for (end = first; end < squares.length && squares[end].ptex === p; end++) {
      const q = squares[end];
      const key = `${q.W},${q.U0 / q.W},${q.V0 / q.W}`;
      if (present.has(key)) r.fail(`two domains cover the same square of ptex face ${p}`);
      present.add(key);
      area += q.W * q.W;
    }
    for (let k = first; k < end; k++) {
      for (let W = squares[k].W * 2; W <= R; W *= 2) {
        if (present.has(`${W},${Math.floor(squares[k].U0 / W)},${Math.floor(squares[k].V0 / W)}`)) r.fail(`a domain lies inside another one of ptex face ${p}`);
      }
    }
    if (area !== R * R) r.fail(`the domains do not cover ptex face ${p} exactly once`);
  }
  // Limit points read level N (the irregular faces' corners) or level D (the leaves').
  const last = levels[depth], deepest = levels[D];
  const lo = last.first, hi = last.first + last.count, lo1 = deepest.first, hi1 = deepest.first + deepest.count;
  const limitPosition = readStencils(r, 'limit positions', L, true, lo, hi, lo1, hi1, compact, v9);
  const limitTangent1 = readStencils(r, 'limit tangents 1', L, true, lo, hi, lo1, hi1, compact, v9);
  const limitTangent2 = readStencils(r, 'limit tangents 2', L, true, lo, hi, lo1, hi1, compact, v9);
  const limitVertex = r.array(Uint32Array, L, 'limit vertices');
  for (const v of limitVertex) if (!((v >= lo && v < hi) || (v >= lo1 && v < hi1))) r.fail("a limit point's vertex is not at the last level");
  const limitFlags = r.array(Uint32Array, L, 'limit flags');
  for (const f of limitFlags) if (f > 1) r.fail('unknown limit point flag');
  r.requireEnd();
  // The GPU buffers, as subdivision_draw.cpp's patchBuffer() and irregularBuffer(): the patches,
  // then the irregular faces' quadtrees; the irregular faces, then the leaves.
  const surface = packIrregularQuadtrees(P, Q, irregularFaces, v3);
  const patches = new Uint32Array(Math.max(P * W + surface.nodes.length, W));
  patches.set(patchRecords);
  patches.set(surface.nodes, P * W);
  const irregular = new Uint32Array(Math.max(Q * 8 + surface.leaves.length, 8));
  irregular.set(irregularFaces);
  irregular.set(surface.leaves, Q * 8);
  return {
    depth, irregularLevels: extra, uniform: (flags & 1) === 1, options, totalVertices, levels, facePoints, edgePoints, vertexPoints,
    patchCount: P, patches, irregularCount: Q, irregular, limitCount: L, limitPosition, limitTangent1, limitTangent2,
    limitVertex, limitFlags, irregularNodeCount: surface.nodes.length / W,
  };
}

// TBLS version 3's irregular-face surface (lib/subdiv/tables_chunk.cpp): sub-patches, quadtree
// nodes, leaves, per-valence bases, smooth faces and their points, with the C++ reader's checks.
function readIrregularSurface(r, o) {
  const { readPatches, readFaces, compact, programs, depth, levels, Q } = o;
  const subs = r.u32('sub-patch count');
  const subPatches = readPatches(subs, 'sub-patch', false);
  const nodes = r.u32('irregular node count');
  if (!programs && nodes > Math.floor(r.remaining / 16)) r.fail('irregular node count is too large');
  if (nodes && nodes < Q) r.fail('an irregular face has no quadtree');
  const codes = programs ? readNodeStream(r, nodes) : r.array(Uint32Array, nodes * 4, 'irregular nodes');
  const leafCount = r.u32('irregular leaf count');
  if (leafCount > Math.floor(r.remaining / 32)) r.fail('irregular leaf count is too large');
  for (let i = 0; i < nodes; i++) {
    for (let q = 0; q < 4; q++) {
      const c = codes[4 * i + q], x = c & NODE_INDEX, kind = (c & ~NODE_INDEX) >>> 0;
      // Children come after their parent, so every walk ends.
      const ok = c === NODE_NONE || kind === NODE_BASIS || (kind === NODE_SUBPATCH && x < subs) ||
        (kind === NODE_CHILD && x > i && x < nodes) || (kind === NODE_LEAF && x < leafCount);
      if (!ok) r.fail(`irregular node ${i} has a bad child`);
    }
  }
  const leaves = readFaces(leafCount, 'irregular leaf', false);
  const baseCount = r.u32('irregular basis count');
  if (baseCount > Math.floor(r.remaining / 8)) r.fail('irregular basis count is too large');
  const bases = [], chainPrograms = [], dictionary = o.version >= 9 ? programDictionary() : null;
  // Version 7: each with its configuration (a boundary one's support size stored); version 8's
  // decaying-crease chains share their programs across the chunk.
  // The bases' K x 48 x M weights share one GPU storage buffer (WebGPU: 128 MiB at most), and a
  // chain naming programs read before expands a few dozen bytes to up to 1.6 MB: a small damaged
  // file must not ask for gigabytes (lib/subdiv/tables_chunk.cpp).
  let weightCount = 0;
  for (let i = 0; programs && i < baseCount; i++) {
    bases.push(o.version >= 7 ? readConfigurationBasis(r, `irregular basis ${i}`, bases, o.version >= 8 ? chainPrograms : null, dictionary) : readBasisProgram(r, i, bases));
    weightCount += bases[i].weights.length;
    if (weightCount * 4 > MAX_BASIS_WEIGHT_BYTES) r.fail(`irregular bases 0 to ${i} expand to more than 128 MiB of weights`);
  }
  for (let i = 0; !programs && i < baseCount; i++) {
    const valence = r.u32(), lv = r.u32();
    if (valence < 3 || valence > MAX_STENCIL_VALENCE || lv < 1 || lv > MAX_DEPTH) r.fail(`irregular basis ${i} has a bad valence or level count`);
    const support = 2 * valence + 8;
    let weights;
    if (compact) { // each control point names its row of weights; equal rows are stored once
      // Rows are copied per use (up to 768 times): a high or repeated valence would let a few
      // bytes decode to gigabytes; limn-tables writes neither (formats/limn.md).
      if (valence > MAX_BASIS_VALENCE) r.fail(`irregular basis ${i} has valence ${valence}; version 4 bases go up to ${MAX_BASIS_VALENCE}`);
      if (bases.some((b) => b.valence === valence)) r.fail(`irregular basis ${i} repeats valence ${valence}`);
      const distinct = r.u32('irregular basis row count');
      if (distinct === 0 || distinct > lv * 48) r.fail(`irregular basis ${i} has a bad row count`);
      const pick = r.array(Uint16Array, lv * 48, 'irregular basis rows');
      const rows = r.array(Float32Array, distinct * support, 'irregular basis weights');
      weights = new Float32Array(lv * 48 * support);
      pick.forEach((row, j) => {
        if (row >= distinct) r.fail(`irregular basis ${i} names a missing row`);
        weights.set(rows.subarray(row * support, (row + 1) * support), j * support);
      });
    } else {
      weights = r.array(Float32Array, lv * 48 * support, 'irregular basis weights');
    }
    for (const x of weights) if (!(Math.abs(x) <= MAX_STENCIL_WEIGHT)) r.fail(`irregular basis ${i} has a bad weight`);
    bases.push({ valence, levels: lv, support, weights });
    // Stored weights take their bytes in the file, but the GPU buffer is the same one.
    weightCount += weights.length;
    if (weightCount * 4 > MAX_BASIS_WEIGHT_BYTES) r.fail(`irregular bases 0 to ${i} expand to more than 128 MiB of weights`);
  }
  const smoothCount = r.u32('smooth irregular face count');
  if (!programs && smoothCount > Math.floor(r.remaining / 12)) r.fail('smooth irregular face count is too large');
  const smooth = programs ? readSmoothFaces(r, smoothCount, bases) : [];
  for (let i = 0; !programs && i < smoothCount; i++) {
    const f = { basis: r.u32(), corner: r.u32(), first: r.u32() };
    if (f.basis >= baseCount || f.corner > 3) r.fail(`smooth irregular face ${i} is bad`);
    smooth.push(f);
  }
  const points = r.u32('smooth irregular point count');
  let smoothPoints;
  if (programs) {
    smoothPoints = readSmoothPoints(r, points, levels, depth, o.D);
  } else if (compact) { // differences from the previous point
    const s = new Stream(r, 'smooth irregular points');
    if (points > s.size) s.fail(`count ${points} is too large`);
    smoothPoints = new Uint32Array(points);
    for (let i = 0, previous = 0; i < points; i++) smoothPoints[i] = previous = s.after(previous, 'a point');
    s.finish();
  } else {
    smoothPoints = r.array(Uint32Array, points, 'smooth irregular points');
  }
  for (const f of smooth) if (f.first + bases[f.basis].support > points) r.fail("a smooth irregular face's points run past the end");
  const below = checkSmoothFaceLevels(r, { codes, nodes, Q, bases, smooth, smoothPoints, levels, depth, D: o.D, version: o.version });
  if (o.version >= 6) assignSubPatchDomains(r, { codes, nodes, Q, subPatches, subs, irregularFaces: o.irregularFaces, depth });
  return { subPatches, subs, codes, nodes, leaves, bases, smooth, smoothPoints, below };
}

// v6's sub-patches hold no domain (tables_surface_records.cpp's assignSubPatchDomains): each is
// a quadrant of its node's square, down from its irregular face's. Every node below the roots
// and every sub-patch is named exactly once, a sub-patch at its node's level plus one.
function assignSubPatchDomains(r, { codes, nodes, Q, subPatches, subs, irregularFaces, depth }) {
  const W = 24, f32 = new Float32Array(subPatches.buffer, subPatches.byteOffset, subPatches.length);
  const faces = new Float32Array(irregularFaces.buffer, irregularFaces.byteOffset, irregularFaces.length);
  const square = new Array(nodes).fill(null), named = new Uint8Array(subs);
  for (let i = 0; i < Math.min(Q, nodes); i++) square[i] = { ptex: irregularFaces[8 * i + 4], level: depth, u0: faces[8 * i + 5], v0: faces[8 * i + 6], size: faces[8 * i + 7] };
  for (let i = 0; i < nodes; i++) {
    const s = square[i];
    if (!s) r.fail(`irregular node ${i} is in no quadtree`);
    for (let q = 0; q < 4; q++) {
      const c = codes[4 * i + q], kind = (c & ~NODE_INDEX) >>> 0, x = c & NODE_INDEX;
      if (c === NODE_NONE || (kind !== NODE_CHILD && kind !== NODE_SUBPATCH)) continue;
      // Quadrant q = (s >= 1/2) + 2 (t >= 1/2); halving a dyadic float is exact, as in float.
      const half = Math.fround(s.size / 2);
      const child = { ptex: s.ptex, level: s.level + 1, u0: Math.fround(s.u0 + (q & 1 ? half : 0)), v0: Math.fround(s.v0 + (q & 2 ? half : 0)), size: half };
      if (kind === NODE_CHILD) {
        if (square[x]) r.fail(`irregular node ${x} is named twice`);
        square[x] = child;
        continue;
      }
      if (named[x]) r.fail(`sub-patch ${x} is named twice`);
      named[x] = 1;
      const level = subPatches[W * x + 20] & 0xff;
      if (level !== child.level) r.fail(`sub-patch ${x} is at level ${level}, its node's quadrant at ${child.level}`);
      subPatches[W * x + 16] = child.ptex;
      f32[W * x + 17] = child.u0; f32[W * x + 18] = child.v0; f32[W * x + 19] = child.size;
    }
  }
  const missing = named.indexOf(0);
  if (missing >= 0) r.fail(`sub-patch ${missing} is in no quadtree`);
}

const isSmoothRoot = (codes, i) => ((codes[4 * i] & ~NODE_INDEX) >>> 0) === NODE_BASIS &&
  codes[4 * i] === codes[4 * i + 1] && codes[4 * i] === codes[4 * i + 2] && codes[4 * i] === codes[4 * i + 3];

// Smooth faces below level N (version 5; tables_chunk.cpp's checkSmoothFaceLevels): a basis code
// at a root whose four codes are equal is the root's own smooth face; any other names the smooth
// face of its quadrant, a level below its node. Each smooth face is named once, has bands left
// at its level, and its support points are at that level. Returns per smooth face its levels
// below its irregular face.
function checkSmoothFaceLevels(r, { codes, nodes, Q, bases, smooth, smoothPoints, levels, depth, D, version }) {
  const depthOf = new Uint32Array(nodes), levelOf = new Array(smooth.length).fill(-1);
  for (let i = 0; i < nodes; i++) {
    const root = i < Q && isSmoothRoot(codes, i);
    for (let q = 0; q < 4; q++) {
      const c = codes[4 * i + q];
      if (c === NODE_NONE) continue;
      const kind = (c & ~NODE_INDEX) >>> 0, x = c & NODE_INDEX;
      if (kind === NODE_CHILD) depthOf[x] = depthOf[i] + 1;
      if (kind !== NODE_BASIS) continue;
      if (x >= smooth.length) r.fail(`irregular node ${i} has a bad basis code`);
      if (!root && version < 5) r.fail(`irregular node ${i} has a basis code below a root (version 5)`);
      const below = root ? 0 : depthOf[i] + 1;
      if (levelOf[x] !== -1 && !(root && levelOf[x] === depth)) r.fail(`smooth irregular face ${x} is named twice`);
      if (below && (depth + below >= D || below >= bases[smooth[x].basis].levels)) r.fail(`irregular node ${i} names a smooth face too deep`);
      levelOf[x] = depth + below;
    }
  }
  return smooth.map((f, i) => {
    const l = levelOf[i] === -1 ? depth : levelOf[i], L = levels[l];
    for (let k = 0; k < bases[f.basis].support; k++) {
      const v = smoothPoints[f.first + k];
      if (v < L.first || v >= L.first + L.count) r.fail("a smooth irregular point is not at its face's level");
    }
    return l - depth;
  });
}

// subdivision_draw.cpp's packIrregularQuadtrees: the quadtree codes made absolute indices into
// the GPU buffers (surface_eval.glsl), 24 words a record as a Patch. Every irregular face gets a
// root node, with no children where the tables have no quadtree.
function packIrregularQuadtrees(P, Q, irregularFaces, v3) {
  const W = 24;
  if (!v3) v3 = { subPatches: new Uint32Array(0), subs: 0, codes: new Uint32Array(0), nodes: 0, leaves: new Uint32Array(0), bases: [], smooth: [], smoothPoints: new Uint32Array(0), below: [] };
  const nodes = Math.max(Q, v3.nodes);
  const header = [], basisFirst = [];
  let next = P + nodes + v3.subs;
  for (const f of v3.smooth) { header.push(next); next += 1 + Math.ceil(v3.bases[f.basis].support / 16); }
  for (const b of v3.bases) { basisFirst.push(next); next += b.levels * 3 * b.support; }
  const out = new Uint32Array((next - P) * W);
  // Per node its irregular face (children come after their parents); per smooth face the
  // irregular face whose corner it shares.
  const faceOf = new Uint32Array(v3.smooth.length), rootOf = new Uint32Array(v3.nodes);
  for (let i = 0; i < nodes; i++) {
    const g = out.subarray(W * i, W * i + 16);
    g.fill(NODE_NONE);
    if (i >= v3.nodes) continue;
    if (i < Q) rootOf[i] = i;
    for (let q = 0; q < 4; q++) {
      const c = v3.codes[4 * i + q], kind = (c & ~NODE_INDEX) >>> 0, x = c & NODE_INDEX;
      if (c !== NODE_NONE && kind === NODE_CHILD) rootOf[x] = rootOf[i];
      if (c !== NODE_NONE && kind === NODE_BASIS) faceOf[x] = rootOf[i];
      g[q] = c === NODE_NONE ? NODE_NONE
        : kind === NODE_BASIS ? (NODE_BASIS | header[x]) >>> 0
          : kind === NODE_CHILD ? (NODE_CHILD | (P + x)) >>> 0
            : kind === NODE_LEAF ? (NODE_LEAF | (Q + x)) >>> 0
              : (NODE_SUBPATCH | (P + nodes + x)) >>> 0;
    }
  }
  // Sub-patch records are already in the GPU layout (padding words zero).
  out.set(v3.subPatches, W * nodes);
  let at = nodes + v3.subs;
  const of = new Float32Array(out.buffer);
  v3.smooth.forEach((f, i) => {
    const b = v3.bases[f.basis];
    const below = v3.below[i];
    out.set([b.support, f.corner, basisFirst[f.basis], Math.max(1, b.levels - below), irregularFaces[8 * faceOf[i] + f.corner], below], W * at++);
    for (let k = 0; k < b.support; k += 16) {
      for (let j = 0; j < 16 && k + j < b.support; j++) out[W * at + j] = v3.smoothPoints[f.first + k + j];
      at++;
    }
  });
  for (const b of v3.bases) {
    const M = b.support;
    for (let block = 0; block < b.levels * 3; block++) {
      for (let i = 0; i < M; i++, at++) {
        for (let j = 0; j < 16; j++) of[W * at + j] = b.weights[(block * 16 + j) * M + i];
        // A chain's band kind rides on its block's first record (surface_eval_impl basisPatchPoint).
        if (i === 0 && b.chain) { out[W * at + 20] = b.crease[block] << 16; of[W * at + 21] = b.sharpness[block]; }
      }
    }
  }
  return { nodes: out, leaves: v3.leaves };
}
