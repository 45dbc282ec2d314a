// limn-web-render's images against limn-render's for the same container and options, both on the
// private Mesa 25 lavapipe (the same rasterizer): at most 0.5% of the covered pixels may differ by
// more than 8/255. The fixed grids (--edge-pixels 0) and the view-adaptive tessellation, 1 and 4
// samples, lit and --shade levels, on real models: spot (depths 1, 3, 6), a creased torus, a model
// with face-varying UVs and tags, the paper's demo sphere in its camera, the paper-size car, and
// colour textures (--texture, a glTF's MATL texture) and the triangles' wireframe (--wire-triangles).
//
// The web side renders in this process through the library (one device, each container loaded
// once, so its CPU tessellation is built once and Dawn compiles each pipeline once); limn-render
// runs as a command. The command line's own path to the same pixels is pinned by the same-bytes
// test below and by cli.test.mjs.
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, paperSphereObj, scratch, tool, repo } from './support.mjs';
import { privateIcd } from '../src/node_device.mjs';
import { decodePng, encodePng } from '../src/png.mjs';
import { requestNodeDevice } from '../src/node_device.mjs';
import { loadLimn } from '../src/chunks.mjs';
import { Renderer } from '../src/renderer.mjs';
import { compareImages } from './compare.mjs';
import { readImageFile } from '../src/node_image.mjs';

const cli = join(repo, 'web/bin/limn-web-render.mjs');
const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd, XDG_RUNTIME_DIR: process.env.XDG_RUNTIME_DIR ?? '/tmp' };

let gpu = null;
const surfaces = new Map();
after(() => gpu?.device.destroy());

// limn-web-render's settings for the options these tests use (its defaults otherwise).
function settingsOf(args) {
  const s = { view: {}, samples: 4, width: 1024, height: 768, shade: 'lit', edgePixels: 32, maxError: 0.1, tess: 64 }; // limn-render's defaults
  const nums = (v) => v.split(',').map(Number);
  for (let i = 0; i < args.length; i++) {
    const v = args[i + 1];
    switch (args[i]) {
      case '--size': [s.width, s.height] = v.split('x').map(Number); i++; break;
      case '--samples': s.samples = Number(v); i++; break;
      case '--shade': s.shade = v; i++; break;
      case '--edge-pixels': s.edgePixels = Number(v); i++; break;
      case '--max-error': s.maxError = Number(v); i++; break;
      case '--interior-error': s.interiorError = Number(v); i++; break;
      case '--pixel-normals': s.pixelNormals = true; break;
      case '--tess': s.tess = Number(v); i++; break;
      case '--view': [s.view.azimuthDeg, s.view.elevationDeg] = nums(v); i++; break;
      case '--eye': s.view.eye = nums(v); i++; break;
      case '--target': s.view.target = nums(v); i++; break;
      case '--sample-shading': s.sampleShading = true; break;
      case '--texture': s.texture = readImageFile(v, '--texture'); i++; break;
      case '--color': s.color = nums(v); i++; break;
      case '--wire-triangles': s.wire = 'triangles'; break;
      default: throw new Error(`settingsOf: ${args[i]} is not mapped here`);
    }
  }
  if (s.texture && s.shade === 'lit') s.shade = 'texture'; // as limn-render's --texture
  return s;
}

async function renderBoth(limn, args, name, webArgs = args) {
  const native = join(scratch, `${name}-native.png`);
  if (!existsSync(native)) execFileSync(tool('limn-render'), [limn, '-o', native, ...args], { env, stdio: ['ignore', 'ignore', 'pipe'] });
  gpu ??= await requestNodeDevice();
  const { device } = gpu;
  if (!surfaces.has(limn)) surfaces.set(limn, loadLimn(new Uint8Array(readFileSync(limn))));
  const errors = [];
  device.onuncapturederror = (e) => errors.push(e.error.message);
  const s = settingsOf(webArgs);
  const r = await Renderer.create(device, surfaces.get(limn), s);
  r.frame();
  await device.queue.onSubmittedWorkDone();
  const rgba = await r.pixels();
  r.destroy();
  assert.deepEqual(errors, [], `${name}: WebGPU errors`);
  return compareImages({ width: s.width, height: s.height, rgba }, decodePng(readFileSync(native)));
}

