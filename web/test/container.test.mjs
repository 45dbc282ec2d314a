// The container reader on real containers and on hostile ones: every truncation, every payload
// cut short (lengths patched so that the framing holds and the chunk's own reader must notice),
// and byte flips. Each is a LimnError naming the header or the chunk, never another exception.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadLimn } from '../src/chunks.mjs';
import { ByteReader, LimnError, parseContainer } from '../src/container.mjs';
import { readBasisProgram, readNodeStream, readSmoothPoints } from '../src/tables_surface_records.mjs';
import { join } from 'node:path';
import { build, container, irregularSectionOffset, read, repo } from './support.mjs';

// With its boundary faces refined (no boundary bases): the hostile tests below need sub-patches
// and quadtree nodes; TBLS v7's bases have their own test.
const small = () => read(container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, seams: true, tablesArgs: ['--boundary-bases', 'off', '--crease-chains', 'off'], name: 'fvar_bound1_refined_d2_s.limn' }));

function expectLimnError(bytes, where) {
  try {
    loadLimn(bytes);
  } catch (e) {
    assert.ok(e instanceof LimnError, `not a LimnError: ${e.stack}`);
    if (where) assert.match(e.message, where);
    else assert.match(e.message, /^(header|container|chunk )/);
    return e;
  }
  assert.fail('accepted');
}

test('reads a real container: every chunk limn-render reads', () => {
  const s = loadLimn(small());
  assert.ok(s.mesh.vertexCount > 0 && s.tables.depth === 2 && s.seams && s.uvs && s.classification);
  // TBLS v4 (limn-tables' default): the irregular faces' quadtrees follow the patches, their
  // leaves the irregular faces (subdivision_draw.cpp patchBuffer, irregularBuffer).
  assert.ok(s.tables.irregularCount > 0 && s.tables.irregularLevels > 0);
  assert.ok(s.tables.patches.length >= (s.tables.patchCount + s.tables.irregularCount) * 24);
  assert.equal(s.tables.patches.length % 24, 0);
  assert.ok(s.tables.levels.length > s.tables.depth + 1);
  assert.equal(s.seams.records.length, (s.tables.patchCount + s.tables.irregularCount) * 24);
});

test('the rebuilt container is the same bytes (the test writer is faithful)', () => {
  const bytes = small();
  assert.deepEqual(build(parseContainer(bytes)), bytes);
});

test('every truncation is an error naming the header or a chunk', () => {
  const bytes = small();
  for (let n = 0; n < bytes.length; n++) expectLimnError(bytes.subarray(0, n));
  // The same with the header's length patched, so that the chunk framing is what fails. A cut
  // between chunks is a valid container with fewer chunks (kept unless it lost MESH or TBLS).
  const boundaries = new Set(parseContainer(bytes).map((c) => c.offset));
  let accepted = 0;
  for (let n = 24; n < bytes.length; n += 8) {
    const cut = bytes.slice(0, n);
    new DataView(cut.buffer).setBigUint64(16, BigInt(n), true);
    if (!boundaries.has(n)) expectLimnError(cut);
    else {
      try {
        loadLimn(cut);
        accepted++;
      } catch (e) {
        assert.ok(e instanceof LimnError, e.stack);
      }
    }
  }
  assert.equal(accepted, 1, 'only the cut before SEAM (the last chunk) leaves a renderable container');
});

test('every payload cut short is an error naming its chunk', () => {
  const chunks = parseContainer(small());
  for (const [i, c] of chunks.entries()) {
    for (let n = 0; n < c.payload.length; n += c.payload.length > 4000 ? 7 : 1) {
      const changed = chunks.map((d, j) => (j === i ? { ...d, payload: d.payload.subarray(0, n) } : d));
      const e = expectLimnError(build(changed));
      // A shorter TBLS or FVUV also makes SEAM stale, but the chunk itself is read first.
      assert.match(e.message, new RegExp(`chunk ${c.type}`), `${c.type} cut to ${n}: ${e.message}`);
    }
  }
});

test('byte flips are accepted or refused with a LimnError, never another exception', () => {
  const bytes = small();
  let refused = 0;
  // Every other byte, the mask cycling through a low bit, the sign/high bit and all bits.
  for (let i = 0; i < bytes.length; i += 2) {
    for (const mask of [[0x01, 0x80, 0xff][(i >> 1) % 3]]) {
      const b = bytes.slice();
      b[i] ^= mask;
      try {
        loadLimn(b);
      } catch (e) {
        assert.ok(e instanceof LimnError, `flip ${mask} at ${i}: ${e.stack}`);
        refused++;
      }
    }
  }
  assert.ok(refused > bytes.length / 4, `${refused} refused`);
});

