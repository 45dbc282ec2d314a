// TBLS version 9's program dictionary and compact chain fields (formats/tbls.md, "Program
// dictionary (version 9)"), field by field on hand-written streams, as
// tests/subdiv/tables_program_dictionary_test.cpp does for the C++ reader: every damaged field is
// refused by name (a LimnError) before it is used, never another exception or an allocation from
// an unchecked count. The streams are written here from the format text, not by an encoder; each
// test starts from a stream the reader accepts, so a refusal is the damage's.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ByteReader, LimnError, parseContainer } from '../src/container.mjs';
import { loadLimn } from '../src/chunks.mjs';
import { join } from 'node:path';
import { build, irregularSectionOffset, read, repo } from './support.mjs';
import { readLevels, Stream } from '../src/tables_stream.mjs';
import { programDictionary, readDictionaryProgram } from '../src/tables_program_dictionary.mjs';
import { readChainBasis } from '../src/tables_chain_records.mjs';

class StreamBytes {
  constructor(b = []) { this.b = [...b]; }
  copy() { return new StreamBytes(this.b); }
  v(x) { // LEB128 of a non-negative integer (BigInt for those past 2^53)
    let y = BigInt(x);
    for (; y >= 0x80n; y >>= 7n) this.b.push(Number(y & 0x7fn) | 0x80);
    this.b.push(Number(y));
    return this;
  }
  f(x) {
    const v = new DataView(new ArrayBuffer(4));
    v.setFloat32(0, x, true);
    this.b.push(...new Uint8Array(v.buffer));
    return this;
  }
  raw(bytes) { this.b.push(...bytes); return this; }
  add(o) { this.b.push(...o.b); return this; }
  // Values packed in `width` bits each, least significant bit first, spare bits `spare`.
  packed(values, width, spare = 0) {
    let pending = 0, bits = 0;
    for (const x of values) {
      pending |= x << bits;
      for (bits += width; bits >= 8; bits -= 8, pending >>>= 8) this.b.push(pending & 0xff);
    }
    if (bits) this.b.push((pending | (spare << bits)) & 0xff);
    return this;
  }
}

// u32 length, the bytes, zero padding to 4.
function framed(s) {
  const n = s.b.length, out = new Uint8Array(4 + Math.ceil(n / 4) * 4);
  new DataView(out.buffer).setUint32(0, n, true);
  out.set(s.b, 4);
  return out;
}

const repeated = (n, x) => new Array(n).fill(x);

// A program over 4 support points of one new row (source 0, a new weight 1) and 48 control rows
// naming it (row + 1 = 1, in bit_width(2) = 2 bits).
const oneRowProgram = () => new StreamBytes().v(1).v(1 << 2).v(0).v(0).f(1).packed(repeated(48, 1), 2);

function readProgram(s, d, support = 4, maxRows = 12, next = 0, phantoms = false) {
  const r = new ByteReader(framed(s), 'chunk TBLS');
  const in_ = new Stream(r, 'program');
  const p = readDictionaryProgram(in_, support, maxRows, next, phantoms, d);
  in_.finish();
  return p;
}

function refused(read, why) {
  assert.throws(read, (e) => {
    assert.ok(e instanceof LimnError, `not a LimnError: ${e.stack}`);
    assert.ok(e.message.includes(why), `${e.message} does not say "${why}"`);
    return true;
  });
}

// A dictionary holding three rows over 4 points (sources 0, 1, 2), one weight (1).
function threeRows() {
  const d = programDictionary();
  readProgram(new StreamBytes().v(3).v(4).v(0).v(0).f(1).v(4).v(1).v(0).v(4).v(2).v(0).packed(repeated(48, 1), 3), d);
  return d;
}