const spot = (depth) => () => container('quad/spot_quadrangulated.obj', { depth });
const sphere6 = () => container(paperSphereObj(), { depth: 6, name: 'paper_sphere_d6.limn' });
const fixed = ['--edge-pixels', '0'];
const spotTexture = join(repo, 'tests/data/textures/spot_texture.png');
// Smooth face-varying UVs (corners-plus1: the UVs are smoothed across the faces, their seams
// kept), drawn from the FVSF chunk, textured by a checkerboard of 8-texel squares: its edges show
// where the UVs land. Linear and smooth UVs give images 4% of covered pixels apart here (the
// test 'smooth UVs are not the linear ones' below), web and native none.
const spotSmooth = () => container('quad/spot_quadrangulated.obj', { depth: 2, classifyArgs: ['--fvar', 'corners-plus1'], name: 'spot_smooth_uvs_d2.limn' });
function checker() {
  const path = join(scratch, 'checker.png');
  if (existsSync(path)) return path;
  const n = 256, px = new Uint8Array(n * n * 4);
  for (let y = 0; y < n; y++) for (let x = 0; x < n; x++) { const c = ((x >> 3) ^ (y >> 3)) & 1 ? 230 : 25; px.set([c, c, c, 255], 4 * (y * n + x)); }
  writeFileSync(path, encodePng(n, n, px));
  return path;
}

const cases = [
  // The fixed grids (--edge-pixels 0).
  ['fixed: spot depth 1', spot(1), fixed, [1, 4], ['lit', 'levels']],
  ['fixed: spot depth 3', spot(3), fixed, [4], ['lit', 'levels']],
  ['fixed: spot depth 6 (grids capped at 4)', spot(6), [...fixed, '--tess', '4'], [1], ['lit', 'levels']],
  ['fixed: creased torus depth 3', () => container('osd/catmark/catmark_torus_creases0.obj', { depth: 3 }), [...fixed, '--view', '30,40'], [4], ['lit', 'levels']],
  ['fixed: face-varying UVs and tags depth 2', () => container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 }), fixed, [1], ['lit', 'levels']],
  ['fixed: paper sphere depth 6 in its camera', sphere6, [...fixed, '--eye', '0,12,22', '--target', '0,0,0', '--tess', '16', '--size', '1280x720'], [4], ['lit']],
  ['fixed: car depth 3', () => container('osd/catmark/catmark_car.obj', { depth: 3 }), [...fixed, '--tess', '4'], [4], ['lit', 'levels']],
  // The view-adaptive tessellation (limn-render's default: --max-error 0.1, --edge-pixels 32).
  ['adaptive: spot depth 3', spot(3), [], [1, 4], ['lit', 'levels']],
  ['adaptive: spot depth 3, normals and per-sample shading', spot(3), ['--sample-shading'], [4], ['normal', 'lit']],
  ['adaptive: spot depth 6', spot(6), [], [4], ['lit']],
  ['adaptive: creased torus depth 3', () => container('osd/catmark/catmark_torus_creases0.obj', { depth: 3 }), ['--view', '30,40'], [4], ['lit', 'levels']],
  ['adaptive: paper sphere depth 6 in its camera', sphere6, ['--eye', '0,12,22', '--target', '0,0,0', '--size', '1280x720'], [4], ['lit']],
  ['adaptive: car depth 6', () => container('osd/catmark/catmark_car.obj', { depth: 6 }), [], [4], ['lit']],
  // A colour texture (--texture; --color tints it), on both tessellations.
  ['fixed: spot depth 2 with its texture', spot(2), [...fixed, '--texture', spotTexture], [4], ['lit']],
  ['adaptive: spot depth 2 with its texture, tinted', spot(2), ['--texture', spotTexture, '--color', '1,0.6,0.4'], [1], ['lit']],
  // The wireframe overlay of the triangles drawn (--wire-triangles).
  ['fixed: spot depth 2, smooth UVs, checker texture', spotSmooth, [...fixed, '--texture', checker()], [4], ['lit']],
  ['adaptive: spot depth 2, smooth UVs, checker texture', spotSmooth, ['--texture', checker()], [1], ['lit']],
  ['fixed: spot depth 2, smooth UVs, shaded by UV', spotSmooth, fixed, [1], ['uv']],
  ['fixed: spot depth 2 with its triangles\' wireframe', spot(2), [...fixed, '--wire-triangles'], [4], ['lit']],
  ['adaptive: spot depth 2 with its triangles\' wireframe', spot(2), ['--wire-triangles'], [1], ['levels']],
];