test('BLND is refused clearly, a newer chunk version names itself', () => {
  const chunks = parseContainer(small());
  expectLimnError(build([...chunks, { type: 'BLND', version: 1, payload: new Uint8Array(24) }]), /chunk BLND: blending surfaces are not supported here/);
  const newer = chunks.map((c) => (c.type === 'TBLS' ? { ...c, version: 10 } : c));
  expectLimnError(build(newer), /chunk TBLS: version 10 is newer/);
  const unknown = [...chunks, { type: 'ZZZZ', version: 9, payload: new Uint8Array(5) }];
  assert.equal(loadLimn(build(unknown)).tables.depth, 2);
  expectLimnError(build(chunks.filter((c) => c.type !== 'TBLS')), /limn-tables/);
});

// TBLS v5's node stream (formats/limn.md): codes as varints from the last index of their kind.
function nodeStream(codes) {
  const bytes = [], next = [0, 0, 0, 0];
  const varint = (x) => { for (; x >= 0x80; x = Math.floor(x / 128)) bytes.push((x % 128) | 0x80); bytes.push(x); };
  const code = (c) => {
    if (c === 0xffffffff) return 0;
    const kind = c >>> 30, x = c & ((1 << 30) - 1), d = x - next[kind];
    next[kind] = x + 1;
    return 1 + kind + 4 * (d >= 0 ? 2 * d : -2 * d - 1);
  };
  for (let i = 0; i < codes.length; i += 4) {
    const same = codes[i] === codes[i + 1] && codes[i] === codes[i + 2] && codes[i] === codes[i + 3];
    varint(2 * code(codes[i]) + (same ? 1 : 0));
    if (!same) for (let q = 1; q < 4; q++) varint(code(codes[i + q]));
  }
  const out = new Uint8Array(4 + Math.ceil(bytes.length / 4) * 4);
  new DataView(out.buffer).setUint32(0, bytes.length, true);
  out.set(bytes, 4);
  return out;
}

