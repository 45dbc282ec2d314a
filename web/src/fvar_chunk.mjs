// The FVSF chunk (formats/limn.md, section 9): the smooth face-varying UV surface limn-tables
// writes beside TBLS, as shaders/fvar_eval.glsl reads it: a quadtree per ptex face (nodes) and
// per element a record of 9 vec4. Checked as lib/subdiv/fvar_chunk.cpp checks it, so that no
// walk leaves the nodes and no record names what is not there. Version 2 stores a face with a
// per-valence basis as a smooth face (support UVs; the basis once per valence, as its one-level
// program like TBLS version 5's), expanded here into the pieces the GPU draws with the same
// arithmetic as lib/subdiv/fvar_expand.cpp (the same bits). Version 3 does the same for faces
// around one UV boundary vertex, with a basis per configuration.
import { chunkReader } from './container.mjs';
import { Stream } from './tables_stream.mjs';
import { readBasisProgram, readConfigurationBasis } from './tables_surface_records.mjs';

const MAX_DEPTH = 16;
const MAX_BASIS_VALENCE = 64; // kMaxBasisValence
const HOLE = 0xffffffff, LEAF = 0x80000000;

/**
 * expected: { depth (TBLS's), ptexCount (the mesh's), topologyHash and uvHash (BigInt, the
 * mesh's), domains (optional): TBLS's element domains, [ptex, u0, v0, size] each }. Returns { depth, ptexCount, nodes: Uint32Array, records: Float32Array (36 floats
 * an element), elementCount }.
 */
export function decodeFvarSurface(chunk, expected) {
  const r = chunkReader(chunk, 3);
  const depth = r.u32('depth');
  if (depth > MAX_DEPTH) r.fail(`depth ${depth} is out of range`);
  const ptexCount = r.u32('ptex count');
  const topology = r.u64('topology hash'), uv = r.u64('UV hash');
  const nodeCount = r.u32('node count'), elementCount = r.u32('element count');
  if (nodeCount < ptexCount) r.fail('fewer nodes than ptex faces');
  const nodes = r.array(Uint32Array, nodeCount, 'nodes');
  if (elementCount > Math.floor(r.remaining / 144)) r.fail('element count is too large');
  const records = r.array(Float32Array, elementCount * 36, 'records');
  const smooth = chunk.version >= 2 ? readSmoothFaces(r, chunk.version) : { faces: [], points: new Float32Array(0), bases: [] };
  r.requireEnd();
  const named = elementCount + smooth.faces.length;
  for (let i = 0; i < nodeCount; i++) {
    const v = nodes[i];
    if (v === HOLE) continue;
    if (v >= LEAF) {
      if (v - LEAF >= named) r.fail(`node ${i} names a missing element`);
    } else if (v <= i || v < ptexCount || v + 4 > nodeCount) {
      r.fail(`node ${i} has a bad child index`); // children after their parent: every walk ends
    }
  }
  for (let i = 0; i < records.length; i++) if (!Number.isFinite(records[i]) || Math.abs(records[i]) > 1e18) r.fail('a record is not finite');
  for (let e = 0; e < elementCount; e++) {
    const [u0, v0, size, kind] = records.subarray(36 * e, 36 * e + 4);
    if (!(size > 0 && size <= 1 && u0 >= 0 && v0 >= 0 && u0 + size <= 1 && v0 + size <= 1) || (kind !== 0 && kind !== 1)) {
      r.fail(`element ${e} has a bad domain`);
    }
  }
  // Each node's square of its ptex face, from its parent's (children follow their parent): a
  // leaf's record must cover exactly its square, or a walk that ends there evaluates the element
  // far outside its domain (a size of 1e-30 gave Inf UVs and NaN displaced points); a node
  // reached twice or deeper than the GPU's walk (24 levels, fvar_eval.glsl) is refused.
  const level = new Int32Array(nodeCount).fill(-1), ci = new Uint32Array(nodeCount), cj = new Uint32Array(nodeCount);
  level.fill(0, 0, ptexCount);
  for (let n = 0; n < nodeCount; n++) {
    const v = nodes[n];
    if (level[n] < 0 || v === HOLE) continue;
    if (v >= LEAF && v - LEAF >= elementCount) { // a smooth face
      const f = smooth.faces[v - LEAF - elementCount];
      if (f.size !== 0) r.fail(`node ${n} names a smooth face named before`);
      if (level[n] + smooth.bases[f.basis].levels > 24) r.fail(`node ${n}'s smooth face is deeper than 24 levels`);
      f.node = n; f.size = Math.fround(2 ** -level[n]); f.u0 = Math.fround(ci[n] * f.size); f.v0 = Math.fround(cj[n] * f.size);
      continue;
    }
    if (v >= LEAF) {
      const o = 36 * (v - LEAF), size = 2 ** -level[n];
      if (records[o] !== ci[n] * size || records[o + 1] !== cj[n] * size || records[o + 2] !== size) {
        r.fail(`node ${n} names element ${v - LEAF}, whose domain is not the node's square`);
      }
      continue;
    }
    if (level[n] >= 24) r.fail(`node ${n} is deeper than 24 levels`);
    for (let k = 0; k < 4; k++) {
      if (level[v + k] >= 0) r.fail(`node ${v + k} has two parents`);
      level[v + k] = level[n] + 1; ci[v + k] = 2 * ci[n] + (k & 1); cj[v + k] = 2 * cj[n] + (k >> 1);
    }
  }
  for (const f of smooth.faces) if (f.size === 0) r.fail('a smooth face is named by no node');
  if (ptexCount !== expected.ptexCount) r.fail("ptex face count differs from the mesh's");
  if (depth !== expected.depth) r.fail(`made at depth ${depth}, but the tables (TBLS) have depth ${expected.depth}; re-run limn-tables`);
  if (topology !== expected.topologyHash) r.fail('the smooth UV surface was built for a different mesh topology or tags; re-run limn-tables');
  if (uv !== expected.uvHash) r.fail('the smooth UV surface was built from other UVs; re-run limn-tables');
  if (expected.domains) checkCoverage(r, nodes, expected.domains);
  const expanded = expandSmoothFaces(nodes, records, smooth);
  return { depth, ptexCount, nodes: expanded.nodes, records: expanded.records, elementCount: expanded.records.length / 36 };
}