test('TBLS v9: hostile dictionary rows, runs and weights are refused by name', () => {
  assert.equal(readProgram(oneRowProgram(), programDictionary()).rows, 1); // the base the damage starts from
  const bad = (s, why, support = 4) => refused(() => readProgram(s, threeRows(), support), why);
  const S = () => new StreamBytes();
  bad(S().v(0), 'bad row count 0');
  bad(S().v(13), 'bad row count 13'); // above maxRows (12)
  bad(S().v(2 ** 40), 'bad row count'); // nothing allocated from it
  bad(S().v(1).v(0 << 2), 'row 0 has a bad length'); // a new row of no entries
  bad(S().v(1).v(17 << 2), 'row 0 has a bad length'); // 16 entries a row of the program
  bad(S().v(1).v(1 << 2).v(4), 'reads neither a support point nor an earlier row');
  bad(S().v(1).v(1 << 2).v(0).v(2), 'not in the palette'); // the palette holds 1 weight
  for (const w of [NaN, Infinity, 2e6]) bad(S().v(1).v(1 << 2).v(0).v(1).f(w), 'bad weight');
  // Named rows: h & 3 = 1 one row `back` from the last; h & 3 = 3 a run, its length less 2 after.
  bad(S().v(1).v((3 << 2) | 1), 'row 0 names a missing dictionary row'); // 3 rows: back 0..2
  bad(S().v(2).v((0 << 2) | 3).v(0), 'row 0 names a missing dictionary row'); // 2 rows from the last
  bad(S().v(2).v((2 << 2) | 3).v(1), 'row 0 has a bad run length'); // 3 rows in a program of 2
  bad(S().v(2).v((0 << 2) | 1).v((0 << 2) | 3).v(0), 'row 1 has a bad run length'); // 1 row left
  bad(S().v(2).v((2 << 2) | 3).v(2n ** 63n), 'row 0 has a bad run length');
  // A named row's sources are checked against this program's support: row 2 reads point 2.
  bad(S().v(1).v((0 << 2) | 1), 'row 0 reads neither a support point nor an earlier row', 2);
  bad(S().v(1).raw([0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x02]), 'longer than 64 bits');
  bad(S().v(1).raw([0x80]), 'ends inside a number');
  // A named row brings its entries into this program's 16 a row: a row of 20 entries (from a
  // program of 2 rows, 32 entries) cannot be the one row of another.
  const d20 = programDictionary(), wide = S().v(2).v(20 << 2).v(0).v(0).f(0.05);
  for (let e = 1; e < 20; e++) wide.v(0).v(0);
  readProgram(wide.v(4).v(1).v(0).packed(repeated(48, 1), 2), d20);
  refused(() => readProgram(S().v(1).v((1 << 2) | 1).packed(repeated(48, 1), 2), d20), 'row 0 has a bad length');
  readProgram(S().v(1).v((0 << 2) | 1).packed(repeated(48, 1), 2), d20); // the 1-entry row is fine
  // The three rows as one run, the control rows naming row 3 (bit_width(4) bits).
  const p = readProgram(S().v(3).v((2 << 2) | 3).v(1).packed(repeated(48, 3), 3), threeRows());
  assert.deepEqual(p.source, [0, 1, 2]);
  assert.equal(p.controlRow[0], 2);
});

// The control rows (row + 1, 0 a phantom) and next-support rows, packed in bit_width(rows + 1)
// bits: a value naming no row, a phantom where none may be, and spare bits that are not 0.
test('TBLS v9: hostile packed control and next-support rows are refused by name', () => {
  const bad = (s, why, next = 0, phantoms = false) => refused(() => readProgram(s, programDictionary(), 4, 12, next, phantoms), why);
  const head = () => new StreamBytes().v(1).v(1 << 2).v(0).v(0).f(1);
  const rows = repeated(48, 1);
  rows[7] = 2; // row 1 of a program of 1
  bad(head().packed(rows, 2), 'a control point names a missing row');
  rows[7] = 0; // a phantom
  bad(head().packed(rows, 2), 'a control point names a missing row');
  assert.equal(readProgram(head().packed(rows, 2), programDictionary(), 4, 12, 0, true).controlRow[7], 0xffffffff);
  const withNext = [...repeated(48, 1), 0, 1]; // next-support rows are rows, not row + 1: 1 names no row
  bad(head().packed(withNext, 2), 'a support point names a missing row', 2);
  withNext[49] = 0;
  assert.equal(readProgram(head().packed(withNext, 2), programDictionary(), 4, 12, 2).nextSupport.length, 2);
  // 50 values of 2 bits end inside a byte: its 4 spare bits must be 0.
  bad(head().packed(withNext, 2, 0x1), 'spare bits are not 0', 2);
  bad(head().packed(withNext, 2, 0x8), 'spare bits are not 0', 2);
  bad(head().packed(repeated(40, 1), 2), 'ends inside a record');
});

