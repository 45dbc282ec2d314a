// The chunks the WebGPU runtime reads (formats/limn.md, sections 5-8): MESH, FVUV, TAGS, MATL,
// CLSF, TBLS (versions 1 to 9), SEAM. Every count and index is checked as the C++ readers check it
// (lib/mesh/mesh_chunks.cpp, lib/mesh/mesh.cpp validateMesh, lib/topology/classification.cpp,
// lib/subdiv/tables_chunk.cpp, lib/seams/seams.cpp), so that nothing out of range reaches the GPU.
import { Fnv64, LimnError, bytesOf, chunkReader, parseContainer } from './container.mjs';
import { decodeTables, ptexCount, topologyHash } from './tables_chunk.mjs';
import { decodeFvarSurface } from './fvar_chunk.mjs';

const MAX_COORDINATE = 1e18; // lib/mesh: beyond it a float square overflows

function decodeMesh(chunk) {
  const r = chunkReader(chunk, 1);
  const V = r.u32('vertex count'), F = r.u32('face count'), C = r.u64n('corner count');
  const positions = r.array(Float64Array, V * 3, 'positions');
  const faceSizes = r.array(Uint32Array, F, 'face sizes');
  const faceVertices = r.array(Uint32Array, C, 'face vertices');
  r.requireEnd();
  const where = 'chunk MESH';
  if (V === 0) throw new LimnError('the mesh has no vertices', where);
  if (F === 0) throw new LimnError('the mesh has no faces', where);
  const faceOffsets = new Uint32Array(F + 1);
  let sum = 0;
  for (let f = 0; f < F; f++) {
    sum += faceSizes[f];
    if (sum > C) throw new LimnError(`face sizes add up to more than the ${C} corners (at face ${f})`, where);
    faceOffsets[f + 1] = sum;
  }
  if (sum !== C) throw new LimnError(`face sizes add up to ${sum}, not the ${C} corners stored`, where);
  for (let i = 0; i < V * 3; i++) {
    const x = positions[i];
    if (!Number.isFinite(x)) throw new LimnError(`vertex ${Math.floor(i / 3)} has a non-finite position (NaN or Inf)`, where);
    if (Math.abs(x) > MAX_COORDINATE) throw new LimnError(`vertex ${Math.floor(i / 3)} lies beyond the 1e18 that the GPU's float arithmetic carries; scale the mesh down`, where);
  }
  const seen = new Int32Array(V).fill(-1);
  for (let f = 0; f < F; f++) {
    const a = faceOffsets[f], b = faceOffsets[f + 1];
    if (b - a < 3) throw new LimnError(`face ${f} has ${b - a} vertices; a face needs at least 3`, where);
    for (let i = a; i < b; i++) {
      const v = faceVertices[i];
      if (v >= V) throw new LimnError(`face ${f} refers to vertex ${v} but there are only ${V}`, where);
      if (seen[v] === f) throw new LimnError(`face ${f} is degenerate: it uses vertex ${v} twice`, where);
      seen[v] = f;
    }
  }
  return { vertexCount: V, faceCount: F, positions, faceOffsets, faceVertices, faceSizes };
}

function decodeUVs(chunk, mesh) {
  const r = chunkReader(chunk, 1);
  const N = r.u32('UV count');
  r.zero32();
  const C = r.u64n('corner count');
  if (C !== mesh.faceVertices.length) r.fail(`UV corner count ${C} differs from the mesh's ${mesh.faceVertices.length}`);
  const values = r.array(Float64Array, N * 2, 'UV values');
  const indices = r.array(Uint32Array, C, 'UV indices');
  r.requireEnd();
  for (let i = 0; i < values.length; i++) {
    if (!Number.isFinite(values[i])) throw new LimnError(`UV ${i >> 1} is not finite`, 'chunk FVUV');
  }
  for (let c = 0; c < C; c++) {
    if (indices[c] >= N) throw new LimnError(`corner ${c} refers to UV ${indices[c]} but there are only ${N}`, 'chunk FVUV');
  }
  return { values, indices };
}