for (const [label, make, args, samplesList, shades] of cases) {
  test(`images: ${label}`, async () => {
    const limn = make();
    for (const samples of samplesList) {
      for (const shade of shades) {
        const name = `${label.replace(/\W+/g, '_')}-${samples}-${shade}`;
        const size = args.includes('--size') ? [] : ['--size', '320x240'];
        const r = await renderBoth(limn, [...size, '--samples', String(samples), '--shade', shade, ...args], name);
        assert.ok(r.covered > 2000, `${name}: only ${r.covered} covered pixels`);
        assert.ok(r.fraction <= 0.005, `${name}: ${r.off} of ${r.covered} covered pixels differ by more than 8/255 (worst ${r.worst})`);
      }
    }
  });
}

// Per-pixel limit normals (--pixel-normals) with the coarser interior they pay for
// (--interior-error 1): the pixel pipelines (surface_pixel.vert, surface_lit_pixel.frag and, with
// --sample-shading, their per-sample variants) and the emit pass's per-element vertices. Against
// the same limn-render image, the web drawing the interpolated normals instead is further off
// (0.7% of covered pixels at 4 samples on lavapipe, against none), so these can fail.
test('images: adaptive spot depth 3, per-pixel normals and the interior error', async () => {
  const limn = spot(3)();
  for (const [samples, extra] of [['1', []], ['4', ['--sample-shading']]]) {
    const args = ['--size', '320x240', '--samples', samples, ...extra, '--pixel-normals', '--interior-error', '1'];
    const name = `pixel-normals-${samples}`;
    const r = await renderBoth(limn, args, name);
    assert.ok(r.covered > 2000, `${name}: only ${r.covered} covered pixels`);
    assert.ok(r.fraction <= 0.005, `${name}: ${r.off} of ${r.covered} covered pixels differ by more than 8/255 (worst ${r.worst})`);
    const interpolated = await renderBoth(limn, args, name, args.filter((a) => a !== '--pixel-normals'));
    assert.ok(interpolated.off > r.off, `${name}: the web's interpolated normals are as close to limn-render's per-pixel image (${interpolated.off} pixels off) as its per-pixel normals (${r.off})`);
  }
});

test('smooth UVs are not the linear ones (the smooth-UV cases above can fail)', async () => {
  const linear = container('quad/spot_quadrangulated.obj', { depth: 2 });
  const render = (limn, name) => {
    const out = join(scratch, `${name}.png`);
    execFileSync(tool('limn-render'), [limn, '-o', out, '--size', '320x240', '--samples', '1', '--edge-pixels', '0', '--texture', checker()], { env, stdio: 'ignore' });
    return decodePng(readFileSync(out));
  };
  const r = compareImages(render(linear, 'checker-linear'), render(spotSmooth(), 'checker-smooth'));
  assert.ok(r.fraction > 0.02, `linear and smooth UVs differ in only ${r.off} of ${r.covered} covered pixels`);
});

test('the same command twice writes the same bytes', () => {
  const limn = container('quad/spot_quadrangulated.obj', { depth: 1 });
  const a = join(scratch, 'twice-a.png'), b = join(scratch, 'twice-b.png');
  for (const out of [a, b]) execFileSync(process.execPath, [cli, limn, '-o', out, '--size', '200x150', '--samples', '4'], { env, stdio: 'ignore' });
  assert.deepEqual(readFileSync(a), readFileSync(b));
});

// A glTF's material (limn-classify keeps it in MATL): its base colour texture is drawn without
// --texture, through the command line (its map and MATL handling), on both tessellations.
test('a MATL base colour texture (BoxTextured.glb), through limn-web-render', () => {
  const limn = container('gltf/BoxTextured/BoxTextured.glb', { depth: 2 });
  for (const ep of ['0', '4']) {
    const args = ['--size', '320x240', '--edge-pixels', ep];
    const native = join(scratch, `box-${ep}-native.png`), web = join(scratch, `box-${ep}-web.png`);
    execFileSync(tool('limn-render'), ['-q', limn, '-o', native, ...args], { env, stdio: ['ignore', 'ignore', 'pipe'] });
    execFileSync(process.execPath, [cli, limn, '-o', web, ...args], { env, stdio: ['ignore', 'ignore', 'pipe'] });
    const r = compareImages(decodePng(readFileSync(web)), decodePng(readFileSync(native)));
    assert.ok(r.covered > 20000, `edge pixels ${ep}: only ${r.covered} covered pixels`);
    assert.ok(r.fraction <= 0.005, `edge pixels ${ep}: ${r.off} of ${r.covered} covered pixels differ by more than 8/255 (worst ${r.worst})`);
  }
});
