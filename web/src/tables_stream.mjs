// TBLS version 4's compact encodings (formats/tbls.md, "Compact encodings";
// lib/subdiv/tables_stream.cpp): byte streams of LEB128 varints, and the stencil tables kept in
// them, decoded with the C++ reader's checks.

// Catmull-Clark's masks have weights of order 1; a larger one can only come from a damaged file.
export const MAX_STENCIL_WEIGHT = 1e6;

// TBLS version 4's byte streams (lib/subdiv/tables_chunk.cpp's StreamReader): u32 length, LEB128
// varints (zigzag for signed differences), zero padding to a multiple of 4.
export class Stream {
  constructor(r, what) {
    this.r = r;
    this.what = what;
    const n = r.u32(`${what} stream length`);
    this.bytes = r.bytesOf(n, `${what} stream`);
    this.at = 0;
    for (let pad = (4 - (n % 4)) % 4; pad > 0; pad--) if (r.u8() !== 0) this.fail('padding is not zero');
  }
  get size() { return this.bytes.length; }
  fail(message) { this.r.fail(`${this.what}: ${message}`); }
  varint() {
    let x = 0;
    for (let shift = 0; shift < 64; shift += 7) {
      if (this.at === this.bytes.length) this.fail('the stream ends inside a number');
      const b = this.bytes[this.at++];
      if (shift === 63 && b > 1) break;
      x += (b & 0x7f) * 2 ** shift;
      if (!(b & 0x80)) return x;
    }
    return this.fail('a number in the stream is longer than 64 bits');
  }
  // A u32 given as a zigzag difference from `previous`.
  after(previous, what) {
    const z = this.varint();
    const x = previous + (z % 2 === 1 ? -(z + 1) / 2 : z / 2);
    if (x < 0 || x > 0xffffffff) this.fail(`${what} out of range`);
    return x;
  }
  rawByte() {
    if (this.at === this.bytes.length) this.fail('the stream ends inside a record');
    return this.bytes[this.at++];
  }
  rawFloat() {
    if (this.bytes.length - this.at < 4) this.fail('the stream ends inside a number');
    const v = new DataView(this.bytes.buffer, this.bytes.byteOffset + this.at, 4).getFloat32(0, true);
    this.at += 4;
    return v;
  }
  finish() { if (this.at !== this.bytes.length) this.fail('unexpected bytes after the last record'); }
}

// Version 4: the weights as indices into the table's palette of distinct values, the sources as
// differences from the previous source (a row's first from the previous row's first), the rows
// as lengths (formats/tbls.md, "Compact stencil tables").
export function readCompactStencils(r, what, rows, entries, weights, paletteSize) {
  if (!weights && paletteSize !== 0) r.fail(`${what}: a palette without weights`);
  const palette = r.array(Float32Array, paletteSize, `${what} palette`);
  for (const x of palette) if (!(Math.abs(x) <= MAX_STENCIL_WEIGHT)) r.fail(`${what}: a palette weight is ${x}; a stencil weight must be finite and within +-1e6`);
  const s = new Stream(r, what);
  // Every entry takes at least one byte (two when weighted), every row one.
  if (rows > s.size || entries > Math.floor(s.size / (weights ? 2 : 1))) s.fail(`${entries} entries do not fit in ${s.size} bytes`);
  const start = new Uint32Array(rows + 1), index = new Uint32Array(entries);
  const weight = weights ? new Float32Array(entries) : null;
  let n = 0, previousFirst = 0;
  for (let i = 0; i < rows; i++) {
    const length = s.varint();
    if (length > 65536 || length > entries - n) s.fail(`row ${i} has a bad length`);
    let previous = previousFirst;
    for (let k = 0; k < length; k++) {
      previous = s.after(previous, 'a source index');
      index[n] = previous;
      if (k === 0) previousFirst = previous;
      if (weights) {
        const p = s.varint();
        if (p >= palette.length) s.fail('a weight is not in the palette');
        weight[n] = palette[p];
      }
      n++;
    }
    start[i + 1] = n;
  }
  if (n !== entries) s.fail(`${n} entries, expected ${entries}`);
  s.finish();
  return { start, index, weight };
}

// The level records (lib/subdiv/tables_stream.cpp's readLevels): six u32 each, or (`stream`,
// version 9) one stream of varints without the first, which is where the previous level ends;
// the caller checks them.
export function readLevels(r, count, stream) {
  const levels = [];
  if (!stream) {
    for (let l = 0; l < count; l++) {
      levels.push({ first: r.u32(), facePoints: r.u32(), edgePoints: r.u32(), vertexPoints: r.u32(), regularPatches: r.u32(), irregularFaces: r.u32() });
    }
    return levels;
  }
  const s = new Stream(r, 'levels');
  const next = () => {
    const x = s.varint();
    if (x > 0xffffffff) s.fail('a count out of range');
    return x;
  };
  let sum = 0;
  for (let l = 0; l < count; l++) {
    const lv = { first: Math.min(sum, 0xffffffff), facePoints: next(), edgePoints: next(), vertexPoints: next(), regularPatches: next(), irregularFaces: next() };
    sum += lv.facePoints + lv.edgePoints + lv.vertexPoints;
    levels.push(lv);
  }
  s.finish();
  return levels;
}