function decodeTags(chunk, mesh) {
  const r = chunkReader(chunk, 1);
  const option = (max, what) => {
    const v = r.u8(what);
    if (v !== 255 && v > max) r.fail(`${what} value ${v} is out of range`);
    return v === 255 ? null : v;
  };
  const tags = {
    boundary: option(2, 'boundary rule'), fvar: option(5, 'face-varying rule'),
    creaseMethod: option(1, 'crease method'), triangles: option(1, 'triangle rule'),
  };
  const nc = r.u32('crease count'), nk = r.u32('corner count'), nh = r.u32('hole count');
  if (nc > Math.floor(r.remaining / 12)) r.fail(`crease count ${nc} too large`);
  tags.creases = [];
  for (let i = 0; i < nc; i++) {
    const v0 = r.u32(), v1 = r.u32(), sharpness = r.f32();
    if (v0 >= mesh.vertexCount || v1 >= mesh.vertexCount || v0 === v1) r.fail(`crease ${i} joins vertices ${v0} and ${v1}, not an edge of the mesh's ${mesh.vertexCount} vertices`);
    if (!(sharpness >= 0) || !Number.isFinite(sharpness)) r.fail(`crease ${i} has sharpness ${sharpness}`);
    tags.creases.push({ v0, v1, sharpness });
  }
  if (nk > Math.floor(r.remaining / 8)) r.fail(`corner count ${nk} too large`);
  tags.corners = [];
  for (let i = 0; i < nk; i++) {
    const vertex = r.u32(), sharpness = r.f32();
    if (vertex >= mesh.vertexCount) r.fail(`corner ${i} refers to vertex ${vertex} of ${mesh.vertexCount}`);
    if (!(sharpness >= 0) || !Number.isFinite(sharpness)) r.fail(`corner ${i} has sharpness ${sharpness}`);
    tags.corners.push({ vertex, sharpness });
  }
  tags.holes = r.array(Uint32Array, nh, 'holes');
  r.requireEnd();
  for (const h of tags.holes) if (h >= mesh.faceCount) throw new LimnError(`hole face ${h} of ${mesh.faceCount}`, 'chunk TAGS');
  return tags;
}

function decodeMaterial(chunk) {
  const r = chunkReader(chunk, 1);
  const baseColorFactor = [];
  for (let c = 0; c < 4; c++) {
    const v = r.f32();
    if (!(v >= 0 && v <= 1)) r.fail(`base colour factor component ${c} is not within 0 to 1`);
    baseColorFactor.push(v);
  }
  const formatLength = r.u32('format length');
  r.zero32();
  const textureLength = r.u64n('texture length');
  if (formatLength > 255) r.fail(`texture format name of ${formatLength} bytes (at most 255)`);
  if ((formatLength === 0) !== (textureLength === 0)) r.fail('a texture needs a format name, and a format name a texture');
  const name = r.bytesOf(formatLength, 'texture format name');
  for (const ch of name) {
    if (!/[A-Za-z0-9._-]/.test(String.fromCharCode(ch))) r.fail('texture format name holds a character other than A-Z a-z 0-9 . _ -');
  }
  const texture = r.bytesOf(textureLength, 'texture bytes');
  r.requireEnd();
  return { baseColorFactor, textureFormat: String.fromCharCode(...name), texture };
}

function decodeClassification(chunk, mesh) {
  const r = chunkReader(chunk, 1);
  const options = { boundary: r.u8(), creaseMethod: r.u8(), triangles: r.u8(), fvar: r.u8() };
  if (options.boundary > 2 || options.creaseMethod > 1 || options.triangles > 1 || options.fvar > 5) r.fail('scheme option out of range');
  const V = r.u32('vertex count'), F = r.u32('face count');
  if (V !== mesh.vertexCount || F !== mesh.faceCount) {
    r.fail(`classification is for ${V} vertices and ${F} faces, the mesh has ${mesh.vertexCount} and ${mesh.faceCount}`);
  }
  const counts = { edges: r.u32(), boundaryEdges: r.u32(), nonManifoldEdges: r.u32(), uvSeamEdges: r.u32() };
  r.zero32();
  const vertexValence = r.array(Uint32Array, V, 'vertex valences');
  const vertexFlags = r.array(Uint32Array, V, 'vertex flags');
  const faceFlags = r.array(Uint32Array, F, 'face flags');
  r.requireEnd();
  return { options, ...counts, vertexValence, vertexFlags, faceFlags };
}

function seamsSourceHash(byType) {
  let h = { hi: 0x5ea4, lo: 0x5ea45ea4 };
  for (const [type, value] of [['TBLS', 0x534c4254], ['FVUV', 0x56555646]]) {
    const c = byType.get(type);
    if (!c) continue;
    const f = new Fnv64(h.hi, (h.lo ^ value) >>> 0).update(c.payload);
    h = { hi: f.hi, lo: f.lo };
  }
  return (BigInt(h.hi) << 32n) | BigInt(h.lo);
}

