// limn-web-render's command line: exit codes (1 bad input, 2 usage, 3 capability), errors in
// limn's format naming the file and chunk, no output file left behind, no hang (timeouts).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, scratch, repo, tool } from './support.mjs';
import { encodePng } from '../src/png.mjs';
import { privateIcd } from '../src/node_device.mjs';
import { parseContainer } from '../src/container.mjs';

// A container of `chunks` (parseContainer's), framed as formats/limn.md section 2-3 says.
function writeContainer(chunks) {
  const size = 24 + chunks.reduce((n, c) => n + 16 + Math.ceil(c.payload.length / 8) * 8, 0);
  const out = Buffer.alloc(size);
  out.set([0x4c, 0x49, 0x4d, 0x4e, 0x0d, 0x0a, 0x1a, 0x0a]);
  out.writeUInt32LE(1, 8);
  out.writeBigUInt64LE(BigInt(size), 16);
  let o = 24;
  for (const c of chunks) {
    out.write(c.type, o, 'latin1');
    out.writeUInt32LE(c.version, o + 4);
    out.writeBigUInt64LE(BigInt(c.payload.length), o + 8);
    out.set(c.payload, o + 16);
    o += 16 + Math.ceil(c.payload.length / 8) * 8;
  }
  return out;
}

const cli = join(repo, 'web/bin/limn-web-render.mjs');
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });

test('usage errors exit 2', () => {
  for (const args of [['--frobnicate'], ['-o', '-', '--bench', '1', 'x.limn'], ['--', '-', '--size', '8x8'], ['x.limn', '-o', 'a.png', '--output', 'b.png'], ['x.limn', '-o', 'y.png', '--samples', '3'], ['x.limn', '-o', 'y.jpg'], ['x.limn', '-o', 'y.png', '--wire', '--wire-triangles']]) {
    const r = run(...args);
    assert.equal(r.status, 2, `${args.join(' ')}: ${r.stderr}`);
    assert.match(r.stderr, /^limn-web-render: error: /);
  }
  assert.equal(run('--help').status, 0);
});

// --max-error's and --interior-error's refusals are limn-render's: the same exit code and message.
test('--max-error, --interior-error: limn-render\'s range, exit code and message', () => {
  const refused = ['-1', '5000', 'abc', '', '+1', ' 1', '0x10', 'inf', '1e400', '1e-400'];
  for (const args of ['--max-error', '--interior-error'].flatMap((o) => [...refused.map((v) => [o, v]), [o, '1', o, '2']])) {
    const native = spawnSync(tool('limn-render'), [...args, 'x.limn', '-o', join(scratch, 'ie.png')], { encoding: 'utf8', timeout: 60000 });
    const r = run(...args, 'x.limn', '-o', join(scratch, 'ie.png'));
    assert.equal(r.status, native.status, `${args.join(' ')}: ${r.stderr}`);
    assert.equal(r.status, 2);
    assert.equal(r.stderr.replace(/^limn-web-render: /, ''), native.stderr.replace(/^limn-render: /, ''));
  }
  assert.equal(existsSync(join(scratch, 'ie.png')), false);
});

test('-q silences limn\'s warnings, as limn-render -q does', () => {
  const input = container('quad/osd_catmark_fvar_bound1.obj', { depth: 1 });
  const out = join(scratch, 'quiet.png');
  const loud = run(input, '--size', '16x12', '--displace-scale', '2', '-o', out);
  assert.equal(loud.status, 0, loud.stderr);
  assert.match(loud.stderr, /limn-web-render: warning: --displace-scale/);
  const quiet = run(input, '--size', '16x12', '--displace-scale', '2', '-q', '-o', out);
  assert.equal(quiet.status, 0, quiet.stderr);
  assert.doesNotMatch(quiet.stderr, /limn-web-render: warning/);
  rmSync(out, { force: true });
});

