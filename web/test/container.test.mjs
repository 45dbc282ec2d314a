// The container reader on real containers and on hostile ones: every truncation, every payload
// cut short (lengths patched so that the framing holds and the chunk's own reader must notice),
// and byte flips. Each is a LimnError naming the header or the chunk, never another exception.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadLimn } from '../src/chunks.mjs';
import { LimnError, parseContainer } from '../src/container.mjs';
import { container, read } from './support.mjs';

const small = () => read(container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, seams: true }));

function build(chunks) {
  const size = 24 + chunks.reduce((n, c) => n + 16 + Math.ceil(c.payload.length / 8) * 8, 0);
  const out = new Uint8Array(size);
  const view = new DataView(out.buffer);
  out.set([0x4c, 0x49, 0x4d, 0x4e, 0x0d, 0x0a, 0x1a, 0x0a]);
  view.setUint32(8, 1, true);
  view.setBigUint64(16, BigInt(size), true);
  let o = 24;
  for (const c of chunks) {
    out.set([...c.type].map((ch) => ch.charCodeAt(0)), o);
    view.setUint32(o + 4, c.version, true);
    view.setBigUint64(o + 8, BigInt(c.payload.length), true);
    out.set(c.payload, o + 16);
    o += 16 + Math.ceil(c.payload.length / 8) * 8;
  }
  return out;
}

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
  // TBLS v3 (limn-tables' default): the irregular faces' quadtrees follow the patches, their
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
  const newer = chunks.map((c) => (c.type === 'TBLS' ? { ...c, version: 4 } : c));
  expectLimnError(build(newer), /chunk TBLS: version 4 is newer/);
  const unknown = [...chunks, { type: 'ZZZZ', version: 9, payload: new Uint8Array(5) }];
  assert.equal(loadLimn(build(unknown)).tables.depth, 2);
  expectLimnError(build(chunks.filter((c) => c.type !== 'TBLS')), /limn-tables/);
});

// Where TBLS v3's irregular-surface section starts (formats/limn.md): after the header, levels,
// stencil tables, patches and irregular faces, as read back from the decoded tables.
function irregularSectionOffset(t) {
  let o = 40 + 24 * t.levels.length;
  const table = (st, weights) => 16 + 4 * (st.rows + 1 + st.index.length * (weights ? 2 : 1));
  for (let l = 0; l + 1 < t.levels.length; l++) o += table(t.facePoints[l], false) + table(t.edgePoints[l], true) + table(t.vertexPoints[l], true);
  return o + 88 * t.patchCount + 32 * t.irregularCount;
}

test('hostile TBLS v3 irregular-surface fields are refused by name, never a hang', () => {
  const bytes = small(), chunks = parseContainer(bytes);
  const s = loadLimn(bytes);
  const at = irregularSectionOffset(s.tables);
  const patched = (edit) => build(chunks.map((c) => {
    if (c.type !== 'TBLS') return c;
    const payload = c.payload.slice();
    edit(new DataView(payload.buffer));
    return { ...c, payload };
  }));
  const subs = new DataView(chunks.find((c) => c.type === 'TBLS').payload.slice().buffer).getUint32(at, true);
  const nodes = at + 4 + 88 * subs + 4;
  // The section as located holds the reader's own sub-patch and node counts.
  assert.ok(subs > 0 && subs < 1e6);
  // A node naming itself (or an earlier node) as its child would make the GPU's walk endless.
  expectLimnError(patched((v) => v.setUint32(nodes, (1 << 30) >>> 0, true)), /chunk TBLS: .*irregular node 0 has a bad child/);
  expectLimnError(patched((v) => v.setUint32(nodes + 4, 0x3fffffff, true)), /chunk TBLS: .*irregular node 0 has a bad child/);
  expectLimnError(patched((v) => v.setUint32(at, 0xffffffff, true)), /chunk TBLS: .*sub-patch count 4294967295 is too large/);
  // Extra levels on uniform tables, or more than depth 16 allows.
  expectLimnError(patched((v) => v.setUint32(12, 15, true)), /chunk TBLS: .*irregular levels 15 out of range/);
});
