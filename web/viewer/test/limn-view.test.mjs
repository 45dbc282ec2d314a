// limn-view: serves the viewer, the runtime and the model on 127.0.0.1 and prints the URL;
// refuses what is not a container and a port in use, in words, with limn's exit codes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, repo, scratch } from '../../test/support.mjs';
import { startView } from './browser.mjs';

const cli = join(repo, 'web/bin/limn-view.mjs');
const run = (args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 20000 });

test('serves the page, its modules and shaders, and the model, on 127.0.0.1 only', async () => {
  const limn = container('quad/spot_quadrangulated.obj', { depth: 1 });
  const view = await startView([limn]);
  try {
    const url = new URL(view.url);
    assert.equal(url.hostname, '127.0.0.1');
    assert.equal(url.pathname, '/viewer/');
    const model = url.searchParams.get('model');
    assert.equal(model, '/model/quad_spot_quadrangulated_obj_d1.limn');
    const page = await fetch(view.url);
    assert.equal(page.status, 200);
    assert.match(page.headers.get('content-type'), /text\/html/);
    assert.match(await page.text(), /<script type="module" src="viewer.mjs">/);
    for (const [path, type] of [['/viewer/viewer.mjs', /javascript/], ['/src/index.mjs', /javascript/], ['/shaders/surface_vert.wgsl', /text\/plain/]]) {
      const r = await fetch(new URL(path, url));
      assert.equal(r.status, 200, path);
      assert.match(r.headers.get('content-type'), type, path);
    }
    const bytes = Buffer.from(await (await fetch(new URL(model, url))).arrayBuffer());
    assert.deepEqual(bytes, readFileSync(limn));
    // The root opens the viewer on the model; nothing outside the served folders is reachable.
    const root = await fetch(new URL('/', url), { redirect: 'manual' });
    assert.equal(root.status, 302);
    assert.equal(root.headers.get('location'), `/viewer/?model=${model}`);
    for (const path of ['/package.json', '/viewer/%2e%2e/package.json', '/src/..%2fpackage.json', '/bin/limn-view.mjs', '/viewer/node_modules/playwright-core/package.json']) {
      const r = await fetch(new URL(path, url));
      assert.equal(r.status, 404, path);
      assert.match(await r.text(), /^not found: /);
    }
  } finally {
    view.stop();
  }
});

test('a port in use is an error that says so (exit 1), and so is a file that is not a container', async () => {
  const limn = container('quad/spot_quadrangulated.obj', { depth: 1 });
  const first = await startView([limn]);
  try {
    const port = new URL(first.url).port;
    const r = run([limn, '--port', port]);
    assert.equal(r.status, 1);
    assert.equal(r.stdout, '');
    assert.equal(r.stderr, `limn-view: error: port ${port} on 127.0.0.1 is in use (another limn-view or server?); give another with --port P, or --port 0 for any free one\n`);
  } finally {
    first.stop();
  }
  const obj = join(scratch, 'not-a-container.limn');
  writeFileSync(obj, 'v 0 0 0\n');
  const bad = run([obj]);
  assert.equal(bad.status, 1);
  assert.match(bad.stderr, /^limn-view: error: .*not-a-container\.limn: not a \.limn container/);
  const missing = run([join(scratch, 'missing.limn')]);
  assert.equal(missing.status, 1);
  assert.match(missing.stderr, /missing\.limn: cannot read it \(ENOENT\)/);
  for (const args of [[], ['--port', '70000', limn], ['--bogus', limn], [limn, limn]]) {
    const u = run(args);
    assert.equal(u.status, 2, `${args.join(' ')}: ${u.stderr}`);
    assert.match(u.stderr, /^limn-view: error: /);
  }
});

test('--displace serves the map beside the model and opens the viewer displaced by it', async () => {
  const limn = container('quad/spot_quadrangulated.obj', { depth: 1 });
  const map = join(repo, 'tests/data/textures/spot_texture.png');
  const view = await startView([limn, '--displace', map, '--displace-scale', '0.05', '--displace-mid', '0.5']);
  try {
    const url = new URL(view.url);
    assert.equal(url.searchParams.get('displace'), '/map/spot_texture.png');
    assert.equal(url.searchParams.get('displaceScale'), '0.05');
    assert.equal(url.searchParams.get('displaceMid'), '0.5');
    assert.deepEqual(Buffer.from(await (await fetch(new URL('/map/spot_texture.png', url))).arrayBuffer()), readFileSync(map));
  } finally {
    view.stop();
  }
  for (const args of [[limn, '--displace-scale', '2'], [limn, '--displace', map, '--texture', map], [limn, '--displace', map, '--displace-mid', 'x']]) {
    const u = run(args);
    assert.equal(u.status, 2, `${args.join(' ')}: ${u.stderr}`);
  }
  assert.equal(run([limn, '--texture', join(scratch, 'absent.png')]).status, 1);
});