test('damaged containers exit 1 naming the chunk, and leave no output', () => {
  const bytes = readFileSync(container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, seams: true }));
  const out = join(scratch, 'damaged.png');
  const cut = join(scratch, 'cut.limn');
  writeFileSync(cut, bytes.subarray(0, 300));
  let r = run(cut, '-o', out);
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /^limn-web-render: error: .*cut\.limn: header: header says \d+ bytes/);
  // The input named as parsed, not as the first argument without a dash (an option's value:
  // the message said "64x48: header: ..."), and a missing input named too.
  r = run('--size', '64x48', cut, '-o', out);
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /^limn-web-render: error: \S*cut\.limn: header: /);
  r = run(join(scratch, 'absent.limn'), '-o', out);
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /^limn-web-render: error: \S*absent\.limn: cannot open: No such file or directory$/m);
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
  // Smooth UVs (an fvar rule other than "all") without their surface (the FVSF chunk removed, as
  // from an older limn-tables).
  const smooth = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, classifyArgs: ['--fvar', 'boundaries'], name: 'fvar_boundaries.limn' });
  const chunks = parseContainer(readFileSync(smooth)), kept = chunks.filter((c) => c.type !== 'FVSF');
  assert.equal(kept.length, chunks.length - 1);
  const older = join(scratch, 'no_fvsf.limn');
  writeFileSync(older, writeContainer(kept));
  const noSurface = run(older, '-o', out, '--shade', 'uv');
  assert.equal(noSurface.status, 1, noSurface.stderr);
  assert.match(noSurface.stderr, /need their surface, the FVSF chunk, which this container lacks; re-run limn-tables/);
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

// --mesh-out against limn-render's on the same driver: the same bytes. The view-adaptive case has
// irregular faces drawn bilinear (--irregular-levels 0: the `approximate` property), is displaced
// by a checkerboard (no sample test without the cull, as limn-render) and writes the image too;
// the fixed-grid case has texture coordinates (s t) and is ASCII (every float as the shortest
// text, as C++'s to_chars writes it).
test('--mesh-out writes the bytes limn-render --mesh-out writes', () => {
  const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd };
  const checker = join(scratch, 'checker.png'), n = 256, px = new Uint8Array(n * n * 4);
  for (let y = 0; y < n; y++) for (let x = 0; x < n; x++) { const c = ((x >> 3) ^ (y >> 3)) & 1 ? 230 : 25; px.set([c, c, c, 255], 4 * (y * n + x)); }
  writeFileSync(checker, encodePng(n, n, px));
  const cases = [
    // --interior-error's coarser interior; --pixel-normals draws as without under --mesh-out.
    [container('quad/spot_quadrangulated.obj', { depth: 3 }), 'mesh_interior.ply', ['--size', '320x240', '--pixel-normals', '--interior-error', '1']],
    [container('quad/spot_quadrangulated.obj', { depth: 2, tablesArgs: ['--irregular-levels', '0'], name: 'spot_bilinear.limn' }), 'mesh_adaptive.ply',
      ['--size', '320x240', '--edge-pixels', '4', '--displace', checker, '--displace-scale', '2%']],
    [container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 }), 'mesh_fixed.ply', ['--size', '64x64', '--edge-pixels', '0', '--mesh-ascii']],
  ];
  for (const [limn, name, args] of cases) {
    const native = join(scratch, `native_${name}`), web = join(scratch, `web_${name}`), png = join(scratch, `${name}.png`);
    execFileSync(tool('limn-render'), [limn, '--mesh-out', native, ...args], { env, stdio: 'ignore' });
    const r = spawnSync(process.execPath, [cli, limn, '--mesh-out', web, ...args, ...(args.includes('--mesh-ascii') ? [] : ['-o', png])], { encoding: 'utf8', timeout: 120000, env });
    assert.equal(r.status, 0, r.stderr);
    const want = readFileSync(native), got = readFileSync(web);
    assert.equal(got.length, want.length, `${name}: ${got.length} bytes, limn-render wrote ${want.length}`);
    assert.ok(got.equals(want), `${name}: the bytes differ from limn-render's`);
    assert.equal(existsSync(png), !args.includes('--mesh-ascii'));
  }
  assert.match(readFileSync(join(scratch, 'web_mesh_adaptive.ply')).toString('latin1', 0, 600), /property uchar approximate\n/);
  assert.match(readFileSync(join(scratch, 'web_mesh_fixed.ply')).toString('latin1', 0, 600), /format ascii 1\.0\n(.|\n)*property float s\n/);
});

