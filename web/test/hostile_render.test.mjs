// Containers that the reader accepts after byte flips (positions, weights, UVs changed within
// their checks) render without a WebGPU error or device loss, at both tessellations: the reader's
// checks are what keep every GPU index in range.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadLimn } from '../src/chunks.mjs';
import { requestNodeDevice } from '../src/node_device.mjs';
import { Renderer } from '../src/renderer.mjs';
import { container, read } from './support.mjs';

test('accepted byte flips render without a GPU error', async () => {
  const bytes = read(container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, seams: true }));
  const { device } = await requestNodeDevice();
  const errors = [];
  device.onuncapturederror = (e) => errors.push(e.error.message);
  let rendered = 0;
  // Flips spread over the file (a fixed stride, so the run is the same every time).
  for (let i = 24, tried = 0; i < bytes.length && rendered < 6; i += Math.floor(bytes.length / 23), tried++) {
    const b = bytes.slice();
    b[i] ^= 0x40;
    let surface;
    try {
      surface = loadLimn(b);
    } catch {
      continue;
    }
    for (const edgePixels of [0, 4]) {
      const r = await Renderer.create(device, surface, { width: 64, height: 48, samples: 1, edgePixels, view: {} });
      r.frame();
      await device.queue.onSubmittedWorkDone();
      await r.pixels();
      r.destroy();
    }
    rendered++;
  }
  assert.ok(rendered >= 3, `only ${rendered} flipped containers were accepted`);
  assert.deepEqual(errors, []);
  device.destroy();
});
