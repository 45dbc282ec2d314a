// The FVSF chunk (formats/limn.md, section 9): the smooth face-varying UV surface limn-tables
// writes beside TBLS, as shaders/fvar_eval.glsl reads it: a quadtree per ptex face (nodes) and
// per element a record of 9 vec4. Checked as lib/subdiv/fvar_chunk.cpp checks it, so that no
// walk leaves the nodes and no record names what is not there.
import { chunkReader } from './container.mjs';

const MAX_DEPTH = 16;
const HOLE = 0xffffffff, LEAF = 0x80000000;

/**
 * expected: { depth (TBLS's), ptexCount (the mesh's), topologyHash and uvHash (BigInt, the
 * mesh's), domains (optional): TBLS's element domains, [ptex, u0, v0, size] each }. Returns { depth, ptexCount, nodes: Uint32Array, records: Float32Array (36 floats
 * an element), elementCount }.
 */
export function decodeFvarSurface(chunk, expected) {
  const r = chunkReader(chunk, 1);
  const depth = r.u32('depth');
  if (depth > MAX_DEPTH) r.fail(`depth ${depth} is out of range`);
  const ptexCount = r.u32('ptex count');
  const topology = r.u64('topology hash'), uv = r.u64('UV hash');
  const nodeCount = r.u32('node count'), elementCount = r.u32('element count');
  if (nodeCount < ptexCount) r.fail('fewer nodes than ptex faces');
  const nodes = r.array(Uint32Array, nodeCount, 'nodes');
  if (elementCount > Math.floor(r.remaining / 144)) r.fail('element count is too large');
  const records = r.array(Float32Array, elementCount * 36, 'records');
  r.requireEnd();
  for (let i = 0; i < nodeCount; i++) {
    const v = nodes[i];
    if (v === HOLE) continue;
    if (v >= LEAF) {
      if (v - LEAF >= elementCount) r.fail(`node ${i} names a missing element`);
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
  if (ptexCount !== expected.ptexCount) r.fail("ptex face count differs from the mesh's");
  if (depth !== expected.depth) r.fail(`made at depth ${depth}, but the tables (TBLS) have depth ${expected.depth}; re-run limn-tables`);
  if (topology !== expected.topologyHash) r.fail('the smooth UV surface was built for a different mesh topology or tags; re-run limn-tables');
  if (uv !== expected.uvHash) r.fail('the smooth UV surface was built from other UVs; re-run limn-tables');
  if (expected.domains) checkCoverage(r, nodes, expected.domains);
  return { depth, ptexCount, nodes, records, elementCount };
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