// Smooth faces below level N (TBLS version 5: quadtree nodes naming per-valence basis faces
// where a semi-sharp crease has decayed, and below faces with two extraordinary corners), and
// faces around boundary vertices on their configurations' bases (TBLS version 7: cube_no_bottom's
// open bottom), and decaying-crease chains (TBLS version 8: chaikin0's faces along its creases,
// single-crease bands, smooth and regular ends): the web reader, its GPU records and the WGSL
// walk draw limn-render's bytes.
test('--mesh-out on smooth faces below level N, boundary bases and crease chains writes limn-render\'s bytes', () => {
  const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd };
  for (const [model, name, tablesArgs] of [['osd/catmark/catmark_pyramid_creases0.obj', 'nested'], ['tri/cube_no_bottom.obj', 'boundary'],
    ['osd/catmark/catmark_chaikin0.obj', 'chains', ['--crease-chains', 'on']]]) {
    const limn = container(model, tablesArgs ? { depth: 2, tablesArgs, name: `${name}.limn` } : { depth: 2 });
    const native = join(scratch, `${name}_native.ply`), web = join(scratch, `${name}_web.ply`);
    const args = ['--size', '160x120', '--mesh-out'];
    execFileSync(tool('limn-render'), [limn, ...args, native, '-o', join(scratch, `${name}_native.png`)], { env, stdio: 'ignore' });
    const r = spawnSync(process.execPath, [cli, limn, ...args, web, '-o', join(scratch, `${name}_web.png`)], { encoding: 'utf8', timeout: 120000, env });
    assert.equal(r.status, 0, r.stderr);
    assert.ok(readFileSync(web).equals(readFileSync(native)), `${name}: the bytes differ from limn-render's`);
  }
});

// A binary --mesh-out PLY's vertices (11 floats: x y z nx ny nz, ptex bits, u v s t) and triangles.
function readDrawnPly(bytes) {
  const end = bytes.indexOf('end_header\n') + 'end_header\n'.length, header = bytes.toString('latin1', 0, end);
  const V = Number(/element vertex (\d+)/.exec(header)[1]), F = Number(/element face (\d+)/.exec(header)[1]);
  const stride = 44 + (header.includes('approximate') ? 1 : 0);
  const vertices = Array.from({ length: V }, (_, i) => Array.from({ length: 11 }, (__, k) => bytes.readFloatLE(end + stride * i + 4 * k)));
  const triangles = Array.from({ length: 3 * F }, (_, k) => bytes.readUInt32LE(end + stride * V + 13 * Math.floor(k / 3) + 1 + 4 * (k % 3)));
  return { vertices, triangles };
}

// Smooth face-varying UVs from the FVSF chunk. View-adaptive: the emit pass evaluates them on the
// GPU from the same records in both, the same bytes. Fixed grids: limn-render evaluates them on
// the CPU from the UV surface's double-precision points, the web from the chunk's floats, so a
// UV may differ in its last float bit (and a seam copy appear where the two faces' bits differ):
// the same triangles, each corner at the same position and texture UV within 1e-6.
test('--mesh-out with smooth UVs: limn-render\'s bytes (view-adaptive), its triangles and UVs (fixed grids)', () => {
  const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd };
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2, classifyArgs: ['--fvar', 'boundaries'], name: 'fvar_boundaries.limn' });
  for (const edgePixels of ['4', '0']) {
    const native = join(scratch, `smooth_native_${edgePixels}.ply`), web = join(scratch, `smooth_web_${edgePixels}.ply`);
    const args = ['--size', '160x120', '--edge-pixels', edgePixels, '--samples', '1'];
    execFileSync(tool('limn-render'), [limn, '--mesh-out', native, ...args], { env, stdio: 'ignore' });
    const r = spawnSync(process.execPath, [cli, limn, '--mesh-out', web, ...args], { encoding: 'utf8', timeout: 120000, env });
    assert.equal(r.status, 0, r.stderr);
    const want = readFileSync(native), got = readFileSync(web);
    if (edgePixels !== '0') {
      assert.ok(got.equals(want), 'view-adaptive: the bytes differ from limn-render\'s');
      continue;
    }
    const a = readDrawnPly(want), b = readDrawnPly(got);
    assert.equal(b.triangles.length, a.triangles.length, 'triangle count');
    let worst = 0;
    for (let k = 0; k < a.triangles.length; k++) {
      const p = a.vertices[a.triangles[k]], q = b.vertices[b.triangles[k]];
      for (const c of [0, 1, 2, 9, 10]) worst = Math.max(worst, Math.abs(p[c] - q[c]));
    }
    assert.ok(worst <= 1e-6, `fixed grids: a corner's position or texture UV is ${worst} away`);
  }
  // Spot's UV mesh has 302 faces with a per-valence basis at depth 2, which FVSF stores as smooth
  // faces: fvar_chunk.mjs expands them into the records limn-render draws, to the same bits.
  const spot = container('quad/spot_quadrangulated.obj', { depth: 2, classifyArgs: ['--fvar', 'corners-plus1'], name: 'spot_smooth_uvs_d2.limn' });
  const native = join(scratch, 'smooth_spot_native.ply'), web = join(scratch, 'smooth_spot_web.ply');
  const args = ['--size', '64x48', '--samples', '1'];
  execFileSync(tool('limn-render'), [spot, '--mesh-out', native, ...args], { env, stdio: 'ignore' });
  const r = spawnSync(process.execPath, [cli, spot, '--mesh-out', web, ...args], { encoding: 'utf8', timeout: 120000, env });
  assert.equal(r.status, 0, r.stderr);
  assert.ok(readFileSync(web).equals(readFileSync(native)), 'view-adaptive smooth faces: the bytes differ from limn-render\'s');
});