test('hostile TBLS v5 irregular-surface fields are refused by name, never a hang', () => {
  const bytes = small(), chunks = parseContainer(bytes);
  const s = loadLimn(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS').payload;
  const { at, stream } = irregularSectionOffset(s.tables, tbls);
  const patched = (edit) => build(chunks.map((c) => {
    if (c.type !== 'TBLS') return c;
    const payload = c.payload.slice();
    edit(new DataView(payload.buffer));
    return { ...c, payload };
  }));
  const view = new DataView(tbls.slice().buffer);
  const subs = view.getUint32(at, true);
  const count = stream(at + 4), nodes = count + 4;
  // The section as located holds the reader's own sub-patch and node counts.
  assert.ok(subs > 0 && subs < 1e6);
  const codes = readNodeStream(new ByteReader(tbls.subarray(nodes), 'test'), view.getUint32(count, true));
  assert.ok(codes.length >= 4);
  const withNodes = (edit) => {
    const c = codes.slice();
    edit(c);
    const payload = new Uint8Array([...tbls.subarray(0, nodes), ...nodeStream(c), ...tbls.subarray(stream(nodes))]);
    return build(chunks.map((k) => (k.type === 'TBLS' ? { ...k, payload } : k)));
  };
  assert.equal(loadLimn(withNodes(() => {})).tables.depth, 2); // the helper writes the same stream
  // A node naming itself (or an earlier node) as its child would make the GPU's walk endless.
  expectLimnError(withNodes((c) => { c[0] = (1 << 30) >>> 0; }), /chunk TBLS: .*irregular node 0 has a bad child/);
  expectLimnError(withNodes((c) => { c[1] = 0x3fffffff; }), /chunk TBLS: .*irregular node 0 has a bad child/);
  expectLimnError(patched((v) => v.setUint32(count, 1 << 30, true)), /chunk TBLS: irregular nodes: count 1073741824 is too large/);
  expectLimnError(patched((v) => v.setUint32(at, 0xffffffff, true)), /chunk TBLS: .*sub-patch count 4294967295 is too large/);
  // Extra levels on uniform tables, or more than depth 16 allows.
  expectLimnError(patched((v) => v.setUint32(12, 15, true)), /chunk TBLS: .*irregular levels 15 out of range/);
});

// TBLS v7's bases carry their configuration and support size (formats/tbls.md, "Boundary
// configurations (version 7)"), as version 9's (limn-tables' output here) do: a place beyond the
// vertex's fan, a code that is no configuration's and a level count of 0 are refused by name,
// before the program is run.
test('hostile TBLS v7 and v9 basis configurations are refused by name', () => {
  const bytes = read(container('osd/catmark/catmark_edgeonly.obj', { depth: 1, tablesArgs: ['--crease-chains', 'off'], name: 'edgeonly_d1_v7.limn' })), chunks = parseContainer(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS');
  assert.equal(tbls.version, 9);
  const { at, stream } = irregularSectionOffset(loadLimn(bytes).tables, tbls.payload, tbls.version);
  const v = new DataView(tbls.payload.buffer, tbls.payload.byteOffset, tbls.payload.byteLength);
  const nodes = stream(at + 4), leaves = stream(nodes + 4), bases = leaves + 4 + 32 * v.getUint32(leaves, true);
  assert.ok(v.getUint32(bases, true) > 0);
  const first = bases + 4, valence = v.getUint32(first, true); // valence, configuration, support size, levels
  assert.ok(valence >= 1 && valence <= 64 && v.getUint32(first + 12, true) === 6);
  const patched = (offset, value) => build(chunks.map((c) => {
    if (c.type !== 'TBLS') return c;
    const payload = c.payload.slice();
    new DataView(payload.buffer).setUint32(offset, value, true);
    return { ...c, payload };
  }));
  const bad = /chunk TBLS: .*irregular basis 0 has a bad configuration, support size or level count/;
  expectLimnError(patched(first + 4, 1 + 4 * valence), bad);
  // From version 8 on, code 2 is a chain's: the record is then refused as a chain.
  expectLimnError(patched(first + 4, 2), /chunk TBLS: .*irregular basis 0 has a bad end, band count, valence or support size/);
  expectLimnError(patched(first + 12, 0), bad);
});

// TBLS v8's decaying-crease chains (formats/tbls.md, "Decaying-crease chains (version 8)"): the
// seed's first chain (chaikin0 d1); an end that is none, more bands than levels, a smooth end
// naming no basis or another valence's and a program index beyond those read are refused by
// name before anything is expanded, and byte flips from the bases on are refused as LimnErrors
// or read (the --mesh-out test checks what is drawn from such tables).
test('hostile TBLS v8 crease chains are refused by name', () => {
  const bytes = read(join(repo, 'fuzz/corpus/render_input/chaikin0_d1_crease_chains_v8.limn')), chunks = parseContainer(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS');
  assert.equal(tbls.version, 8);
  const v = new DataView(tbls.payload.buffer, tbls.payload.byteOffset, tbls.payload.byteLength);
  // The first chain's record: valence 3, configuration 2, support 14, 6 levels, a smooth end
  // naming basis 0 (valence 3's), 1 to 5 bands, band 1 bringing program 0 (found by its header:
  // the sections before it have no fixed size).
  const u = (o) => v.getUint32(o, true);
  let first = -1;
  for (let o = 0; o + 32 <= v.byteLength && first < 0; o++) {
    if (u(o) === 3 && u(o + 4) === 2 && u(o + 8) === 14 && u(o + 12) === 6 && u(o + 16) === 1 && u(o + 20) === 0 &&
        u(o + 24) >= 1 && u(o + 24) <= 5 && u(o + 28) === 0) first = o;
  }
  assert.ok(first >= 0, 'no chain record found');
  const bases = first;
  const patched = (offset, value) => build(chunks.map((c) => {
    if (c.type !== 'TBLS') return c;
    const payload = c.payload.slice();
    new DataView(payload.buffer).setUint32(offset, value, true);
    return { ...c, payload };
  }));
  expectLimnError(patched(first + 16, 3), /irregular basis \d+ has a bad end, band count, valence or support size/);
  expectLimnError(patched(first + 24, 7), /irregular basis \d+ has a bad end, band count, valence or support size/);
  expectLimnError(patched(first + 20, 99), /irregular basis \d+'s smooth end names a missing basis/);
  expectLimnError(patched(first, 5), /irregular basis \d+'s smooth end names basis 0, not valence 5's/);
  expectLimnError(patched(first + 28, 5), /irregular basis \d+ band 1 names a missing program/);
  let state = 8, refused = 0;
  const random = () => (state = (state * 1103515245 + 12345) % 2147483648);
  for (let trial = 0; trial < 300; trial++) {
    const payload = tbls.payload.slice();
    const o = bases + (random() % (payload.length - bases));
    payload[o] ^= 1 << (random() % 8);
    try {
      loadLimn(build(chunks.map((c) => (c.type === 'TBLS' ? { ...c, payload } : c))));
    } catch (e) {
      assert.ok(e instanceof LimnError, `not a LimnError: ${e.stack}`);
      refused++;
    }
  }
  assert.ok(refused > 50, `${refused} refused`);
});

// TBLS v9 (formats/tbls.md, "Program dictionary (version 9)"): the seed's first chain (chaikin0
// d1), its fields varints of one stream after the record's header: an end that is none, more
// bands than levels, a smooth end naming no basis, a program index beyond those read and a
// program of no rows are refused by name before anything is expanded; byte flips from the
// bases on are refused as LimnErrors or read. The tables read are those of the v8 seed (the
// same limn-tables tables), their GPU buffers to the bit.
test('hostile TBLS v9 program dictionaries and chains are refused by name', () => {
  const bytes = read(join(repo, 'fuzz/corpus/render_input/chaikin0_d1_crease_chains_v9.limn')), chunks = parseContainer(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS');
  assert.equal(tbls.version, 9);
  const v8 = loadLimn(read(join(repo, 'fuzz/corpus/render_input/chaikin0_d1_crease_chains_v8.limn'))).tables;
  const v9 = loadLimn(bytes).tables;
  // The GPU buffers (the bases' weights packed after the quadtrees' nodes), to the bit.
  assert.ok(Buffer.from(v9.patches.buffer).equals(Buffer.from(v8.patches.buffer)));
  assert.ok(Buffer.from(v9.irregular.buffer).equals(Buffer.from(v8.irregular.buffer)));
  const v = new DataView(tbls.payload.buffer, tbls.payload.byteOffset, tbls.payload.byteLength);
  // valence 3, configuration 2, support 14, 6 levels, the stream's length, then end 1 (smooth),
  // basis 0, 1 to 5 bands, program 0 (new), its 14 next-support points.
  const u = (o) => v.getUint32(o, true), b = (o) => v.getUint8(o);
  let first = -1;
  for (let o = 0; o + 26 <= v.byteLength && first < 0; o++) {
    if (u(o) === 3 && u(o + 4) === 2 && u(o + 8) === 14 && u(o + 12) === 6 && b(o + 20) === 1 && b(o + 21) === 0 &&
        b(o + 22) >= 1 && b(o + 22) <= 5 && b(o + 23) === 0 && b(o + 24) === 14) first = o;
  }
  assert.ok(first >= 0, 'no chain record found');
  const patched = (offset, value) => build(chunks.map((c) => {
    if (c.type !== 'TBLS') return c;
    const payload = c.payload.slice();
    payload[offset] = value;
    return { ...c, payload };
  }));
  expectLimnError(patched(first + 20, 3), /irregular basis \d+ has a bad end, band count, valence or support size/);
  expectLimnError(patched(first + 22, 7), /irregular basis \d+ has a bad end, band count, valence or support size/);
  expectLimnError(patched(first + 21, 99), /irregular basis \d+'s smooth end names a missing basis/);
  expectLimnError(patched(first + 23, 5), /irregular basis \d+ band 1 names a missing program/);
  expectLimnError(patched(first + 25, 0), /irregular basis \d+: bad row count 0/);
  let state = 9, refused = 0;
  const random = () => (state = (state * 1103515245 + 12345) % 2147483648);
  for (let trial = 0; trial < 300; trial++) {
    const payload = tbls.payload.slice();
    const o = first + (random() % (payload.length - first));
    payload[o] ^= 1 << (random() % 8);
    try {
      loadLimn(build(chunks.map((c) => (c.type === 'TBLS' ? { ...c, payload } : c))));
    } catch (e) {
      assert.ok(e instanceof LimnError, `not a LimnError: ${e.stack}`);
      refused++;
    }
  }
  assert.ok(refused > 50, `${refused} refused`);
});

// TBLS v5 (bases as programs, node and smooth-face streams), v4 (compact stencil tables, patch
// streams, deduplicated bases, point streams) and v3 (the plain layout; this seed was converted
// from the v4 one by a separate decoder written from formats/limn.md) of the same tables, with
// valence bases, sub-patch quadtrees and leaves, read to the same GPU buffers and stencils: the
// weights this reader expands from v5's programs are limn-tables' own (stored in v4), to the bit.
// (The v5 seed is the v4 one's tables written again by limn's encoder.)
test('TBLS v5, v4 and v3 of the same tables read the same', () => {
  const seed = (v) => read(join(repo, `fuzz/corpus/render_input/pentagon_tower_d1_irregular_v${v}.limn`));
  const v3 = loadLimn(seed(3)).tables, v4 = loadLimn(seed(4)).tables, v5 = loadLimn(seed(5)).tables;
  assert.ok(v4.irregularLevels > 0 && v4.patches.length > (v4.patchCount + v4.irregularCount) * 24);
  assert.deepEqual(v4, v3);
  assert.deepEqual(v5, v4);
});

// TBLS v6 stores a level whose stencil tables are the previous level's shifted one level as a bit
// (formats/tbls.md, "Repeated levels"), and sub-patches without their domains, which the reader
// takes from the quadtrees ("Sub-patch domains"): xord_boundary at depth 1 repeats levels 5 to 7
// and has 18 faces on sub-patches. The v6 seed is limn-tables' output, the v5 one the same tables
// written by limn's version-5 encoder, which stores every level and every domain: both read to
// the same stencils and GPU buffers. A repeated level's bit without a previous level, past N + K,
// on a level of other counts or on a level whose tables are stored is refused, by name or by the
// tables' own checks; so are a sub-patch named twice or by no node.
test('TBLS v6 repeated levels and sub-patch domains read as the v5 tables they stand for; hostile ones are refused', () => {
  const seed = (v) => read(join(repo, `fuzz/corpus/render_input/xord_boundary_d1_repeated_levels_v${v}.limn`));
  const v5 = loadLimn(seed(5)).tables, v6 = loadLimn(seed(6)).tables;
  assert.equal(v6.levels.length, 8); // N + K = 7
  assert.ok(v6.patches.length > (v6.patchCount + v6.irregularCount) * 24);
  assert.deepEqual(v6, v5);
  const chunks = parseContainer(seed(6));
  const tbls = chunks.find((c) => c.type === 'TBLS');
  assert.equal(tbls.version, 6);
  const at = 40 + 24 * v6.levels.length;
  const withPayload = (payload) => build(chunks.map((c) => (c.type === 'TBLS' ? { ...c, payload } : c)));
  const withRepeats = (bits) => {
    const payload = tbls.payload.slice();
    new DataView(payload.buffer).setUint32(at, bits, true);
    return withPayload(payload);
  };
  assert.equal(new DataView(tbls.payload.buffer, tbls.payload.byteOffset).getUint32(at, true), 0xe0);
  assert.deepEqual(loadLimn(withRepeats(0xe0)).tables, v5);
  expectLimnError(withRepeats(0xe0 | 2), /chunk TBLS: repeated levels 226 name a level without a previous one/);
  expectLimnError(withRepeats(0xe0 | 0x100), /chunk TBLS: repeated levels .* name a level without a previous one/);
  expectLimnError(withRepeats(0xe0 | 4), /chunk TBLS: level 2 repeats level 1 but has other point counts/);
  for (let l = 3; l <= 7; l++) expectLimnError(withRepeats(0xe0 ^ (1 << l)), /chunk TBLS/);
  // The node stream rewritten with one sub-patch code named twice, then with one named by none.
  const { at: section, stream } = irregularSectionOffset(v6, tbls.payload);
  const nodesAt = stream(section + 4) + 4; // after the sub-patch count and stream, the node count
  const view = new DataView(tbls.payload.buffer, tbls.payload.byteOffset, tbls.payload.byteLength);
  const nodeCount = view.getUint32(nodesAt - 4, true);
  const codes = Array.from(readNodeStream(new ByteReader(tbls.payload.subarray(nodesAt), 'test'), nodeCount));
  const withNodes = (edit) => {
    const c = codes.slice();
    edit(c);
    const encoded = nodeStream(c);
    const payload = new Uint8Array(tbls.payload.length - (stream(nodesAt) - nodesAt) + encoded.length);
    payload.set(tbls.payload.subarray(0, nodesAt));
    payload.set(encoded, nodesAt);
    payload.set(tbls.payload.subarray(stream(nodesAt)), nodesAt + encoded.length);
    return withPayload(payload);
  };
  assert.deepEqual(loadLimn(withNodes(() => {})).tables, v5); // the helper writes the same stream
  const sub = codes.findIndex((c) => c !== 0xffffffff && c >>> 30 === 0);
  const spare = codes.findIndex((c, i) => i !== sub && c !== 0xffffffff && c >>> 30 === 0);
  expectLimnError(withNodes((c) => { c[spare] = c[sub]; }), /chunk TBLS: sub-patch \d+ is (named twice|in no quadtree)/);
  expectLimnError(withNodes((c) => { c[sub] = 0xffffffff; }), /chunk TBLS: sub-patch \d+ is in no quadtree/);
});

// A v5 basis is a program this reader runs over 2n + 8 columns K times: a valence over 64, a
// source that is neither a support point nor an earlier row, or a missing row is refused by name.
test('TBLS v5: a hostile basis program is refused', () => {
  const bytes = read(join(repo, 'fuzz/corpus/render_input/pentagon_tower_d1_irregular_v5.limn'));
  const chunks = parseContainer(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS').payload;
  const v = new DataView(tbls.buffer, tbls.byteOffset, tbls.byteLength);
  // The basis record: found by reading one at each offset where its header fits (valence 3, one
  // level, a small palette), as the sections before it have no fixed size.
  let at = -1;
  for (let o = 0; o + 12 <= tbls.length && at < 0; o += 4) {
    if (v.getUint32(o, true) !== 3 || v.getUint32(o + 4, true) !== 1 || v.getUint32(o + 8, true) > 64) continue;
    try { readBasisProgram(new ByteReader(tbls.subarray(o), 'test'), 0, []); at = o; } catch { /* not it */ }
  }
  assert.ok(at >= 0, 'no basis found');
  const palette = v.getUint32(at + 8, true), stream = at + 12 + 4 * palette + 4;
  const patched = (edit) => {
    const payload = tbls.slice();
    edit(new DataView(payload.buffer), payload);
    return build(chunks.map((c) => (c.type === 'TBLS' ? { ...c, payload } : c)));
  };
  expectLimnError(patched((w) => w.setUint32(at, 65, true)), /chunk TBLS: irregular basis 0 has a bad valence or level count/);
  expectLimnError(patched((w) => w.setUint32(at + 4, 17, true)), /chunk TBLS: irregular basis 0 has a bad valence or level count/);
  // The row count (its first varint, one byte here): 0, or more than twice the support.
  assert.ok(tbls[stream] < 0x80);
  expectLimnError(patched((w, p) => { p[stream] = 0; }), /irregular basis 0: bad row count 0/);
  expectLimnError(patched((w, p) => { p[stream] = 29; }), /irregular basis 0: bad row count 29/);
  // Row 0's first source (after its one-byte head): a later row, itself.
  assert.ok(tbls[stream + 1] < 0x80 && tbls[stream + 2] < 0x80);
  expectLimnError(patched((w, p) => { p[stream + 2] = 14; }), /irregular basis 0: row 0 reads neither a support point nor an earlier row/);
});

// A v4 basis's rows are stored once and copied per use: a valence limn-tables never builds a
// basis for (over 64) would let a few bytes decode to gigabytes; the reader refuses it by name.
test('TBLS v4: a basis of valence over 64 is refused', () => {
  const bytes = read(join(repo, 'fuzz/corpus/render_input/pentagon_tower_d1_irregular_v4.limn'));
  const chunks = parseContainer(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS').payload;
  const v = new DataView(tbls.buffer, tbls.byteOffset, tbls.byteLength);
  // A basis header (valence 3..64, its levels, its row count) followed by row numbers all below
  // that count: found by its own fields, as the sections before it have no fixed size.
  let at = -1;
  for (let o = 0; o + 12 <= tbls.length && at < 0; o += 4) {
    const n = v.getUint32(o, true), k = v.getUint32(o + 4, true), d = v.getUint32(o + 8, true);
    if (n < 3 || n > 64 || k < 1 || k > 16 || d === 0 || d > 48 * k || o + 12 + 96 * k > tbls.length) continue;
    let ok = true;
    for (let j = 0; j < 48 * k && ok; j++) ok = v.getUint16(o + 12 + 2 * j, true) < d;
    if (ok) at = o;
  }
  assert.ok(at >= 0, 'no basis found');
  const payload = tbls.slice();
  new DataView(payload.buffer).setUint32(at, 65, true);
  expectLimnError(build(chunks.map((c) => (c.type === 'TBLS' ? { ...c, payload } : c))),
    /chunk TBLS: .*irregular basis \d+ has valence 65; version 4 bases go up to 64/);
});

// FVSF, the smooth UV surface limn-tables writes under a face-varying rule other than "all":
// read, and refused naming it when cut short, stale (other UVs, other depth) or with a node
// that would send a walk back up its quadtree.
test('FVSF: read with smooth UVs, refused by name when cut, stale or cyclic', () => {
  const bytes = read(container('quad/osd_catmark_fvar_bound1.obj', { depth: 1, classifyArgs: ['--fvar', 'boundaries'], name: 'fvar_smooth_d1.limn' }));
  const s = loadLimn(bytes);
  assert.ok(s.fvarSurface && s.fvarSurface.elementCount > 0 && s.fvarSurface.depth === 1);
  assert.equal(s.fvarSurface.ptexCount, s.mesh.faceSizes.length); // all quads
  assert.equal(loadLimn(small()).fvarSurface, null, 'linear UVs ("all") have none');
  const chunks = parseContainer(bytes);
  const fvsf = chunks.findIndex((c) => c.type === 'FVSF');
  const withPayload = (payload) => build(chunks.map((c, j) => (j === fvsf ? { ...c, payload } : c)));
  const p = chunks[fvsf].payload;
  for (let n = 0; n < p.length; n += 5) expectLimnError(withPayload(p.subarray(0, n)), /^chunk FVSF/);
  const patched = (offset, word) => {
    const q = p.slice();
    new DataView(q.buffer).setUint32(offset, word, true);
    return withPayload(q);
  };
  expectLimnError(patched(0, 2), /chunk FVSF: made at depth 2, but the tables \(TBLS\) have depth 1/);
  expectLimnError(patched(32, 0), /chunk FVSF: node 0 has a bad child index/);
  expectLimnError(patched(32, 0x80000000 + s.fvarSurface.elementCount), /chunk FVSF: node 0 names a missing element/);
  // A hole (0xFFFFFFFF) where the tables draw: every walk from a drawn point must end in an
  // element (the seam fix's walks threw a bare Error, with its stack, from smooth_uvs.mjs).
  // (A node naming a stored patch: a hole in place of a smooth face, since version 3 also along
  // the UV boundary, is refused first as a smooth face named by no node.)
  const pv = new DataView(p.buffer, p.byteOffset, p.byteLength), storedElements = pv.getUint32(28, true);
  const leaf = Array.from({ length: pv.getUint32(24, true) }, (_, i) => pv.getUint32(32 + 4 * i, true))
    .findIndex((v) => v >= 0x80000000 && v !== 0xffffffff && v - 0x80000000 < storedElements);
  assert.ok(leaf >= 0);
  expectLimnError(patched(32 + 4 * leaf, 0xffffffff), /chunk FVSF: no UV element where the tables draw ptex face \d+/);
  // A record's domain that is not its leaf's square (size 1e-30): finite and inside [0, 1], but
  // a walk ending there evaluated the element far outside it (Inf UVs, NaN in --mesh-out).
  const tinyRecord = p.slice();
  new DataView(tinyRecord.buffer).setFloat32(32 + 4 * pv.getUint32(24, true) + 8, 1e-30, true); // the stored nodes
  expectLimnError(withPayload(tinyRecord), /chunk FVSF: node \d+ names element 0, whose domain is not the node's square/);
  // The UVs changed after limn-tables: a value of FVUV moved (its first f64, 16 bytes in).
  const fvuv = chunks.findIndex((c) => c.type === 'FVUV');
  const moved = chunks[fvuv].payload.slice();
  new DataView(moved.buffer).setFloat64(16, 0.125, true);
  expectLimnError(build(chunks.map((c, j) => (j === fvuv ? { ...c, payload: moved } : c))), /chunk FVSF: the smooth UV surface was built from other UVs/);
  // Without FVUV it is refused by name (a container whose UVs were removed by hand).
  expectLimnError(build(chunks.filter((c) => c.type !== 'FVUV')), /chunk FVSF: the mesh has no UVs/);
});

// FVSF version 3's smooth faces (support UVs, per-valence bases and boundary configurations as
// programs; lib/subdiv/fvar_chunk.cpp checks the same): each count and index checked before
// anything is allocated or expanded.
test('FVSF: smooth faces with a count, configuration, program, support or weight out of bounds are refused by name', () => {
  const bytes = read(container('tri/cube_no_bottom.obj', { depth: 2, classifyArgs: ['--fvar', 'boundaries'], name: 'fvar_cube_d2.limn' }));
  const chunks = parseContainer(bytes), fvsf = chunks.findIndex((c) => c.type === 'FVSF');
  assert.equal(chunks[fvsf].version, 3);
  const p = chunks[fvsf].payload, view = new DataView(p.buffer, p.byteOffset, p.byteLength);
  const nodeCount = view.getUint32(24, true), elements = view.getUint32(28, true), at = (o) => view.getUint32(o, true);
  // After the records: the bases (each u32 n, configuration, support size, k, palette size P,
  // f32 palette[P], then its program's stream: u32 bytes, the bytes padded to 4), the values,
  // the smooth faces' count and stream.
  const bases = 32 + 4 * nodeCount + 144 * elements;
  let values = bases + 4;
  const basisAt = [];
  for (let b = 0; b < at(bases); b++) {
    basisAt.push(values);
    const stream = values + 20 + 4 * at(values + 16);
    values = stream + 4 + Math.ceil(at(stream) / 4) * 4;
  }
  const ib = basisAt.findIndex((o) => at(o + 4) === 0), bb = basisAt.findIndex((o) => at(o + 4) !== 0);
  assert.ok(ib >= 0 && bb >= 0, 'the cube has interior and boundary bases');
  const inner = basisAt[ib], edge = basisAt[bb];
  const palette = inner + 20, stream = palette + 4 * at(inner + 16);
  const faces = values + 4 + 8 * at(values);
  assert.ok(at(faces) > 0, 'the cube has smooth faces');
  const s = loadLimn(bytes); // expanded to pieces: more elements than the chunk stores
  assert.ok(s.fvarSurface.elementCount > elements);
  const patched = (offset, word) => {
    const q = p.slice();
    new DataView(q.buffer).setUint32(offset, word, true);
    return build(chunks.map((c, j) => (j === fvsf ? { ...c, payload: q } : c)));
  };
  for (const [offset, word, message] of [
    [bases, 0x10000000, /basis count is too large/],
    [inner, 65, new RegExp(`basis ${ib} has a bad configuration`)],
    [inner + 4, 2, new RegExp(`basis ${ib} has a bad configuration`)], // a corner off the boundary
    [inner + 8, 0xffff, new RegExp(`basis ${ib} has a bad configuration`)],
    [inner + 12, 17, new RegExp(`basis ${ib} has a bad configuration`)],
    [edge + 4, 1 + 4 * at(edge), new RegExp(`basis ${bb} has a bad configuration`)], // beyond its fan
    [edge + 8, 3, new RegExp(`basis ${bb} has a bad configuration`)],
    [inner + 16, 0xffffffff, new RegExp(`basis ${ib} palette`)],
    [palette, 0x7f800000, new RegExp(`basis ${ib} has a bad weight`)],
    [palette, 0x40000000, new RegExp(`basis ${ib} has a weight outside \\[0, 1\\]`)],
    [stream, 0xffffffff, new RegExp(`basis ${ib} stream`)],
    [stream + 4, 0, new RegExp(`basis ${ib}: bad row count 0`)],
    [values, 0x40000000, /values: /],
    [values + 8, 0x7fc00000, /a value is not finite/],
    [faces, 0xffffffff, /smooth face count is too large/],
    [faces + 8, (at(faces + 8) & 0xffffff00 | (4 * basisAt.length)) >>> 0, /smooth face 0 has no basis/],
  ]) expectLimnError(patched(offset, word), new RegExp(`^chunk FVSF: ${message.source}`));
});

// TBLS v5's smooth points come in runs, each at one level N + j (the supports of smooth faces
// below level N at theirs): a run at level N + K or deeper, one of no points or of more than are
// left, and a point outside its run's level are refused by name, as the C++ reader refuses them.
test('TBLS v5: hostile smooth-point runs are refused', () => {
  const level = (first) => ({ first, facePoints: 4, edgePoints: 8, vertexPoints: 4, count: 16 });
  const levels = [level(0), level(16), level(32), level(48)]; // N = 1, K = 2: runs at levels 1 and 2
  const read = (bytes, count = 2) => {
    const out = new Uint8Array(4 + Math.ceil(bytes.length / 4) * 4);
    new DataView(out.buffer).setUint32(0, bytes.length, true);
    out.set(bytes, 4);
    return readSmoothPoints(new ByteReader(out, 'chunk TBLS'), count, levels, 1, 3);
  };
  const refused = (f, why) => assert.throws(f, (e) => e instanceof LimnError && why.test(e.message));
  // Level 1's first face point, then level 2's second edge point (class 1, +1 from its first).
  assert.deepEqual([...read([0, 1, 0, 1, 1, 1 + 3 * 2])], [16, 32 + 4 + 1]);
  refused(() => read([2, 1, 0, 0, 1, 0]), /a run at level N \+ 2 \(levels N to N \+ 1\)/);
  refused(() => read([0, 0]), /a run of 0 points \(2 left\)/);
  refused(() => read([0, 3, 0, 0, 0]), /a run of 3 points \(2 left\)/);
  refused(() => read([1, 2, 2, 2 + 3 * 8]), /a point is not at its run's level/); // vertex points: 4
});