// Version 2's per-valence bases and version 3's configurations (as programs), the distinct
// support and limit UVs, and the smooth faces (fvar_chunk.cpp's readSmoothFaces), each count
// checked against the bytes left before anything is allocated.
function readSmoothFaces(r, version) {
  const basisCount = r.u32('basis count');
  if (basisCount > Math.floor(r.remaining / 8)) r.fail('basis count is too large');
  const bases = [];
  for (let b = 0; b < basisCount; b++) {
    let basis;
    if (version >= 3) {
      // TBLS version 7's reader: the configuration checked, its weights' range too.
      basis = readConfigurationBasis(r, `basis ${b}`, bases);
    } else {
      // TBLS version 5's reader (tables_surface_records.mjs): each basis its one-level program,
      // checked and expanded to limn-tables's weights, bit for bit; no valence twice.
      basis = readBasisProgram(r, b, bases);
      // limn-tables builds no basis of valence 4 (regular).
      if (basis.valence === 4) r.fail(`basis ${b} has valence 4`);
      basis.code = 0;
      // Smooth weights are convex (irregular_basis.h).
      for (const w of basis.weights) if (!(w >= 0 && w <= 1)) r.fail(`basis ${b} has a weight outside [0, 1]`);
    }
    bases.push(basis);
  }
  const valueCount = r.u32('value count');
  const values = r.array(Float32Array, valueCount * 2, 'values');
  for (const x of values) if (!Number.isFinite(x) || Math.abs(x) > 1e18) r.fail('a value is not finite');
  const count = r.u32('smooth face count');
  const s = new Stream(r, 'smooth faces');
  // Each face takes at least 2 + support >= 6 bytes of the stream (2n + 10 >= 16 for an interior
  // one), and gives 8 bytes a point.
  if (count > Math.floor(s.size / (version >= 3 ? 6 : 16))) r.fail('smooth face count is too large');
  const faces = [], points = [];
  let previous = 0;
  const next = (i) => {
    previous = s.after(previous, 'a value index');
    if (previous >= valueCount) r.fail(`smooth face ${i} names a missing value`);
    return [values[2 * previous], values[2 * previous + 1]];
  };
  for (let i = 0; i < count; i++) {
    // Version 2 names the basis by its valence, version 3 by its index.
    const packed = s.varint(), x = Math.floor(packed / 4);
    const basis = version >= 3 ? x : bases.findIndex((b) => b.valence === x);
    if (!(basis >= 0 && basis < bases.length)) r.fail(`smooth face ${i} has no basis`);
    const f = { corner: packed % 4, basis, firstPoint: points.length / 2, limit: next(i), node: 0, u0: 0, v0: 0, size: 0 };
    for (let k = 0; k < bases[basis].support; k++) points.push(...next(i));
    faces.push(f);
  }
  s.finish();
  return { faces, points: Float32Array.from(points), bases };
}

// The band frame (a, c) has the extraordinary corner at (0, 0); the face-local square whose band
// square is [a0, a0 + h] x [c0, c0 + h] (fvar_expand.cpp's bandSquareToFace).
function bandSquareToFace(corner, a0, c0, h) {
  if (corner === 0) return [a0, c0];
  if (corner === 1) return [1 - c0 - h, a0];
  if (corner === 2) return [1 - a0 - h, 1 - c0 - h];
  return [c0, 1 - a0 - h];
}

