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
  assert.equal(s.tables.patches.length, s.tables.patchCount * 24);
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
  const newer = chunks.map((c) => (c.type === 'TBLS' ? { ...c, version: 3 } : c));
  expectLimnError(build(newer), /chunk TBLS: version 3 is newer/);
  const unknown = [...chunks, { type: 'ZZZZ', version: 9, payload: new Uint8Array(5) }];
  assert.equal(loadLimn(build(unknown)).tables.depth, 2);
  expectLimnError(build(chunks.filter((c) => c.type !== 'TBLS')), /limn-tables/);
});
