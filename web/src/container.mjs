// The .limn container (formats/limn.md, sections 2-4): header, chunk list, and a byte reader that
// never trusts a count, as lib/container and lib/base/bytes.h do. Every failure is a LimnError
// naming the chunk (or the header) and the offset.

export const MAGIC = [0x4c, 0x49, 0x4d, 0x4e, 0x0d, 0x0a, 0x1a, 0x0a];

/** A bad-input error; `where` names the chunk or header, `message` says what and what to do. */
export class LimnError extends Error {
  constructor(message, where = '') {
    super(where ? `${where}: ${message}` : message);
    this.name = 'LimnError';
    this.where = where;
    this.detail = message;
  }
}

/** Reads little-endian fields from one payload; `what` names it in errors ("chunk MESH"). */
export class ByteReader {
  constructor(bytes, what) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.at = 0;
    this.what = what;
  }

  get remaining() { return this.bytes.byteLength - this.at; }
  get atEnd() { return this.at === this.bytes.byteLength; }

  fail(message) {
    throw new LimnError(`${message} (at payload offset ${this.at})`, this.what);
  }

  need(n, field) {
    if (n > this.remaining) this.fail(`truncated: ${field} needs ${n} bytes, ${this.remaining} left`);
  }

  u8(field = 'a byte') { this.need(1, field); return this.view.getUint8(this.at++); }
  u32(field = 'a u32') { this.need(4, field); const v = this.view.getUint32(this.at, true); this.at += 4; return v; }
  f32(field = 'an f32') { this.need(4, field); const v = this.view.getFloat32(this.at, true); this.at += 4; return v; }
  f64(field = 'an f64') { this.need(8, field); const v = this.view.getFloat64(this.at, true); this.at += 8; return v; }
  u64(field = 'a u64') {
    this.need(8, field);
    const v = this.view.getBigUint64(this.at, true);
    this.at += 8;
    return v;
  }

  // A count read as u64 that must fit a JS number: anything beyond the file is refused by the
  // array reads anyway, so clamping to MAX_SAFE_INTEGER keeps the comparison exact.
  u64n(field) {
    const v = this.u64(field);
    return v > BigInt(Number.MAX_SAFE_INTEGER) ? Number.MAX_SAFE_INTEGER : Number(v);
  }

  zero32(field = 'reserved field') { if (this.u32(field) !== 0) this.fail(`${field} is not zero`); }

  // Arrays are checked against the bytes left before anything is allocated (limn.md 4.3), and
  // copied so that they are aligned whatever the payload's offset in the file.
  array(Type, count, field) {
    if (count > Math.floor(this.remaining / Type.BYTES_PER_ELEMENT)) {
      this.fail(`${field}: ${count} elements do not fit in the ${this.remaining} bytes left`);
    }
    const n = count * Type.BYTES_PER_ELEMENT;
    const copy = new Uint8Array(n);
    copy.set(this.bytes.subarray(this.at, this.at + n));
    this.at += n;
    return new Type(copy.buffer);
  }

  bytesOf(count, field) {
    return this.array(Uint8Array, count, field);
  }

  requireEnd() {
    if (!this.atEnd) this.fail(`${this.remaining} unexpected bytes after the last field`);
  }
}

const isTypeChar = (c) => (c >= 65 && c <= 90) || (c >= 97 && c <= 122) || (c >= 48 && c <= 57) || c === 95;

/**
 * Splits a .limn file into its chunks: [{type: 'MESH', version, payload: Uint8Array, offset}].
 * Checks the header and chunk framing of limn.md section 4, items 1 and 2.
 */
export function parseContainer(bytes) {
  if (!(bytes instanceof Uint8Array)) bytes = new Uint8Array(bytes);
  const N = bytes.byteLength;
  const looksLike = N >= 4 && MAGIC.slice(0, 4).every((b, i) => bytes[i] === b);
  if (N < 24) {
    throw new LimnError(looksLike ? `truncated container: ${N} bytes, the header alone is 24` : 'not a .limn container (bad magic)', 'header');
  }
  if (!MAGIC.every((b, i) => bytes[i] === b)) {
    throw new LimnError(looksLike ? 'damaged container magic (was the file transferred in text mode?)' : 'not a .limn container (bad magic)', 'header');
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, N);
  const version = view.getUint32(8, true);
  if (version !== 1) throw new LimnError(`container version ${version} is not supported (this reader reads version 1)`, 'header');
  if (view.getUint32(12, true) !== 0) throw new LimnError('reserved header flags are not zero', 'header at offset 12');
  const total = view.getBigUint64(16, true);
  if (total !== BigInt(N)) throw new LimnError(`header says ${total} bytes but the file has ${N} (truncated or trailing data)`, 'header');
  if (N % 8 !== 0) throw new LimnError('total length is not a multiple of 8', 'header at offset 16');
  const chunks = [];
  const seen = new Set();
  for (let o = 24; o < N;) {
    let where = `chunk at offset ${o}`;
    if (N - o < 16) throw new LimnError('truncated chunk header', where);
    const codes = [...bytes.subarray(o, o + 4)];
    if (!codes.every(isTypeChar)) throw new LimnError('chunk type is not four characters from [A-Za-z0-9_]', where);
    const type = String.fromCharCode(...codes);
    where = `chunk ${type} at offset ${o}`;
    const chunkVersion = view.getUint32(o + 4, true);
    if (chunkVersion === 0) throw new LimnError('chunk version 0 is invalid', where);
    const length = view.getBigUint64(o + 8, true);
    const left = N - o - 16;
    if (length > BigInt(left)) throw new LimnError(`payload length ${length} runs past the end (${left} bytes left)`, where);
    const n = Number(length);
    const pad = (8 - (n % 8)) % 8;
    if (pad > left - n) throw new LimnError('missing padding after the payload', where);
    for (let i = 0; i < pad; i++) {
      if (bytes[o + 16 + n + i] !== 0) throw new LimnError('padding bytes are not zero', where);
    }
    if (seen.has(type)) throw new LimnError('chunk type appears twice', where);
    seen.add(type);
    chunks.push({ type, version: chunkVersion, payload: bytes.subarray(o + 16, o + 16 + n), offset: o });
    o += 16 + n + pad;
  }
  return chunks;
}

/** A reader for a known chunk, after refusing a version newer than `newest`. */
export function chunkReader(chunk, newest) {
  if (chunk.version > newest) {
    throw new LimnError(`version ${chunk.version} is newer than this reader reads (${newest}); upgrade limn`, `chunk ${chunk.type}`);
  }
  return new ByteReader(chunk.payload, `chunk ${chunk.type}`);
}

// 64-bit FNV-1a in two 32-bit halves (prime 2^40 + 0x1b3), as lib/container's hashBytes.
export class Fnv64 {
  constructor(hi = 0xcbf29ce4, lo = 0x84222325) { this.hi = hi >>> 0; this.lo = lo >>> 0; }
  update(bytes) {
    let { hi, lo } = this;
    for (let i = 0; i < bytes.length; i++) {
      lo = (lo ^ bytes[i]) >>> 0;
      const t = lo * 0x1b3;
      const nlo = t >>> 0;
      hi = (hi * 0x1b3 + Math.floor(t / 4294967296) + ((lo << 8) >>> 0)) >>> 0;
      lo = nlo;
    }
    this.hi = hi; this.lo = lo;
    return this;
  }
  get value() { return (BigInt(this.hi) << 32n) | BigInt(this.lo); }
}

// The bytes of a typed array, for hashing.
export const bytesOf = (a) => new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
