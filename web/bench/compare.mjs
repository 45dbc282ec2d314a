#!/usr/bin/env node
// limn-web-render --bench against limn-render --bench on the same driver (the private Mesa 25
// lavapipe), the same containers, options and views, interleaved case by case so that both see
// the same machine load; 4 samples. Prints one table row per case; medians of the frames after
// the first. EDGE_PIXELS: 4 (limn-render's default, view-adaptive) or 0 (the fixed grids, whose
// depth-6 cases are capped by --tess to fit WebGPU's 128 MiB buffers).
// The README's displaced quad_sphere (paper 000, 4.5: displacement with the seam fix) too.
//   node web/bench/compare.mjs [FRAMES] [EDGE_PIXELS] [CASE]   (CASE: only cases whose label has it;
//   needs build/bin: scripts/build.sh release)
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';
import { container, paperSphereObj, quadSphere, tool, repo } from '../test/support.mjs';
import { privateIcd } from '../src/node_device.mjs';

const frames = process.argv[2] ?? '10';
const edgePixels = process.argv[3] ?? '4';
const cap = (t) => (edgePixels === '0' ? ['--tess', t] : []);
const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd, XDG_RUNTIME_DIR: '/tmp' };
const cli = join(repo, 'web/bin/limn-web-render.mjs');
const sphere = (d) => container(paperSphereObj(), { depth: d, name: `paper_sphere_d${d}.limn` });
const cases = [
  ['spot d3 1024x768', () => container('quad/spot_quadrangulated.obj', { depth: 3 }), ['--size', '1024x768']],
  ['spot d6 1024x768', () => container('quad/spot_quadrangulated.obj', { depth: 6 }), ['--size', '1024x768', ...cap('16')]],
  ...[1, 2, 3, 4, 5, 6].map((d) => [`sphere d${d} 1280x720`, () => sphere(d), ['--size', '1280x720', '--eye', '0,12,22', '--target', '0,0,0']]),
  ['car d6 1024x768', () => container('osd/catmark/catmark_car.obj', { depth: 6 }), ['--size', '1024x768', ...cap('8')]],
  ['quad_sphere d3 displaced 1024x768', () => quadSphere().limn,
    ['--size', '1024x768', '--displace', quadSphere().height, '--displace-scale', '0.2', '--displace-mid', '0.5']],
].filter(([label]) => label.includes(process.argv[4] ?? ''));
console.log('| case | triangles | native frame ms (gpu total) | native cpu ms | web frame ms | web JS ms | web / native |');
console.log('|---|---|---|---|---|---|---|');
for (const [label, make, args] of cases) {
  const limn = make();
  const common = [limn, '--edge-pixels', edgePixels, '--samples', '4', '--bench', frames, ...args];
  const native = JSON.parse(execFileSync(tool('limn-render'), common, { env, stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  const web = JSON.parse(execFileSync(process.execPath, [cli, ...common], { env, stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  const n = native.gpu_ms.total;
  console.log(`| ${label} | ${native.triangles} / ${web.triangles} | ${n.toFixed(2)} | ${native.cpu_ms.toFixed(2)} | ${web.gpu_ms.total.toFixed(2)} | ${web.cpu_ms.toFixed(3)} | ${(web.gpu_ms.total / n).toFixed(2)} |`);
}