// A leaf chain of one band over 4 points (valence 0, K = 1): end 0, 1 band, program 0 (new, no
// next support); the band's three kinds and, for a regular end (end 2), its kind and 16 rows follow.
const chainHead = (end = 0) => new StreamBytes().v(end).v(1).v(0).v(0).add(oneRowProgram());

function readChain(s) {
  const b = readChainBasis(new ByteReader(framed(s), 'chunk TBLS'), 'chain', 0, 4, 1, [], [], programDictionary());
  assert.equal(b.weights.length, 48 * 4);
}

// A kind is a varint boundary | crease << 4 | how << 8, its sharpness 0, the previous band's less
// 1, the previous band's, or 4 raw bytes; the previous of band 1 and of a regular end's kind is 0.
test('TBLS v9: hostile compact chain fields are refused by name', () => {
  readChain(chainHead().v(0).v(0).v(0));
  const sharp3 = new StreamBytes().v(0x10 | (3 << 8)).f(3); // a crease of sharpness 3
  readChain(chainHead().add(sharp3).v(0).v(0));
  const bad = (s, why) => refused(() => readChain(s), why);
  bad(chainHead().v(1 << 8).v(0).v(0), 'bad patch kind'); // 0 - 1 on band 1
  bad(chainHead().v(0x10 | (2 << 8)).v(0).v(0), 'bad patch kind'); // a crease of the previous 0
  bad(chainHead().v(0x10).v(0).v(0), 'bad patch kind'); // a crease of sharpness 0
  for (const x of [NaN, Infinity, -0.5, 10.5]) bad(chainHead().v(3 << 8).f(x).v(0).v(0), 'bad patch kind');
  bad(chainHead().v(4 << 8).v(0).v(0), 'bad patch kind'); // how 4
  bad(chainHead().v(0x30 | (3 << 8)).f(2).v(0).v(0), 'bad patch kind'); // two crease edges
  bad(chainHead().v(0x11 | (3 << 8)).f(2).v(0).v(0), 'bad patch kind'); // a crease on the boundary
  // A regular end's kind starts from 0 again: "less 1" is -1 there, not band 1's 3 - 1.
  const regular = chainHead(2).add(sharp3).v(0).v(0), centreRows = new StreamBytes();
  for (let i = 0; i < 16; i++) centreRows.v(1);
  readChain(regular.copy().v(0).add(centreRows));
  bad(regular.copy().v(1 << 8).add(centreRows), 'bad patch kind');
  bad(regular.copy().v(0).v(2), 'regular end names a missing row'); // row 1 of a program of 1
  // Numbers are u32s as varints: 2^32 overflows; counts are bounded before anything is sized.
  const S = () => new StreamBytes();
  bad(S().v(2 ** 32), 'a number out of range');
  bad(S().v(0).v(2 ** 32), 'a number out of range');
  bad(S().v(0).v(1).v(1), 'band 1 names a missing program');
  bad(S().v(0).v(1).v(0).v(529), 'bad support size');
  bad(S().v(0).v(1).v(0).v(2 ** 40), 'bad support size');
  bad(S().v(0).v(1).v(0).v(0).v(13), 'bad row count 13'); // 3 rows a support point
  bad(chainHead().v(0).v(0).v(0).v(0), 'unexpected bytes after the last record');
});

