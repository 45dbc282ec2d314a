// The viewer in headless Chromium (WebGPU on SwiftShader) against limn-render (Vulkan on the
// system's lavapipe): the page's canvas, opened with ?model=, for spot at depth 3, lit and
// levels, 1 and 4 samples; then interaction on the same page (a drag turns the view and the URL
// follows; the URL reloaded draws the same bytes; a truncated container dropped on the page
// shows the reader's error and the page goes on working), with no console error or warning.
// Fixed grids and view-adaptive tessellation (limn-render's default) both. Maps: the README's
// displaced quad_sphere (seam fix on and off, a dropped map, the wireframe) and spot's texture.
//
// What differs, and why: with 1 sample the two agree within the criterion (at most 1% of the
// covered pixels off by more than 8/255; measured 17 of 14362 lit, 55 levels). With 4 samples
// SwiftShader's multisampled rasterization covers the samples of a pixel that an edge crosses
// differently from lavapipe's: as many pixels come out lighter as darker, up to ~80/255, along
// the silhouette (212 of 14591 lit, 1.5%) and, with --shade levels, along the colour steps
// between patches. Pixel centres agree (the 1-sample images); the cause inside SwiftShader was not
// looked into. So the 4-sample images are held to the criterion away from the silhouette, and the
// whole image to 3%.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, quadSphere, repo, scratch, tool } from '../../test/support.mjs';
import { decodePng } from '../../src/png.mjs';
import { loadLimn } from '../../src/chunks.mjs';
import { launch, newPage, settled, frames, errorText, serveModels } from './browser.mjs';

const SIZE = [320, 240];
const BG = [51, 51, 51];
let browser, server, spot, sphere, page;

before(async () => {
  spot = container('quad/spot_quadrangulated.obj', { depth: 3 });
  sphere = quadSphere();
  // One origin for every page: Chromium keeps compiled pipelines per origin.
  server = await serveModels({
    'spot_d3.limn': spot, 'spot_d1.limn': container('quad/spot_quadrangulated.obj', { depth: 1 }),
    'quad_sphere.limn': sphere.limn, 'quad_sphere.height.png': sphere.height, 'uv-noise.png': sphere.noise,
    'spot_texture.png': join(repo, 'tests/data/textures/spot_texture.png'),
  });
  browser = await launch();
  page = await newPage(browser);
});
after(async () => { await browser?.close(); server?.stop(); });

const base = () => server.url.replace(/\/$/, '');
const shot = async () => decodePng(await page.locator('#view').screenshot());

function native(limn, args, name) {
  const out = join(scratch, `${name}.png`);
  execFileSync(tool('limn-render'), [limn, '-o', out, '--size', SIZE.join('x'), ...args], { stdio: ['ignore', 'ignore', 'pipe'] });
  return decodePng(readFileSync(out));
}

const isBg = (img, i) => img.rgba[4 * i] === BG[0] && img.rgba[4 * i + 1] === BG[1] && img.rgba[4 * i + 2] === BG[2];
/** Covered pixels, those off by more than `tolerance`/255 (8), and the same split at and away from the silhouette. */
function compare(a, b, tolerance = 8) {
  assert.equal(a.width, b.width);
  assert.equal(a.height, b.height);
  const r = { covered: 0, off: 0, interior: 0, interiorOff: 0, worst: 0 };
  for (let y = 0; y < a.height; y++) {
    for (let x = 0; x < a.width; x++) {
      const i = y * a.width + x;
      if (isBg(a, i) && isBg(b, i)) continue;
      let d = 0;
      for (let c = 0; c < 3; c++) d = Math.max(d, Math.abs(a.rgba[4 * i + c] - b.rgba[4 * i + c]));
      let silhouette = false;
      for (let dy = -1; dy <= 1; dy++) {
        for (let dx = -1; dx <= 1; dx++) {
          const X = x + dx, Y = y + dy;
          if (X >= 0 && Y >= 0 && X < a.width && Y < a.height && (isBg(a, Y * a.width + X) || isBg(b, Y * a.width + X))) silhouette = true;
        }
      }
      r.covered++;
      if (d > tolerance) r.off++;
      if (!silhouette) { r.interior++; if (d > tolerance) r.interiorOff++; }
      r.worst = Math.max(r.worst, d);
    }
  }
  return r;
}

