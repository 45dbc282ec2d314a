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

// Tables whose own buffers pass WebGPU's 128 MiB binding limit are refused by name before any GPU
// work (no device is even needed): the patches buffer as uploaded, with the irregular faces'
// quadtree, sub-patch and basis records after the patches (TBLS v3), not the patch count alone.
test('tables over 128 MiB are refused, naming the buffer, before any GPU work', async () => {
  const surface = loadLimn(read(container('quad/spot_quadrangulated.obj', { depth: 1 })));
  const { tables } = surface;
  assert.ok(tables.patches.byteLength > tables.patchCount * 96, 'spot has irregular-face records after its patches');
  // As many records past the patches as would pass 128 MiB, with the patches themselves small.
  const records = { byteLength: tables.patchCount * 96 + 129 * 2 ** 20 };
  const big = { ...surface, tables: { ...tables, patches: records } };
  await assert.rejects(Renderer.create(null, big, { width: 64, height: 48, edgePixels: 4, view: {} }),
    /GPU buffer 'patches' would need 1\d\d\.\d MiB, over WebGPU's 128 MiB storage-buffer limit/);
});

// A map whose GPU buffer would pass 128 MiB is refused by name, before any GPU work.
test('maps over 128 MiB on the GPU are refused, naming the option', async () => {
  const surface = loadLimn(read(container('quad/spot_quadrangulated.obj', { depth: 1 })));
  const huge = { width: 6000, height: 6000 }; // only the size is read before the refusal
  await assert.rejects(Renderer.create(null, surface, { width: 64, height: 48, view: {}, texture: huge }),
    /--texture: a 6000x6000 map needs 137\.3 MiB on the GPU, over WebGPU's 128 MiB/);
  await assert.rejects(Renderer.create(null, surface, { width: 64, height: 48, view: {}, displace: { map: huge, scale: 1, mid: 0, seamFix: true } }),
    /--displace: a 6000x6000 map needs 137\.3 MiB/);
});
