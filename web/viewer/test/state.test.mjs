// The viewer's URL state (state.mjs) and camera edits (orbit.mjs), without a browser.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseQuery, toQuery, renderCommand, DEFAULTS } from '../state.mjs';
import { orbit, zoom, frame, directionOf, anglesOf } from '../orbit.mjs';

test('a link round-trips: parse(toQuery(state)) is the state', () => {
  const q = parseQuery('model=m.limn&view=12.5,-30&shade=levels&samples=1&edgePixels=0&tess=16&size=320x240&upAxis=z&fov=50');
  assert.deepEqual(q.errors, []);
  assert.equal(q.model, 'm.limn');
  assert.deepEqual(q.state.view, [12.5, -30]);
  assert.equal(q.state.upAxis, 'z');
  const again = parseQuery(toQuery(q.state, { model: q.model }));
  assert.deepEqual(again.state, q.state);
  assert.equal(toQuery(DEFAULTS), 'view=-30,20');
});

test('a bad parameter is reported in words and keeps its default; the rest of the link holds', () => {
  const q = parseQuery('view=400,0&samples=2&shade=shiny&tess=0&target=1,2,3&edgePixels=8');
  assert.deepEqual(q.errors, [
    'view=400,0: azimuth -360 to 360, elevation -90 to 90', 'shade=shiny: one of lit, levels, normal, uv, texture',
    'samples=2: 1 or 4', 'tess=0: an integer from 1 to 4096', 'target and up describe an explicit camera: give eye too (ignored)']);
  assert.deepEqual(q.state, { ...DEFAULTS, edgePixels: 8 });
});

test('the limn-render command names the same options', () => {
  const q = parseQuery('eye=0,12,22&target=0,0,0&shade=levels&samples=1&edgePixels=0&tess=16');
  assert.equal(renderCommand(q.state, { modelName: 'sphere d6.limn', width: 1280, height: 720 }),
    "limn-render 'sphere d6.limn' -o view.png --size 1280x720 --eye 0,12,22 --target 0,0,0 --shade levels --samples 1 --edge-pixels 0 --tess 16");
  // The view-adaptive default names limn-render's defaults, and a link's maxError is kept.
  assert.match(renderCommand(DEFAULTS, { width: 64, height: 48 }), / --max-error 0\.1 --edge-pixels 32 --tess 64$/);
  const e = parseQuery('maxError=0.5&edgePixels=8');
  assert.deepEqual(e.errors, []);
  assert.equal(toQuery(e.state), 'view=-30,20&maxError=0.5&edgePixels=8');
  assert.match(renderCommand(e.state, { width: 64, height: 48 }), / --max-error 0\.5 --edge-pixels 8 /);
  assert.deepEqual(parseQuery('maxError=-1').errors, ['maxError=-1: a number from 0 to 4096']);
  // Per-pixel normals and the interior error: limn-render's options, view-adaptive only.
  const p = parseQuery('interiorError=1&pixelNormals=1');
  assert.deepEqual(p.errors, []);
  assert.equal(toQuery(p.state), 'view=-30,20&interiorError=1&pixelNormals=1');
  assert.match(renderCommand(p.state, { width: 64, height: 48 }), / --tess 64 --interior-error 1 --pixel-normals$/);
  assert.doesNotMatch(renderCommand({ ...p.state, edgePixels: 0 }, { width: 64, height: 48 }), /interior|pixel-normals/);
  assert.deepEqual(parseQuery('interiorError=x&pixelNormals=2').errors, ['interiorError=x: a number from 0 to 4096', 'pixelNormals=2: 1 or 0']);
});

test('orbit keeps a framed view framed; zoom makes it explicit; frame goes back from the same direction', () => {
  const s = { ...DEFAULTS };
  assert.deepEqual(orbit(s, -24, -8, null).view, [-54, 12]);
  assert.deepEqual(orbit({ ...s, view: [170, 89] }, 20, 5, null).view, [-170, 89.9]);
  const camera = { eye: [0, 0, 10], target: [0, 0, 0], up: [0, 1, 0] };
  const z = zoom(s, 0.5, camera);
  assert.deepEqual(z.eye, [0, 0, 5]);
  assert.deepEqual(z.target, [0, 0, 0]);
  const turned = orbit(z, 90, 0, camera);
  assert.deepEqual(turned.eye.map((x) => Math.round(x * 1e4) / 1e4), [5, 0, 0]);
  assert.deepEqual(frame(turned, { ...camera, eye: turned.eye }).view, [90, 0]);
  // The direction of limn-render's --view AZ,EL (front +Z, right +X; Z-up: front -Y).
  for (const zUp of [false, true]) {
    const [az, el] = anglesOf(directionOf([-30, 20], zUp), zUp);
    assert.ok(Math.abs(az + 30) < 1e-9 && Math.abs(el - 20) < 1e-9);
  }
  assert.deepEqual(directionOf([0, 0], true).map((x) => Math.round(x)), [0, -1, 0]);
});
