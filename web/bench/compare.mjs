#!/usr/bin/env node
// limn-web-render --bench against limn-render --bench on the same driver (the private Mesa 25
// lavapipe), the same containers, options and views, interleaved case by case so that both see
// the same machine load; 4 samples. Prints one table row per case. EDGE_PIXELS: 32 (both tools'
// default, view-adaptive) or 0 (the fixed grids, whose depth-6 cases are capped by --tess to
// fit WebGPU's 128 MiB buffers).
// The README's displaced quad_sphere (paper 000, 4.5: displacement with the seam fix) too.
//   node web/bench/compare.mjs [FRAMES] [EDGE_PIXELS] [CASE]   (CASE: only cases whose label has it;
//   needs build/bin: scripts/build.sh release)
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';
import { loadavg } from 'node:os';
import { container, paperSphereObj, quadSphere, tool, repo } from '../test/support.mjs';
import { privateIcd } from '../src/node_device.mjs';

const frames = process.argv[2] ?? '10';
const edgePixels = process.argv[3] ?? '32';
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
// ROUNDS (env LIMN_COMPARE_ROUNDS, default 3): each case runs native, web, native, web, ...;
// the table gives medians over the rounds. Frame ms is the host's frame (cpu_ms: record, submit,
// wait) on both sides; GPU ms is the timestamps' total (limn-render sums its passes, the web
// spans the frame's submissions).
const rounds = +(process.env.LIMN_COMPARE_ROUNDS ?? 3);
const med = (a) => { const b = [...a].sort((x, y) => x - y), n = b.length; return n % 2 ? b[n >> 1] : (b[n / 2 - 1] + b[n / 2]) / 2; };
const run = (file, args) => JSON.parse(execFileSync(file, args, { env, stdio: ['ignore', 'pipe', 'ignore'] }).toString());
console.log(`load average before: ${loadavg().map((x) => x.toFixed(2)).join(' ')}; ${rounds} rounds of ${frames} frames`);
console.log('| case | triangles (native / web) | native frame ms | web frame ms | web / native frame | native GPU ms | web GPU ms | web / native GPU | web JS ms |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const [label, make, args] of cases) {
  const limn = make();
  const common = [limn, '--edge-pixels', edgePixels, '--samples', '4', '--bench', frames, ...args];
  const n = [], w = [];
  for (let r = 0; r < rounds; r++) {
    n.push(run(tool('limn-render'), common));
    w.push(run(process.execPath, [cli, ...common]));
  }
  const col = (a, f) => med(a.map(f));
  const ratio = (f) => med(w.map((x, i) => f(x) / f(n[i])));
  console.log(`| ${label} | ${n[0].triangles} / ${w[0].triangles} | ${col(n, (x) => x.cpu_ms).toFixed(2)} | ${col(w, (x) => x.cpu_ms).toFixed(2)} | ` +
    `${ratio((x) => x.cpu_ms).toFixed(2)} | ${col(n, (x) => x.gpu_ms.total).toFixed(2)} | ${col(w, (x) => x.gpu_ms.total).toFixed(2)} | ` +
    `${ratio((x) => x.gpu_ms.total).toFixed(2)} | ${col(w, (x) => x.js_ms).toFixed(3)} |`);
}
console.log(`load average after: ${loadavg().map((x) => x.toFixed(2)).join(' ')}`);
