// PNG in Node (zlib is built in): 8-bit RGB or RGBA, filter 0 on every row, fixed deflate level,
// so the same pixels give the same bytes. decodePng reads what encodePng and limn-render write
// (8-bit grey, RGB, RGBA; non-interlaced; any filter), for the tests' comparisons.
import { deflateSync, inflateSync } from 'node:zlib';

const CRC = new Int32Array(256).map((_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c;
});
function crc32(bytes) {
  let c = -1;
  for (const b of bytes) c = CRC[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ -1) >>> 0;
}

function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, 'latin1');
  Buffer.from(data).copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}

/** rgba: RGBA8 rows top to bottom; channels 3 drops alpha (limn-render's default output). */
export function encodePng(width, height, rgba, channels = 3) {
  const row = width * channels;
  const raw = Buffer.alloc((row + 1) * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      for (let c = 0; c < channels; c++) raw[y * (row + 1) + 1 + x * channels + c] = rgba[(y * width + x) * 4 + c];
    }
  }
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr.set([8, channels === 4 ? 6 : 2, 0, 0, 0], 8);
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', deflateSync(raw, { level: 6 })), chunk('IEND', Buffer.alloc(0))]);
}

/** { width, height, rgba } from PNG bytes. */
export function decodePng(bytes) {
  const b = Buffer.from(bytes);
  let o = 8, width = 0, height = 0, type = 0;
  const idat = [];
  while (o < b.length) {
    const len = b.readUInt32BE(o), t = b.toString('latin1', o + 4, o + 8);
    const d = b.subarray(o + 8, o + 8 + len);
    if (t === 'IHDR') {
      width = d.readUInt32BE(0); height = d.readUInt32BE(4);
      if (d[8] !== 8 || d[12] !== 0) throw new Error('decodePng: only 8-bit non-interlaced images');
      type = d[9];
    } else if (t === 'IDAT') idat.push(d);
    o += 12 + len;
  }
  const channels = { 0: 1, 2: 3, 6: 4, 4: 2 }[type];
  const raw = inflateSync(Buffer.concat(idat));
  const row = width * channels;
  const cur = new Uint8Array(row), prev = new Uint8Array(row);
  const rgba = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; y++) {
    const f = raw[y * (row + 1)];
    for (let i = 0; i < row; i++) {
      const x = raw[y * (row + 1) + 1 + i], a = i >= channels ? cur[i - channels] : 0, up = prev[i], c = i >= channels ? prev[i - channels] : 0;
      let v;
      if (f === 0) v = x; else if (f === 1) v = x + a; else if (f === 2) v = x + up; else if (f === 3) v = x + ((a + up) >> 1);
      else { const p = a + up - c, pa = Math.abs(p - a), pb = Math.abs(p - up), pc = Math.abs(p - c); v = x + (pa <= pb && pa <= pc ? a : pb <= pc ? up : c); }
      cur[i] = v & 0xff;
    }
    for (let x = 0; x < width; x++) {
      const px = (y * width + x) * 4;
      if (channels === 1 || channels === 2) { rgba[px] = rgba[px + 1] = rgba[px + 2] = cur[x * channels]; rgba[px + 3] = channels === 2 ? cur[x * 2 + 1] : 255; } else {
        for (let c = 0; c < 3; c++) rgba[px + c] = cur[x * channels + c];
        rgba[px + 3] = channels === 4 ? cur[x * 4 + 3] : 255;
      }
    }
    prev.set(cur);
  }
  return { width, height, rgba };
}