function check(name, r, samples) {
  const what = `${name}: ${r.off} of ${r.covered} covered pixels off by more than 8/255 (${r.interiorOff} of ${r.interior} away from the silhouette; worst ${r.worst})`;
  assert.ok(r.covered > 5000, `${name}: only ${r.covered} covered pixels`);
  if (samples === 1) assert.ok(r.off <= 0.01 * r.covered, what);
  else {
    assert.ok(r.interiorOff <= 0.01 * r.interior, what);
    assert.ok(r.off <= 0.03 * r.covered, what);
  }
  return what;
}

test('spot depth 3 from ?model=: lit and levels, 4 then 1 samples, as limn-render draws them', async (t) => {
  await page.goto(`${base()}/viewer/?model=../models/spot_d3.limn&size=${SIZE.join('x')}&edgePixels=0&samples=4`);
  await settled(page);
  assert.equal(await errorText(page), '');
  const common = ['--view', '-30,20', '--edge-pixels', '0'];
  t.diagnostic(check('spot lit, 4 samples', compare(await shot(), native(spot, [...common, '--samples', '4'], 'spot-lit-4')), 4));
  // The panel's shade control; no new renderer, the next frame.
  let n = await frames(page);
  await page.getByLabel('levels').check();
  await settled(page, n + 1);
  t.diagnostic(check('spot levels, 4 samples', compare(await shot(), native(spot, [...common, '--samples', '4', '--shade', 'levels'], 'spot-levels-4')), 4));
  // Per-pixel normals are the view-adaptive lit shading's only: elsewhere the box is disabled, saying why.
  assert.equal(await page.locator('#pixelNormals').isDisabled(), true);
  assert.equal(await page.locator('#pixelNormals').locator('xpath=..').getAttribute('title'), 'not with the fixed grids');
  assert.match(await page.evaluate(() => location.search), /shade=levels/);
  n = await frames(page);
  await page.selectOption('#samples', '1');
  await settled(page, n + 1);
  t.diagnostic(check('spot levels, 1 sample', compare(await shot(), native(spot, [...common, '--samples', '1', '--shade', 'levels'], 'spot-levels-1')), 1));
  n = await frames(page);
  await page.getByLabel('lit').check();
  await settled(page, n + 1);
  t.diagnostic(check('spot lit, 1 sample', compare(await shot(), native(spot, [...common, '--samples', '1'], 'spot-lit-1')), 1));
  // View-adaptive (limn-render's default) from the panel: a new renderer.
  n = await frames(page);
  await page.getByLabel('View-adaptive').check();
  await settled(page, n + 1);
  t.diagnostic(check('spot lit, 1 sample, view-adaptive', compare(await shot(), native(spot, ['--view', '-30,20', '--samples', '1', '--edge-pixels', '32'], 'spot-adaptive-1')), 1));
  assert.doesNotMatch(await page.evaluate(() => location.search), /edgePixels/);
  // The command the panel prints is the one that drew the reference.
  assert.equal(await page.locator('#command').textContent(),
    'limn-render spot_d3.limn -o view.png --size 320x240 --view -30,20 --shade lit --samples 1 --max-error 0.1 --edge-pixels 32 --tess 64');
});