// lib/subdiv/fvar_expand.cpp's expandSmoothFaces, step for step (double sums in the same order,
// rounded to float once): each smooth face's band sub-patches and leaf, appended as elements and
// as children of its node.
function expandSmoothFaces(nodesIn, recordsIn, { faces, points, bases }) {
  if (faces.length === 0) return { nodes: nodesIn, records: recordsIn };
  const nodes = Array.from(nodesIn), out = Array.from(recordsIn);
  let next = recordsIn.length / 36;
  const insert = (start, level, s0, t0, e) => {
    const i = Math.round(s0 * 2 ** level), j = Math.round(t0 * 2 ** level);
    let node = start;
    for (let l = 0; l < level; l++) {
      if (nodes[node] === HOLE) { nodes[node] = nodes.length; nodes.push(HOLE, HOLE, HOLE, HOLE); }
      const shift = level - 1 - l;
      node = nodes[node] + ((i >>> shift) & 1) + 2 * ((j >>> shift) & 1);
    }
    nodes[node] = (LEAF | e) >>> 0;
  };
  for (const f of faces) {
    const { levels: K, weights, support: M } = bases[f.basis], first = 2 * f.firstPoint;
    nodes[f.node] = HOLE;
    const control = (k, q) => { // P[i][j] of band k's quadrant q, [x, y] each
      const base = ((k - 1) * 3 + (q - 1)) * 16 * M, P = [[], [], [], []];
      for (let j = 0; j < 16; j++) {
        let x = 0, y = 0;
        for (let i = 0; i < M; i++) {
          const w = weights[base + j * M + i];
          x += w * points[first + 2 * i];
          y += w * points[first + 2 * i + 1];
        }
        P[j % 4][j >> 2] = [x, y];
      }
      return P;
    };
    const record = (s0, t0, h, kind) => out.push(Math.fround(f.u0 + s0 * f.size), Math.fround(f.v0 + t0 * f.size), Math.fround(h * f.size), kind);
    const corners = [null, null, null, null];
    for (let k = 1; k <= K; k++) {
      const h = 2 ** -k;
      for (let q = 1; q <= 3; q++) {
        const P = control(k, q);
        const Q = (i, j) => (f.corner === 0 ? P[i][j] : f.corner === 1 ? P[j][3 - i] : f.corner === 2 ? P[3 - i][3 - j] : P[3 - j][i]);
        const [s0, t0] = bandSquareToFace(f.corner, q === 3 ? 0 : h, q === 1 ? 0 : h, h);
        insert(f.node, k, s0, t0, next++);
        record(s0, t0, h, 0);
        for (let c = 0; c < 16; c++) out.push(...Q(c % 4, c >> 2));
        if (k === K) { // the B-spline at (0, 0): (1, 4, 1)/6 in each direction
          const b = [1 / 6, 4 / 6, 1 / 6];
          let vx = 0, vy = 0;
          for (let j = 0; j < 3; j++) {
            let rx = 0, ry = 0;
            for (let i = 0; i < 3; i++) { rx += b[i] * P[i][j][0]; ry += b[i] * P[i][j][1]; }
            vx += b[j] * rx; vy += b[j] * ry;
          }
          corners[q] = [vx, vy];
        }
      }
    }
    corners[0] = f.limit;
    const h = 2 ** -K, [s0, t0] = bandSquareToFace(f.corner, 0, 0, h);
    insert(f.node, K, s0, t0, next++);
    record(s0, t0, h, 1);
    const ds = [0, 1, 1, 0], dt = [0, 0, 1, 1];
    for (let p = 0; p < 4; p++) {
      const da = f.corner === 0 ? ds[p] : f.corner === 1 ? dt[p] : f.corner === 2 ? 1 - ds[p] : 1 - dt[p];
      const dc = f.corner === 0 ? dt[p] : f.corner === 1 ? 1 - ds[p] : f.corner === 2 ? 1 - dt[p] : ds[p];
      out.push(...corners[da === 0 ? (dc === 0 ? 0 : 3) : (dc === 0 ? 1 : 2)]);
    }
    for (let z = 0; z < 24; z++) out.push(0);
  }
  return { nodes: Uint32Array.from(nodes), records: Float32Array.from(out) };
}

// Every point the tables draw finds a UV element: walking toward an element's domain meets no
// hole, and below the node of its square there is none (a hole is a face the tables do not
// draw). Else the seam fix's walks (smooth_uvs.mjs) would end in a hole. Children follow their
// parent, so one backward pass knows for every node whether a hole lies below it.
function checkCoverage(r, nodes, domains) {
  const holeBelow = new Uint8Array(nodes.length);
  for (let i = nodes.length - 1; i >= 0; i--) {
    const v = nodes[i];
    holeBelow[i] = v === HOLE ? 1 : v >= LEAF ? 0 : holeBelow[v] | holeBelow[v + 1] | holeBelow[v + 2] | holeBelow[v + 3];
  }
  for (const [ptex, u0, v0, size] of domains) {
    let node = ptex, ou = 0, ov = 0, s = 1;
    for (;;) {
      const v = nodes[node];
      if (v >= LEAF && v !== HOLE) break;
      if (v === HOLE || s <= size) {
        if (holeBelow[node]) r.fail(`no UV element where the tables draw ptex face ${ptex} at (${u0}, ${v0})`);
        break;
      }
      s /= 2;
      const i = u0 >= ou + s ? 1 : 0, j = v0 >= ov + s ? 1 : 0;
      ou += i * s; ov += j * s;
      node = v + i + 2 * j;
    }
  }
}
