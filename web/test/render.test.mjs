// limn-web-render's images against limn-render's for the same container and options, both on the
// private Mesa 25 lavapipe (the same rasterizer): at most 0.5% of the covered pixels may differ by
// more than 8/255. The fixed grids (--edge-pixels 0) and the view-adaptive tessellation, 1 and 4
// samples, lit and --shade levels, on real models: spot (depths 1, 3, 6), a creased torus, a model
// with face-varying UVs and tags, the paper's demo sphere in its camera, and the paper-size car.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, paperSphereObj, scratch, tool, repo } from './support.mjs';
import { privateIcd } from '../src/node_device.mjs';
import { decodePng } from '../src/png.mjs';
import { compareImages } from './compare.mjs';

const cli = join(repo, 'web/bin/limn-web-render.mjs');
const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd, XDG_RUNTIME_DIR: process.env.XDG_RUNTIME_DIR ?? '/tmp' };

function renderBoth(limn, args, name) {
  const web = join(scratch, `${name}-web.png`), native = join(scratch, `${name}-native.png`);
  execFileSync(process.execPath, [cli, limn, '-o', web, ...args], { env, stdio: ['ignore', 'ignore', 'pipe'] });
  execFileSync(tool('limn-render'), [limn, '-o', native, ...args], { env, stdio: ['ignore', 'ignore', 'pipe'] });
  return compareImages(decodePng(readFileSync(web)), decodePng(readFileSync(native)));
}

const spot = (depth) => () => container('quad/spot_quadrangulated.obj', { depth });
const sphere6 = () => container(paperSphereObj(), { depth: 6, name: 'paper_sphere_d6.limn' });
const fixed = ['--edge-pixels', '0'];
const cases = [
  // The fixed grids (--edge-pixels 0).
  ['fixed: spot depth 1', spot(1), fixed, [1, 4], ['lit', 'levels']],
  ['fixed: spot depth 3', spot(3), fixed, [4], ['lit', 'levels']],
  ['fixed: spot depth 6 (grids capped at 4)', spot(6), [...fixed, '--tess', '4'], [1], ['lit', 'levels']],
  ['fixed: creased torus depth 3', () => container('osd/catmark/catmark_torus_creases0.obj', { depth: 3 }), [...fixed, '--view', '30,40'], [4], ['lit', 'levels']],
  ['fixed: face-varying UVs and tags depth 2', () => container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 }), fixed, [1], ['lit', 'levels']],
  ['fixed: paper sphere depth 6 in its camera', sphere6, [...fixed, '--eye', '0,12,22', '--target', '0,0,0', '--tess', '16', '--size', '1280x720'], [4], ['lit']],
  ['fixed: car depth 3', () => container('osd/catmark/catmark_car.obj', { depth: 3 }), [...fixed, '--tess', '4'], [4], ['lit', 'levels']],
  // The view-adaptive tessellation (limn-render's default, --edge-pixels 4).
  ['adaptive: spot depth 3', spot(3), [], [1, 4], ['lit', 'levels']],
  ['adaptive: spot depth 3, normals and per-sample shading', spot(3), ['--sample-shading'], [4], ['normal', 'lit']],
  ['adaptive: spot depth 6', spot(6), [], [4], ['lit']],
  ['adaptive: creased torus depth 3', () => container('osd/catmark/catmark_torus_creases0.obj', { depth: 3 }), ['--view', '30,40'], [4], ['lit', 'levels']],
  ['adaptive: paper sphere depth 6 in its camera', sphere6, ['--eye', '0,12,22', '--target', '0,0,0', '--size', '1280x720'], [4], ['lit']],
  ['adaptive: car depth 6', () => container('osd/catmark/catmark_car.obj', { depth: 6 }), [], [4], ['lit']],
];

for (const [label, make, args, samplesList, shades] of cases) {
  test(`images: ${label}`, () => {
    const limn = make();
    for (const samples of samplesList) {
      for (const shade of shades) {
        const name = `${label.replace(/\W+/g, '_')}-${samples}-${shade}`;
        const size = args.includes('--size') ? [] : ['--size', '320x240'];
        const r = renderBoth(limn, [...size, '--samples', String(samples), '--shade', shade, ...args], name);
        assert.ok(r.covered > 2000, `${name}: only ${r.covered} covered pixels`);
        assert.ok(r.fraction <= 0.005, `${name}: ${r.off} of ${r.covered} covered pixels differ by more than 8/255 (worst ${r.worst})`);
      }
    }
  });
}

test('the same command twice writes the same bytes', () => {
  const limn = container('quad/spot_quadrangulated.obj', { depth: 1 });
  const a = join(scratch, 'twice-a.png'), b = join(scratch, 'twice-b.png');
  for (const out of [a, b]) execFileSync(process.execPath, [cli, limn, '-o', out, '--size', '200x150', '--samples', '4'], { env, stdio: 'ignore' });
  assert.deepEqual(readFileSync(a), readFileSync(b));
});