test('a drag turns the view, the URL follows, and reloading it draws the same image', async (t) => {
  const before = await shot();
  const search = await page.evaluate(() => location.search);
  assert.match(search, /view=-30,20/);
  const box = await page.locator('#view').boundingBox();
  const n = await frames(page);
  await page.mouse.move(box.x + 160, box.y + 120);
  await page.mouse.down();
  await page.mouse.move(box.x + 220, box.y + 100, { steps: 4 });
  await page.mouse.up();
  await settled(page, n + 1);
  const url = await page.evaluate(() => location.href);
  // 60 px right and 20 px up at 0.4 degrees a pixel: azimuth -24 degrees, elevation -8.
  assert.match(url, /view=-54,12(&|$)/, url);
  const turned = await shot();
  const moved = compare(before, turned);
  assert.ok(moved.off > 0.2 * moved.covered, `the drag changed only ${moved.off} of ${moved.covered} pixels`);
  // The same view by limn-render from the URL's options (the check above, 1 sample).
  t.diagnostic(check('spot after the drag', compare(turned, native(spot, ['--view', '-54,12', '--edge-pixels', '32', '--samples', '1'], 'spot-dragged')), 1));
  await page.reload();
  await settled(page);
  const again = await shot();
  assert.deepEqual(Buffer.from(again.rgba), Buffer.from(turned.rgba), 'the reloaded URL draws other pixels');
  // Nothing changes, nothing is drawn.
  const drawn = await frames(page);
  await page.waitForTimeout(1500);
  assert.equal(await frames(page), drawn, 'the page drew frames while nothing changed');
});

// The rate controls make a new renderer with the new rates: a coarser max error and interior
// error draw fewer triangles, and per-pixel normals change the shading to limn-render's
// --pixel-normals image (its own pipelines), not the interpolated normals' image.
test('max error, interior error and per-pixel normals from the panel draw what limn-render draws with them', async (t) => {
  const p = await newPage(browser);
  try {
    await p.goto(`${base()}/viewer/?model=../models/spot_d3.limn&size=${SIZE.join('x')}&samples=1`);
    await settled(p);
    const triangles = async () => +(await p.locator('#st-tris').textContent()).replace(/,/g, '');
    const shotOf = async () => decodePng(await p.locator('#view').screenshot());
    const set = async (change) => { const n = await frames(p); await change(); await settled(p, n + 1); };
    const number = (id, v) => set(() => p.fill(id, v).then(() => p.locator(id).dispatchEvent('change')));
    const byDefault = await triangles();
    await number('#interiorError', '1');
    const interior = await triangles();
    assert.ok(interior < 0.9 * byDefault, `--interior-error 1 drew ${interior} triangles, without ${byDefault}`);
    const interpolated = await shotOf();
    await set(() => p.getByLabel('Per-pixel normals').check());
    assert.equal(await triangles(), interior, 'per-pixel normals changed the rates');
    const perPixel = await shotOf();
    const args = ['--view', '-30,20', '--samples', '1', '--interior-error', '1', '--pixel-normals'];
    t.diagnostic(check('spot, per-pixel normals', compare(perPixel, native(spot, args, 'spot-pixel-normals')), 1));
    // The shading moves by a few levels where the interior's triangles are large (at 320x240
    // few pixels move by more than 8/255), so any change of more than 1/255 counts.
    const changed = compare(perPixel, interpolated, 1);
    t.diagnostic(`per-pixel against interpolated normals: ${changed.off} of ${changed.covered} pixels off by more than 1/255`);
    assert.ok(changed.off >= 0.02 * changed.covered, `per-pixel normals changed only ${changed.off} pixels`);
    await number('#maxError', '0.25');
    const coarse = await triangles();
    assert.ok(coarse < 0.8 * interior, `--max-error 0.25 drew ${coarse} triangles, 0.1 ${interior}`);
    assert.match(p.url(), /maxError=0.25&interiorError=1&pixelNormals=1/);
    assert.equal(await p.locator('#command').textContent(),
      'limn-render spot_d3.limn -o view.png --size 320x240 --view -30,20 --shade lit --samples 1 --max-error 0.25 --edge-pixels 32 --tess 64 --interior-error 1 --pixel-normals');
    assert.deepEqual(p.problems, []);
  } finally {
    await p.close();
  }
});

