// PNG in Node, through the npm package pngjs (encode and decode): 8-bit RGB or RGBA, with a fixed
// deflate level and pngjs's per-row filter choice (a function of the pixels only), so the same
// pixels give the same bytes.
import { createRequire } from 'node:module';

const { PNG } = createRequire(import.meta.url)('pngjs');

/** rgba: RGBA8 rows top to bottom; channels 3 drops alpha (limn-render's default output). */
export function encodePng(width, height, rgba, channels = 3) {
  let data = Buffer.from(rgba.buffer, rgba.byteOffset, width * height * 4);
  if (channels === 3) {
    // Alpha dropped here: given RGBA for RGB output, pngjs would blend it over a background.
    const rgb = Buffer.alloc(width * height * 3);
    for (let i = 0, n = width * height; i < n; i++) rgb.set(data.subarray(4 * i, 4 * i + 3), 3 * i);
    data = rgb;
  }
  const colorType = channels === 4 ? 6 : 2;
  return PNG.sync.write({ width, height, data }, { colorType, inputColorType: colorType, inputHasAlpha: channels === 4, bitDepth: 8, deflateLevel: 6 });
}

/**
 * { width, height, rgba: RGBA8 } from PNG bytes, for the tests' comparisons: decoded by pngjs, the
 * runtime's PNG reader (node_image.mjs), so any PNG reads (16-bit scaled to 8).
 */
export function decodePng(bytes) {
  const png = PNG.sync.read(Buffer.from(bytes));
  return { width: png.width, height: png.height, rgba: new Uint8Array(png.data.buffer, png.data.byteOffset, png.data.length) };
}
