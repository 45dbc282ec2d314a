// limn-web-render's command line: exit codes (1 bad input, 2 usage, 3 capability), errors in
// limn's format naming the file and chunk, no output file left behind, no hang (timeouts).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, scratch, repo } from './support.mjs';
import { encodePng } from '../src/png.mjs';

const cli = join(repo, 'web/bin/limn-web-render.mjs');
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });

test('usage errors exit 2', () => {
  for (const args of [[], ['x.limn'], ['--frobnicate'], ['x.limn', '-o', 'y.png', '--samples', '3'], ['x.limn', '-o', 'y.jpg'], ['x.limn', '-o', 'y.png', '--wire', '--wire-triangles']]) {
    const r = run(...args);
    assert.equal(r.status, 2, `${args.join(' ')}: ${r.stderr}`);
    assert.match(r.stderr, /^limn-web-render: error: /);
  }
  assert.equal(run('--help').status, 0);
});

test('damaged containers exit 1 naming the chunk, and leave no output', () => {
  const bytes = readFileSync(container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, seams: true }));
  const out = join(scratch, 'damaged.png');
  const cut = join(scratch, 'cut.limn');
  writeFileSync(cut, bytes.subarray(0, 300));
  let r = run(cut, '-o', out);
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /^limn-web-render: error: .*cut\.limn: header: header says \d+ bytes/);
  // A TBLS count corrupted (the limit-point count, 36 bytes into its payload).
  const chunks = [];
  for (let o = 24; o < bytes.length;) {
    const n = Number(bytes.readBigUInt64LE(o + 8));
    chunks.push({ type: bytes.toString('latin1', o, o + 4), o });
    o += 16 + Math.ceil(n / 8) * 8;
  }
  const tbls = chunks.find((c) => c.type === 'TBLS').o;
  const bad = Buffer.from(bytes);
  bad.writeUInt32LE(0x7fffffff, tbls + 16 + 36);
  writeFileSync(cut, bad);
  r = run(cut, '-o', out);
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /chunk TBLS: /);
  assert.equal(existsSync(out), false);
});

test('what is not supported here exits 3 and says so; maps it cannot use exit 1 naming them', () => {
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 });
  const out = join(scratch, 'x.png');
  // Smooth face-varying UVs (an fvar rule other than "all").
  const smooth = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, classifyArgs: ['--fvar', 'boundaries'], name: 'fvar_boundaries.limn' });
  const r = run(smooth, '-o', out, '--shade', 'uv');
  assert.equal(r.status, 3, r.stderr);
  assert.match(r.stderr, /smooth face-varying UVs .* not supported here/);
  // A map that cannot be read or is not a PNG is named.
  const noMap = run(limn, '-o', out, '--displace', join(scratch, 'absent.png'));
  assert.equal(noMap.status, 1, noMap.stderr);
  assert.match(noMap.stderr, /--displace .*absent\.png: cannot read/);
  const notPng = join(scratch, 'not.png');
  writeFileSync(notPng, 'not a png');
  const bad = run(limn, '-o', out, '--texture', notPng);
  assert.equal(bad.status, 1, bad.stderr);
  assert.match(bad.stderr, /--texture .*not\.png: not a PNG/);
  // A PNG too large for the GPU is refused from its header, before its pixels are decoded.
  const big = join(scratch, 'big.png'), header = encodePng(1, 1, new Uint8Array(4));
  header.writeUInt32BE(20000, 16);
  header.writeUInt32BE(20000, 20);
  writeFileSync(big, header);
  const huge = run(limn, '-o', out, '--displace', big);
  assert.equal(huge.status, 1, huge.stderr);
  assert.match(huge.stderr, /big\.png: a 20000x20000 image, over the 2\^25 texels/);
  const map = join(scratch, 'map.png');
  writeFileSync(map, encodePng(2, 2, new Uint8Array(16).fill(128)));
  // Displacement needs UVs.
  const noUVs = run(container('osd/catmark/catmark_pyramid_creases2.obj', { depth: 1 }), '-o', out, '--displace', map);
  assert.equal(noUVs.status, 1, noUVs.stderr);
  assert.match(noUVs.stderr, /need texture coordinates; the mesh has none/);
  assert.equal(run(limn, '-o', out, '--displace', map, '--displace-scale', 'x%').status, 2);
  assert.equal(existsSync(out), false);
});