test('a truncated or damaged container dropped on the page shows the reader\'s error; the page goes on working', async (t) => {
  // Where the drag left the page (or there, when this test runs alone).
  if (!/view=-54,12/.test(page.url())) {
    await page.goto(`${base()}/viewer/?model=../models/spot_d3.limn&view=-54,12&size=${SIZE.join('x')}&samples=1`);
    await settled(page);
  }
  const bytes = readFileSync(spot).subarray(0, 4000);
  let expected;
  try { loadLimn(new Uint8Array(bytes)); } catch (e) { expected = `truncated.limn: ${e.message}`; }
  assert.ok(expected, 'the runtime reads the truncated container without an error');
  await page.evaluate(async () => {
    const b = await (await fetch('../models/spot_d3.limn')).arrayBuffer();
    const dt = new DataTransfer();
    dt.items.add(new File([b.slice(0, 4000)], 'truncated.limn'));
    document.getElementById('stage').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction(() => document.getElementById('errors').textContent !== '');
  assert.equal(await errorText(page), expected);
  t.diagnostic(`shown: ${expected}`);
  // A damaged chunk: the error names it.
  const damaged = new Uint8Array(readFileSync(spot));
  damaged[100000] ^= 0xff;
  try { loadLimn(damaged); } catch (e) { expected = `damaged.limn: ${e.message}`; }
  assert.match(expected, /^damaged\.limn: chunk [A-Z]{4}: /);
  await page.evaluate(async () => {
    const b = new Uint8Array(await (await fetch('../models/spot_d3.limn')).arrayBuffer());
    b[100000] ^= 0xff;
    const dt = new DataTransfer();
    dt.items.add(new File([b], 'damaged.limn'));
    document.getElementById('stage').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction((text) => document.getElementById('errors').textContent === text, expected);
  t.diagnostic(`shown: ${expected}`);
  // An image the browser cannot decode, dropped as a map: said so, next to the container's error.
  await page.evaluate(() => {
    const dt = new DataTransfer();
    dt.items.add(new File([new Uint8Array([0x89, 0x50, 0x4e, 0x47, 1, 2, 3])], 'broken.png', { type: 'image/png' }));
    document.getElementById('stage').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction(() => document.querySelectorAll('#errors .error').length === 2);
  const mapError = await page.locator('#errors .error').nth(1).textContent();
  assert.match(mapError, /^broken\.png: the browser cannot decode this image \(.+\); use PNG, JPEG or WebP$/);
  t.diagnostic(`shown: ${mapError}`);
  // Still spot, still turning: a key press draws the next view.
  const before = await shot();
  const n = await frames(page);
  await page.locator('#stage').focus();
  await page.keyboard.press('ArrowLeft');
  await settled(page, n + 1);
  assert.match(await page.evaluate(() => location.search), /view=-49,12/);
  const after = compare(before, await shot());
  assert.ok(after.off > 0.05 * after.covered, 'the key press did not turn the view');
  // The turntable turns the view frame after frame until it is turned off.
  const turning = await frames(page);
  await page.locator('#turntable').check();
  await page.waitForFunction((n) => +document.body.dataset.frames >= n + 2, turning);
  await page.locator('#turntable').uncheck();
  await settled(page);
  assert.match(await page.evaluate(() => location.search), /view=-4[0-8](\.\d+)?,12(&|$)/);
  const stopped = await frames(page);
  await page.waitForTimeout(1000);
  assert.equal(await frames(page), stopped);
  // Two fingers moving apart zoom in: the camera becomes explicit (eye and target in the URL).
  const box = await page.locator('#view').boundingBox();
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Emulation.setTouchEmulationEnabled', { enabled: true, maxTouchPoints: 2 });
  const touch = (type, d) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: type === 'touchEnd' ? [] : [{ x: box.x + 160 - d, y: box.y + 120, id: 1 }, { x: box.x + 160 + d, y: box.y + 120, id: 2 }],
  });
  const pinched = await frames(page);
  await touch('touchStart', 20);
  for (const d of [30, 40]) await touch('touchMove', d);
  await touch('touchEnd', 40);
  await settled(page, pinched + 1);
  assert.match(await page.evaluate(() => location.search), /eye=[-\d.e]+,[-\d.e]+,[-\d.e]+&target=/);
  assert.deepEqual(page.problems, []);
});

test('without a WebGPU adapter the page says what to enable', async () => {
  const { chromium } = await import('playwright-core');
  const { CHROMIUM, FLAGS } = await import('./browser.mjs');
  const plain = await chromium.launch({ executablePath: CHROMIUM, args: FLAGS.filter((f) => !/webgpu|vulkan|angle/i.test(f)) });
  try {
    const p = await plain.newPage();
    await p.goto(`${base()}/viewer/?model=../models/spot_d3.limn`);
    await p.waitForFunction(() => document.body.dataset.ready === '1');
    assert.match(await p.locator('#errors').textContent(), /^WebGPU is there but offers no adapter .* --enable-unsafe-webgpu --enable-features=Vulkan/);
  } finally {
    await plain.close();
  }
});

test('?bench=N prints one JSON line per tessellation on the console', async () => {
  const p = await newPage(browser);
  try {
    const lines = [];
    const done = new Promise((resolve) => p.on('console', (m) => {
      if (m.text().startsWith('{')) lines.push(JSON.parse(m.text()));
      if (m.text() === 'limn-viewer bench: done') resolve();
    }));
    await p.goto(`${base()}/viewer/?model=../models/spot_d1.limn&size=96x72&samples=1&edgePixels=0&bench=2`);
    await done;
    assert.deepEqual(lines.map((l) => [l.tessellation, l.edge_pixels, l.max_error, l.depth, l.frames, l.size.join('x')]),
      [['fixed', 0, null, 1, 2, '96x72'], ['adaptive', 32, 0.1, 1, 2, '96x72']]);
    for (const l of lines) {
      assert.ok(l.triangles > 0 && l.js_ms > 0 && l.wall_ms >= l.js_ms, JSON.stringify(l));
      assert.ok(l.gpu_ms === null || l.gpu_ms > 0, JSON.stringify(l));
    }
    assert.deepEqual(p.problems, []);
  } finally {
    await p.close();
  }
});

// The paper's Figure 14, live: the README's displaced quad_sphere (its height map from ?displace=,
// scale and mid from the link), as limn-render draws it with the seam fix, then with the panel's
// seam fix turned off, then view-adaptive; one page, 1 sample (see above for SwiftShader's 4).
test('the displaced quad_sphere from ?displace=: seam fix on and off, fixed and view-adaptive, wireframe, as limn-render draws it', async (t) => {
  const p = await newPage(browser);
  try {
    const shotOf = async () => decodePng(await p.locator('#view').screenshot());
    await p.goto(`${base()}/viewer/?model=../models/quad_sphere.limn&displace=../models/quad_sphere.height.png&displaceScale=0.2&displaceMid=0.5&size=${SIZE.join('x')}&samples=1&edgePixels=0`);
    await settled(p);
    assert.equal(await p.locator('#errors').textContent(), '');
    const args = ['--view', '-30,20', '--samples', '1', '--displace', sphere.height, '--displace-scale', '0.2', '--displace-mid', '0.5'];
    const fixed = await shotOf();
    t.diagnostic(check('displaced, seam fix, fixed grids', compare(fixed, native(sphere.limn, [...args, '--edge-pixels', '0'], 'sphere-fixed')), 1));
    let n = await frames(p);
    await p.locator('#seamFix').uncheck();
    await settled(p, n + 1);
    assert.match(await p.evaluate(() => location.search), /seamFix=0/);
    t.diagnostic(check('displaced, no seam fix, fixed grids', compare(await shotOf(), native(sphere.limn, [...args, '--edge-pixels', '0', '--no-seam-fix'], 'sphere-nofix')), 1));
    n = await frames(p);
    await p.locator('#seamFix').check();
    await p.getByLabel('View-adaptive').check();
    await settled(p, n + 1);
    t.diagnostic(check('displaced, seam fix, view-adaptive', compare(await shotOf(), native(sphere.limn, [...args, '--edge-pixels', '32'], 'sphere-adaptive')), 1));
    assert.equal(await p.locator('#command').textContent(),
      `limn-render quad_sphere.limn -o view.png --size 320x240 --view -30,20 --shade lit --samples 1 --max-error 0.1 --edge-pixels 32 --tess 64 --displace quad_sphere.height.png --displace-scale 0.2 --displace-mid 0.5`);
    // The wireframe overlay: the triangles this view's rates chose (limn-render --wire-triangles).
    n = await frames(p);
    await p.locator('#wire').check();
    await settled(p, n + 1);
    assert.match(await p.locator('#command').textContent(), / --wire-triangles /);
    t.diagnostic(check('displaced, view-adaptive, wireframe', compare(await shotOf(), native(sphere.limn, [...args, '--edge-pixels', '32', '--wire-triangles'], 'sphere-wire')), 1));
    // Another map dropped on the page replaces the first (a local file: not in the URL).
    n = await frames(p);
    await p.evaluate(async () => {
      const b = await (await fetch('../models/uv-noise.png')).arrayBuffer();
      const dt = new DataTransfer();
      dt.items.add(new File([b], 'uv-noise.png', { type: 'image/png' }));
      document.getElementById('stage').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    });
    await settled(p, n + 1);
    assert.doesNotMatch(await p.evaluate(() => location.search), /displace=/);
    assert.match(await p.locator('#command').textContent(), / --displace uv-noise\.png /);
    const noisy = args.map((a) => (a === sphere.height ? sphere.noise : a));
    t.diagnostic(check('dropped UV-noise map, view-adaptive, wireframe', compare(await shotOf(), native(sphere.limn, [...noisy, '--edge-pixels', '32', '--wire-triangles'], 'sphere-noise')), 1));
    assert.deepEqual(p.problems, []);
  } finally {
    await p.close();
  }
});

// A colour map from ?texture= (decoded by the browser, read back through WebGPU): spot's own
// texture, drawn as limn-render --texture draws it (shade texture, white base).
test('spot with its texture from ?texture=, as limn-render --texture draws it', async (t) => {
  const p = await newPage(browser);
  try {
    await p.goto(`${base()}/viewer/?model=../models/spot_d1.limn&texture=../models/spot_texture.png&size=${SIZE.join('x')}&samples=1&edgePixels=0`);
    await settled(p);
    assert.equal(await p.locator('#errors').textContent(), '');
    assert.match(await p.evaluate(() => location.search), /shade=texture/);
    const texture = join(repo, 'tests/data/textures/spot_texture.png');
    const shotOf = decodePng(await p.locator('#view').screenshot());
    t.diagnostic(check('spot textured', compare(shotOf, native(container('quad/spot_quadrangulated.obj', { depth: 1 }), ['--view', '-30,20', '--samples', '1', '--edge-pixels', '0', '--texture', texture], 'spot-texture')), 1));
    // The panel says what a dropped image becomes: here a colour texture, replacing the linked one.
    await p.selectOption('#map-kind', 'texture');
    await p.evaluate(async () => {
      const b = await (await fetch('../models/spot_texture.png')).arrayBuffer();
      const dt = new DataTransfer();
      dt.items.add(new File([b], 'dropped.png', { type: 'image/png' }));
      document.getElementById('stage').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    });
    await p.waitForFunction(() => /^dropped\.png: 1024×1024, as colour map$/.test(document.getElementById('map-name').textContent));
    await settled(p);
    assert.match(await p.locator('#command').textContent(), / --shade texture .*--texture dropped\.png$/);
    assert.deepEqual(p.problems, []);
  } finally {
    await p.close();
  }
});
