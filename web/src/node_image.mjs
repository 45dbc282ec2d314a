// Images for --displace and --texture in Node, decoded by the npm package pngjs (any PNG: grey,
// RGB, palette, with alpha, 8 or 16 bits, interlaced) into what limn-render's lib/image reads:
// values in 0..1, v / 255 or v / 65535, no colour-space change. (In a browser, the viewer decodes
// with createImageBitmap instead; this module is Node-only.)
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { LimnError } from './container.mjs';

const require = createRequire(import.meta.url);

/** PNG bytes -> {width, height, rgb: Float32Array (3 a texel, rows top to bottom)}. */
export function decodePngImage(bytes, what) {
  // The header's size first: an image the GPU cannot take (4 bytes a texel, 128 MiB) is refused
  // before its pixels are allocated (a 20000x20000 PNG decodes to 1.6 GB).
  const b = Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (b.length >= 24 && b.readUInt32BE(0) === 0x89504e47) {
    const width = b.readUInt32BE(16), height = b.readUInt32BE(20);
    if (width * height > 2 ** 25) throw new LimnError(`${what}: a ${width}x${height} image, over the 2^25 texels a map may have on the GPU (WebGPU's 128 MiB buffers); scale it down`, 'input');
  }
  let png;
  try {
    const { PNG } = require('pngjs');
    png = PNG.sync.read(Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength), { skipRescale: true });
  } catch (e) {
    if (e.code === 'MODULE_NOT_FOUND') throw new LimnError('the npm package pngjs is missing: run npm ci in web/', 'capability');
    throw new LimnError(`${what}: not a PNG this can read (${e.message}); PNG is what limn-web-render decodes`, 'input');
  }
  const { width, height, data } = png;
  // pngjs gives RGBA: 16-bit values in a Uint16Array with skipRescale, else bytes (grey and
  // palette already expanded to RGB, as lib/image does).
  const scale = data instanceof Uint16Array ? 65535 : 255;
  const rgb = new Float32Array(width * height * 3);
  for (let i = 0; i < width * height; i++) for (let k = 0; k < 3; k++) rgb[3 * i + k] = Math.fround(data[4 * i + k] / scale);
  return { width, height, rgb };
}

/** Reads an image file; throws a LimnError naming the option and the file. */
export function readImageFile(path, option) {
  let bytes;
  try {
    bytes = readFileSync(path);
  } catch (e) {
    throw new LimnError(`${option} ${path}: cannot read (${e.code ?? e.message})`, 'input');
  }
  return decodePngImage(bytes, `${option} ${path}`);
}

/** A displacement map from an image: channel 0 of each texel. */
export function heightMap(image) {
  const values = new Float32Array(image.width * image.height);
  for (let i = 0; i < values.length; i++) values[i] = image.rgb[3 * i];
  return { width: image.width, height: image.height, values };
}