function decodeSeams(chunk, elements, expectedHash) {
  const r = chunkReader(chunk, 1);
  const hash = r.u64('source hash');
  if (hash !== expectedHash) throw new LimnError('the seams were made for other tables or UVs; re-run limn-seams', 'chunk SEAM');
  const E = r.u32('element count'), U = r.u32('UV count');
  if (E !== elements) r.fail(`seams for ${E} elements, the tables have ${elements}`);
  if (E > Math.floor(r.remaining / 96)) r.fail(`element count ${E} is too large`);
  // 24 words an element as the chunk has them (own UVs, then (first, count) pairs), then the UVs.
  const records = r.array(Uint32Array, E * 24, 'elements');
  const uvs = r.array(Float32Array, U * 2, 'UVs');
  r.requireEnd();
  const rf = new Float32Array(records.buffer);
  for (let i = 0; i < U * 2; i++) if (!Number.isFinite(uvs[i])) throw new LimnError(`UV ${i >> 1} is not finite`, 'chunk SEAM');
  for (let i = 0; i < E; i++) {
    const e = 24 * i;
    for (let k = 0; k < 4; k++) {
      if (!Number.isFinite(rf[e + 2 * k]) || !Number.isFinite(rf[e + 2 * k + 1])) throw new LimnError(`element ${i} has a non-finite UV`, 'chunk SEAM');
      const cf = records[e + 8 + 2 * k], cc = records[e + 9 + 2 * k];
      if (cc < 1 || cc > 4096 || cf > U || cc > U - cf) throw new LimnError(`element ${i} corner ${k} UV range is out of bounds`, 'chunk SEAM');
      const ef = records[e + 16 + 2 * k], es = records[e + 17 + 2 * k];
      if (es < 1 || es > 2 || ef > U || 2 * es > U - ef) throw new LimnError(`element ${i} edge ${k} UV range is out of bounds`, 'chunk SEAM');
    }
  }
  return { records, uvs, uvCount: U };
}

/**
 * Reads a .limn file into what the runtime uploads. Throws LimnError (bad input) naming the
 * chunk; BLND is refused (blending surfaces are not supported here).
 */
export function loadLimn(bytes) {
  const chunks = parseContainer(bytes);
  const byType = new Map(chunks.map((c) => [c.type, c]));
  if (byType.has('BLND')) {
    throw new LimnError('blending surfaces are not supported here; render this file with limn-render', 'chunk BLND');
  }
  if (!byType.has('MESH')) throw new LimnError('the container has no MESH chunk (was it made by limn-classify?)', 'container');
  const mesh = decodeMesh(byType.get('MESH'));
  const uvs = byType.has('FVUV') ? decodeUVs(byType.get('FVUV'), mesh) : null;
  const tags = byType.has('TAGS') ? decodeTags(byType.get('TAGS'), mesh) : null;
  const material = byType.has('MATL') ? decodeMaterial(byType.get('MATL')) : null;
  const classification = byType.has('CLSF') ? decodeClassification(byType.get('CLSF'), mesh) : null;
  if (!byType.has('TBLS')) throw new LimnError('the container has no subdivision tables; run limn-tables --depth N on it', 'container');
  const tables = decodeTables(byType.get('TBLS'), mesh, tags);
  // FVSF: only with UVs to smooth (FVUV present, TAGS fvar other than "all").
  let fvarSurface = null;
  if (byType.has('FVSF')) {
    if (!uvs) throw new LimnError('the mesh has no UVs (no FVUV chunk) for its smooth UV surface', 'chunk FVSF');
    const uvHash = new Fnv64().update(bytesOf(uvs.values)).update(bytesOf(uvs.indices)).value;
    const pw = tables.patches, pf = new Float32Array(pw.buffer, pw.byteOffset, pw.length);
    const qw = tables.irregular, qf = new Float32Array(qw.buffer, qw.byteOffset, qw.length);
    const domains = [];
    for (let i = 0; i < tables.patchCount; i++) domains.push([pw[24 * i + 16], pf[24 * i + 17], pf[24 * i + 18], pf[24 * i + 19]]);
    for (let i = 0; i < tables.irregularCount; i++) domains.push([qw[8 * i + 4], qf[8 * i + 5], qf[8 * i + 6], qf[8 * i + 7]]);
    fvarSurface = decodeFvarSurface(byType.get('FVSF'), { depth: tables.depth, ptexCount: ptexCount(mesh), topologyHash: topologyHash(mesh, tags, tables.options), uvHash, domains });
  }
  const seams = byType.has('SEAM')
    ? decodeSeams(byType.get('SEAM'), tables.patchCount + tables.irregularCount, seamsSourceHash(byType))
    : null;
  return { mesh, uvs, tags, material, classification, tables, seams, fvarSurface };
}