// Version 9's level records: per level five counts as varints of one stream (each level's first
// is where the previous ends): a count past 2^32 - 1, a stream cut short or one with bytes left.
test('TBLS v9: a hostile level stream is refused by name', () => {
  const levels = (s, count) => readLevels(new ByteReader(framed(s), 'chunk TBLS'), count, true);
  const two = levels(new StreamBytes().v(0).v(0).v(9).v(0).v(1).v(1).v(2).v(3).v(4).v(5), 2);
  assert.equal(two[1].first, 9);
  assert.equal(two[1].vertexPoints, 3);
  refused(() => levels(new StreamBytes().v(0).v(0).v(2 ** 32).v(0).v(0), 1), 'a count out of range');
  refused(() => levels(new StreamBytes().v(0).v(0).v(9).v(0), 1), 'ends inside a number');
  refused(() => levels(new StreamBytes().v(0).v(0).v(9).v(0).v(0).v(0), 1), 'unexpected bytes');
  // Every stream's padding to 4 bytes MUST be 0 (5 bytes of counts, 3 of padding).
  const padded = framed(new StreamBytes().v(0).v(0).v(9).v(0).v(0));
  padded[padded.length - 1] = 1;
  refused(() => readLevels(new ByteReader(padded, 'chunk TBLS'), 1, true), 'padding is not zero');
});

// A chain naming programs read before takes a few dozen bytes and expands to K x 48 x M weights:
// copies of one of the v9 seed's chains (chaikin0 d1) past 128 MiB of weights (the bases' GPU
// buffer, WebGPU's limit) are refused by name once past it, not read on into gigabytes.
test('TBLS v9: bases expanding past 128 MiB of weights are refused by name', () => {
  const bytes = read(join(repo, 'fuzz/corpus/render_input/chaikin0_d1_crease_chains_v9.limn')), chunks = parseContainer(bytes);
  const tbls = chunks.find((c) => c.type === 'TBLS'), p = tbls.payload;
  const v = new DataView(p.buffer, p.byteOffset, p.byteLength), u = (o) => v.getUint32(o, true);
  const { at, stream } = irregularSectionOffset(loadLimn(bytes).tables, p, tbls.version);
  const nodes = stream(at + 4), leaves = stream(nodes + 4), count = leaves + 4 + 32 * u(leaves);
  const records = []; // each v9 basis: 16 header bytes (valence, code, M, K) and a stream
  let end = count + 4;
  for (let i = 0; i < u(count); i++, end = stream(end + 16)) records.push(end);
  // Copies of record `o` after the last basis (the smooth faces name none of them).
  const copied = (o, copies) => {
    const record = p.subarray(o, stream(o + 16)), payload = new Uint8Array(p.length + copies * record.length);
    payload.set(p.subarray(0, end));
    for (let k = 0; k < copies; k++) payload.set(record, end + k * record.length);
    payload.set(p.subarray(end), end + copies * record.length);
    new DataView(payload.buffer).setUint32(count, u(count) + copies, true);
    return build(chunks.map((c) => (c.type === 'TBLS' ? { ...c, payload } : c)));
  };
  // The last chain that brings no program of its own reads as a copy.
  const chain = records.filter((o) => u(o + 4) === 2).reverse().find((o) => {
    try { loadLimn(copied(o, 1)); return true; } catch { return false; }
  });
  assert.ok(chain !== undefined, 'no chain reads as a copy');
  const copies = Math.floor(32 * 2 ** 20 / (u(chain + 12) * 48 * u(chain + 8))) + 1;
  assert.throws(() => loadLimn(copied(chain, copies)), (e) => e instanceof LimnError && /expand to more than 128 MiB of weights/.test(e.message));
});