test('--mesh-out: a bad extension exits 2, a format not written here exits 3, and no file is left', () => {
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 });
  const before = readdirSync(scratch).length;
  for (const [args, status, message] of [
    [['--mesh-out', join(scratch, 'm.stl')], 2, /unknown extension; limn-render writes \.ply, \.obj, \.gltf, \.glb/],
    [['--mesh-out', join(scratch, 'noext')], 2, /unknown extension/],
    [['--mesh-out', join(scratch, 'm.obj')], 3, /writes PLY only/],
    [['-o', join(scratch, 'm.exr')], 3, /writes PNG only \(name it \.png\); limn-render writes \.exr/],
    [['-o', join(scratch, 'm.png'), '--mesh-ascii'], 2, /--mesh-ascii applies to a \.ply --mesh-out/],
    [['--mesh-out', '-', '--bench', '1'], 2, /cannot share standard output/],
  ]) {
    const r = run(limn, ...args);
    assert.equal(r.status, status, `${args.join(' ')}: ${r.stderr}`);
    assert.match(r.stderr, message);
  }
  // The extension is case-insensitive, as limn-render's: X.PNG is a PNG (it was a usage error).
  const upper = run(limn, '--size', '32x32', '-o', join(scratch, 'UPPER.PNG'));
  assert.equal(upper.status, 0, upper.stderr);
  assert.ok(existsSync(join(scratch, 'UPPER.PNG')));
  rmSync(join(scratch, 'UPPER.PNG'));
  // A directory that does not exist: exit 1 naming the file, no temporary file left beside it.
  // With -o too: the PNG was written before the PLY failed; now neither is (limn-render's way).
  let r = run(limn, '--size', '32x32', '-o', join(scratch, 'both.png'), '--mesh-out', join(scratch, 'absent', 'm.ply'));
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /absent\/m\.ply: cannot create output: No such file or directory/);
  assert.equal(readdirSync(scratch).length, before);
  // A directory under the PLY's name: refused before the render, no PNG either.
  mkdirSync(join(scratch, 'dir.ply'));
  r = run(limn, '--size', '32x32', '-o', join(scratch, 'both.png'), '--mesh-out', join(scratch, 'dir.ply'));
  assert.equal(r.status, 1, r.stderr);
  assert.match(r.stderr, /dir\.ply: is a directory, not a file/);
  rmSync(join(scratch, 'dir.ply'), { recursive: true });
  assert.equal(readdirSync(scratch).length, before);
});

test('--bench prints limn-render\'s JSON fields: GPU ms from timestamps, the host\'s frame, the JS of it', () => {
  const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd };
  const args = [container('quad/spot_quadrangulated.obj', { depth: 1 }), '--size', '64x48', '--samples', '1', '--bench', '2'];
  const native = JSON.parse(execFileSync(tool('limn-render'), args, { env, stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  const r = spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000, env });
  assert.equal(r.status, 0, r.stderr);
  const web = JSON.parse(r.stdout);
  for (const k of Object.keys(native)) assert.ok(k in web, `limn-render's field ${k} is missing: ${r.stdout}`);
  assert.deepEqual(Object.keys(web.gpu_ms), Object.keys(native.gpu_ms));
  assert.equal(web.frames, 2);
  assert.equal(web.triangles, native.triangles);
  // The adapter has timestamp queries (Mesa 25 lavapipe): the GPU total is measured, not null.
  assert.ok(web.gpu_ms.total > 0 && web.gpu_ms.total < web.cpu_ms + 1, r.stdout);
  assert.ok(web.js_ms > 0 && web.js_ms <= web.cpu_ms, r.stdout);
});
