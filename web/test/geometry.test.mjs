// The tessellation the web runtime draws, read back, against limn-render --mesh-out of the same
// container and options (fixed grids): the same triangles, every position within 1e-6 of the
// diagonal. This pins the JavaScript port of the watertight tessellation vertex for vertex, and
// the generated WGSL of the subdivision passes and the surface evaluation.
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, scratch, tool } from './support.mjs';
import { privateIcd, requestNodeDevice } from '../src/node_device.mjs';
import { loadLimn } from '../src/chunks.mjs';
import { Renderer } from '../src/renderer.mjs';

function readPly(bytes) {
  const end = bytes.indexOf('end_header\n') + 'end_header\n'.length;
  const header = bytes.toString('latin1', 0, end);
  const V = Number(/element vertex (\d+)/.exec(header)[1]), F = Number(/element face (\d+)/.exec(header)[1]);
  const stride = header.includes('property float s') ? 44 : 36;
  const positions = new Float32Array(3 * V), triangles = new Uint32Array(3 * F);
  for (let i = 0; i < V; i++) for (let c = 0; c < 3; c++) positions[3 * i + c] = bytes.readFloatLE(end + stride * i + 4 * c);
  let o = end + stride * V;
  for (let t = 0; t < F; t++, o += 13) {
    assert.equal(bytes[o], 3);
    for (let c = 0; c < 3; c++) triangles[3 * t + c] = bytes.readUInt32LE(o + 1 + 4 * c);
  }
  return { positions, triangles };
}

const cases = [
  ['spot depth 2', 'quad/spot_quadrangulated.obj', 2, []],
  ['creased torus depth 3', 'osd/catmark/catmark_torus_creases0.obj', 3, []],
  ['face-varying UVs depth 2 (seam copies)', 'quad/osd_catmark_fvar_bound1.obj', 2, []],
  ['car depth 3, grids capped at 4', 'osd/catmark/catmark_car.obj', 3, ['--tess', '4']],
];

// The view-adaptive tessellation of one view (--edge-pixels 4 with the default --max-error 0.1),
// mostly from explicit cameras. One is auto-framed: the framing hull is evaluated in double as
// limn-render evaluates it (framing.mjs), so the camera is the same to the bit; evaluated on the
// GPU in float, the camera moved by a float step and the car at depth 6 drew another triangle.
// Both sides at 4 samples (limn-render's default): the cull drops a flat element's triangles
// that cover no sample, so the sample pattern decides which triangles are emitted.
const view = (eye, target) => ['--size', '320x240', '--samples', '4', '--eye', eye, '--target', target];
cases.push(['view-adaptive: spot depth 3', 'quad/spot_quadrangulated.obj', 3, view('1.5,1.2,2.5', '0,0.1,0.2')],
  ['view-adaptive: creased torus depth 3', 'osd/catmark/catmark_torus_creases0.obj', 3, ['--size', '320x240', '--samples', '1']],
  ['view-adaptive: spot depth 1, one sample', 'quad/spot_quadrangulated.obj', 1, ['--size', '320x240', '--samples', '1', '--eye', '1.5,1.2,2.5', '--target', '0,0.1,0.2']],
  ['view-adaptive: car depth 4', 'osd/catmark/catmark_car.obj', 4, view('4,-1,2.5', '0.6,-1.9,0.3')],
  ['view-adaptive: car depth 6, auto-framed', 'osd/catmark/catmark_car.obj', 6, ['--size', '320x240', '--samples', '4']]);

function optionView(args) {
  const at = (o) => (args.includes(o) ? args[args.indexOf(o) + 1].split(',').map(Number) : undefined);
  return at('--eye') ? { eye: at('--eye'), target: at('--target') } : {};
}

// One device for every case (each device costs Dawn's start-up and its pipeline compiles).
let gpu = null;
after(() => gpu?.device.destroy());

for (const [label, mesh, depth, args] of cases) {
  test(`geometry: ${label}`, async () => {
    const limn = container(mesh, { depth });
    const ply = join(scratch, `${label.replace(/\W+/g, '_')}.ply`);
    const adaptive = label.startsWith('view-adaptive');
    execFileSync(tool('limn-render'), [limn, '--edge-pixels', adaptive ? '4' : '0', '--mesh-out', ply, ...args],
      { env: { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd }, stdio: 'ignore' });
    const native = readPly(readFileSync(ply));
    const surface = loadLimn(new Uint8Array(readFileSync(limn)));
    gpu ??= await requestNodeDevice();
    const { device } = gpu;
    const tess = args.includes('--tess') ? Number(args[args.indexOf('--tess') + 1]) : 64;
    const r = await Renderer.create(device, surface, adaptive
      ? { width: 320, height: 240, samples: Number(args[args.indexOf('--samples') + 1]), edgePixels: 4, tess, view: optionView(args), meshOut: true }
      : { width: 64, height: 64, samples: 1, edgePixels: 0, tess, view: { eye: [0, 0, 10] } });
    const web = await r.drawnMesh();
    r.destroy();
    assert.equal(web.triangles.length, native.triangles.length, 'triangle count');
    assert.equal(web.positions.length / 4, native.positions.length / 3, 'vertex count');
    assert.deepEqual(web.triangles, native.triangles, 'the same triangles over the same vertices');
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < native.positions.length; i++) { lo[i % 3] = Math.min(lo[i % 3], native.positions[i]); hi[i % 3] = Math.max(hi[i % 3], native.positions[i]); }
    const diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    let worst = 0;
    for (let i = 0; i < native.positions.length / 3; i++) {
      const d = Math.hypot(web.positions[4 * i] - native.positions[3 * i], web.positions[4 * i + 1] - native.positions[3 * i + 1], web.positions[4 * i + 2] - native.positions[3 * i + 2]);
      worst = Math.max(worst, d);
    }
    assert.ok(worst <= 1e-6 * diagonal, `a position is ${worst / diagonal} of the diagonal away`);
  });
}
