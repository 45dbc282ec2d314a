// Displacement with the seam fix (paper 000, 4.5) on WebGPU: the README's quad_sphere pipeline
// (limn-examples, limn-classify, limn-tables --depth 3, limn-seams, limn-heightmap), displaced
// by limn-web-render's library against limn-render's PNG for the same container, map and options
// (both on the private Mesa 25 lavapipe): at most 0.5% of the covered pixels may differ by more
// than 8/255, on the fixed grids and the view-adaptive tessellation.
// Watertightness: the displaced surface read back and welded by exact position bits is a closed
// surface (every edge in two triangles, Euler characteristic 2 for the sphere) with the seam fix,
// on a map whose two sides of every UV seam differ (limn-heightmap --kind uv); without the fix
// the same check finds the cracks (so it can fail).
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { container, quadSphere as quadSphereInputs, scratch, tool } from './support.mjs';
import { privateIcd, requestNodeDevice } from '../src/node_device.mjs';
import { loadLimn } from '../src/chunks.mjs';
import { Renderer } from '../src/renderer.mjs';
import { computeSeams } from '../src/displacement.mjs';
import { decodePng, encodePng } from '../src/png.mjs';
import { readImageFile, heightMap } from '../src/node_image.mjs';
import { compareImages } from './compare.mjs';

const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd, XDG_RUNTIME_DIR: process.env.XDG_RUNTIME_DIR ?? '/tmp' };
const SCALE = 0.2, MID = 0.5; // Makefile.examples' DISPLACE

let gpu = null;
after(() => gpu?.device.destroy());

let loaded = null;
function quadSphere() {
  loaded ??= { ...quadSphereInputs(), surface: null };
  loaded.surface ??= loadLimn(new Uint8Array(readFileSync(loaded.limn)));
  return loaded;
}

async function webRenderer(settings) {
  gpu ??= await requestNodeDevice();
  const errors = [];
  gpu.device.onuncapturederror = (e) => errors.push(e.error.message);
  const r = await Renderer.create(gpu.device, quadSphere().surface, settings);
  return { r, errors };
}

const displaced = (map, seamFix = true) => ({ map: heightMap(readImageFile(map, '--displace')), scale: SCALE, mid: MID, seamFix });

// Two renders cover lit and levels shading (both use the displaced normals), 4 and 1 samples,
// both tessellations and both wireframes over the displaced surface (--wire: the elements'
// outlines; --wire-triangles): each costs seconds of CPU.
const cases = [['fixed grids, outlines', 0, 4, 'lit', 'outlines'], ['view-adaptive, levels, triangles\' wireframe', 4, 1, 'levels', 'triangles']];
for (const [label, edgePixels, samples, shade, wire] of cases) {
  test(`displaced quad_sphere, seam fix on, ${label}: the image limn-render draws`, async () => {
    const { limn, height } = quadSphere();
    const name = `displaced-${edgePixels}-${samples}-${shade}`;
    const native = join(scratch, `${name}.png`);
    const args = ['--size', '320x240', '--samples', String(samples), '--shade', shade, '--edge-pixels', String(edgePixels),
      '--displace', height, '--displace-scale', String(SCALE), '--displace-mid', String(MID), ...({ outlines: ['--wire'], triangles: ['--wire-triangles'] }[wire] ?? [])];
    execFileSync(tool('limn-render'), ['-q', limn, '-o', native, ...args], { env, stdio: ['ignore', 'ignore', 'pipe'] });
    const s = { width: 320, height: 240, samples, shade, edgePixels, tess: 64, view: {}, displace: displaced(height), wire };
    const { r, errors } = await webRenderer(s);
    r.frame();
    const rgba = await r.pixels();
    r.destroy();
    assert.deepEqual(errors, [], 'WebGPU errors');
    const c = compareImages({ width: 320, height: 240, rgba }, decodePng(readFileSync(native)));
    assert.ok(c.covered > 10000, `${name}: only ${c.covered} covered pixels`);
    assert.ok(c.fraction <= 0.005, `${name}: ${c.off} of ${c.covered} covered pixels differ by more than 8/255 (worst ${c.worst})`);
  });
}

// Welds the drawn vertices by their exact position bits; counts edges not in exactly two triangles.
function closedness({ positions, triangles }) {
  const bits = new Uint32Array(positions.buffer, positions.byteOffset, positions.length);
  const ids = new Map(), id = (i) => {
    const k = `${bits[4 * i]},${bits[4 * i + 1]},${bits[4 * i + 2]}`;
    if (!ids.has(k)) ids.set(k, ids.size);
    return ids.get(k);
  };
  const uses = new Map();
  for (let t = 0; t < triangles.length; t += 3) {
    for (let k = 0; k < 3; k++) {
      const a = id(triangles[t + k]), b = id(triangles[t + ((k + 1) % 3)]);
      const e = a < b ? a * 2 ** 26 + b : b * 2 ** 26 + a;
      uses.set(e, (uses.get(e) ?? 0) + 1);
    }
  }
  let open = 0;
  for (const n of uses.values()) if (n !== 2) open++;
  return { open, euler: ids.size - uses.size + triangles.length / 3 };
}

test('displaced quad_sphere: watertight with the seam fix (fixed grids and view-adaptive), cracked without', async () => {
  const { noise } = quadSphere();
  for (const edgePixels of [0, 4]) {
    for (const seamFix of edgePixels ? [true] : [true, false]) {
      const s = { width: 320, height: 240, samples: 1, shade: 'lit', edgePixels, tess: 64, view: {}, displace: displaced(noise, seamFix) };
      const { r, errors } = await webRenderer(s);
      const c = closedness(await r.drawnMesh());
      r.destroy();
      assert.deepEqual(errors, [], 'WebGPU errors');
      const what = `edge pixels ${edgePixels}, seam fix ${seamFix ? 'on' : 'off'}`;
      if (seamFix) {
        assert.equal(c.open, 0, `${what}: ${c.open} edges are not shared by two triangles (cracks)`);
        assert.equal(c.euler, 2, `${what}: V - E + F = ${c.euler}, not a sphere's 2`);
      } else {
        assert.ok(c.open > 100, `${what}: the UV-noise map should open the seams, found ${c.open} open edges`);
      }
    }
  }
});

// Smooth face-varying UVs (spot, corners-plus1, from the FVSF chunk) on the fixed grids, displaced
// by a checkerboard (8-texel squares: steps show where the UVs land; linear UVs put 2% of the
// covered pixels off here): limn-render's image; the seam fix averages every face's smooth UV
// around a point (ChartUVs sides), so the surface is closed with it and cracked without. The
// view-adaptive tessellation takes the smooth UVs' seam records and is closed too.
test('displaced spot with smooth UVs: limn-render\'s image, watertight with the seam fix (both tessellations)', async () => {
  const limn = container('quad/spot_quadrangulated.obj', { depth: 2, classifyArgs: ['--fvar', 'corners-plus1'], name: 'spot_smooth_uvs_d2.limn' });
  const checker = join(scratch, 'checker-height.png'), n = 256, px = new Uint8Array(n * n * 4);
  for (let y = 0; y < n; y++) for (let x = 0; x < n; x++) { const c = ((x >> 3) ^ (y >> 3)) & 1 ? 230 : 25; px.set([c, c, c, 255], 4 * (y * n + x)); }
  writeFileSync(checker, encodePng(n, n, px));
  const surface = loadLimn(new Uint8Array(readFileSync(limn)));
  assert.ok(surface.fvarSurface, 'limn-tables wrote the FVSF chunk');
  const P = surface.mesh.positions, lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < P.length; i++) { lo[i % 3] = Math.min(lo[i % 3], P[i]); hi[i % 3] = Math.max(hi[i % 3], P[i]); }
  const scale = 0.02 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]); // --displace-scale 2%
  gpu ??= await requestNodeDevice();
  const errors = [];
  gpu.device.onuncapturederror = (e) => errors.push(e.error.message);
  for (const [edgePixels, seamFix] of [[0, true], [0, false], [4, true]]) {
    const displace = { map: heightMap(readImageFile(checker, '--displace')), scale, mid: 0, seamFix };
    const r = await Renderer.create(gpu.device, surface, { width: 320, height: 240, samples: 1, shade: 'lit', edgePixels, tess: 64, view: {}, displace });
    const c = closedness(await r.drawnMesh());
    if (seamFix) {
      // View-adaptive: the smooth UVs' seam records (smoothSeamRecords) weld every seam.
      assert.equal(c.open, 0, `edge pixels ${edgePixels}: ${c.open} edges are not shared by two triangles (cracks)`);
      r.frame();
      const rgba = await r.pixels();
      const native = join(scratch, `displaced-smooth-${edgePixels}.png`);
      execFileSync(tool('limn-render'), ['-q', limn, '-o', native, '--size', '320x240', '--samples', '1', '--edge-pixels', String(edgePixels),
        '--displace', checker, '--displace-scale', '2%'], { env, stdio: ['ignore', 'ignore', 'pipe'] });
      const d = compareImages({ width: 320, height: 240, rgba }, decodePng(readFileSync(native)));
      assert.ok(d.covered > 10000 && d.fraction <= 0.005, `edge pixels ${edgePixels}: ${d.off} of ${d.covered} covered pixels differ by more than 8/255 (worst ${d.worst})`);
    } else {
      assert.ok(c.open > 100, `seam fix off: the checkerboard should open the seams, found ${c.open} open edges`);
    }
    r.destroy();
  }
  assert.deepEqual(errors, [], 'WebGPU errors');
});

// Holes with smooth UVs: a hole has no UV surface (its FVSF root is empty) and is not drawn, so
// the seam fix samples only the drawn faces around a point (smooth_uvs.mjs locate), as
// limn-render does. Both threw "no face-varying element contains ptex face 6" on this valid mesh.
test('displaced holes with smooth UVs: limn-render\'s image (both tessellations)', async () => {
  const limn = container('osd/catmark/catmark_hole_test2.obj', { depth: 2, classifyArgs: ['--fvar', 'boundaries'], name: 'holes_smooth_uvs_d2.limn' });
  const surface = loadLimn(new Uint8Array(readFileSync(limn)));
  assert.ok(surface.fvarSurface && surface.fvarSurface.nodes.some((v) => v === 0xffffffff), 'FVSF with hole roots');
  const { height } = quadSphere();
  gpu ??= await requestNodeDevice();
  const errors = [];
  gpu.device.onuncapturederror = (e) => errors.push(e.error.message);
  for (const edgePixels of [0, 4]) {
    const displace = { map: heightMap(readImageFile(height, '--displace')), scale: 0.05, mid: 0, seamFix: true };
    const r = await Renderer.create(gpu.device, surface, { width: 160, height: 120, samples: 1, shade: 'lit', edgePixels, tess: 64, view: {}, displace });
    r.frame();
    const rgba = await r.pixels();
    r.destroy();
    const native = join(scratch, `displaced-holes-${edgePixels}.png`);
    execFileSync(tool('limn-render'), ['-q', limn, '-o', native, '--size', '160x120', '--samples', '1', '--edge-pixels', String(edgePixels),
      '--displace', height, '--displace-scale', '0.05'], { env, stdio: ['ignore', 'ignore', 'pipe'] });
    const d = compareImages({ width: 160, height: 120, rgba }, decodePng(readFileSync(native)));
    assert.ok(d.covered > 1000 && d.fraction <= 0.005, `edge pixels ${edgePixels}: ${d.off} of ${d.covered} covered pixels differ by more than 8/255 (worst ${d.worst})`);
  }
  assert.deepEqual(errors, [], 'WebGPU errors');
});

// Without a SEAM chunk the renderer computes the seam records itself, as limn-render does: they
// are limn-seams' own, bit for bit (the chunk written by limn-seams is the reference).
test('seam records computed without a SEAM chunk are the ones limn-seams writes', () => {
  const { surface } = quadSphere();
  const c = computeSeams(surface.mesh, surface.uvs, surface.tables);
  assert.equal(c.uvCount, surface.seams.uvCount);
  assert.deepEqual(new Uint32Array(c.records.buffer, c.records.byteOffset, c.records.length), surface.seams.records);
  assert.deepEqual(new Uint32Array(c.uvs.buffer), new Uint32Array(surface.seams.uvs.buffer, surface.seams.uvs.byteOffset, surface.seams.uvs.length));
});

// A cone whose apex has its own UV in each of its n faces (messages_cli_test.cpp's
// coneWithSeamAtApex): each element at the apex carries all n UVs. n = 1,000: the records equal
// limn-seams'; n = 4,097 (past the readers' 4,096 at a point): refused at once, as limn-seams does
// (the search it replaced cost n^2 per element).
test('seam records of a vertex with a UV seam between each two faces: limn-seams\' records, refused past 4,096 UVs', () => {
  const cone = (n) => {
    const lines = ['v 0 0 1'];
    for (let ring = 1; ring <= 2; ring++) {
      for (let i = 0; i < n; i++) {
        const a = 2 * Math.PI * (i + 0.5 * (ring - 1)) / n;
        lines.push(`v ${ring * Math.cos(a)} ${ring * Math.sin(a)} 0`);
      }
    }
    for (let ring = 0; ring <= 2; ring++) {
      for (let i = 0; i < n; i++) {
        const a = 2 * Math.PI * (i + 0.5) / n, r = 0.05 + 0.15 * ring;
        lines.push(`vt ${0.5 + r * Math.cos(a)} ${0.5 + r * Math.sin(a)}`);
      }
    }
    for (let i = 0; i < n; i++) {
      const j = (i + 1) % n;
      lines.push(`f 1/${1 + i} ${2 + i}/${1 + n + i} ${2 + n + i}/${1 + 2 * n + i} ${2 + j}/${1 + n + j}`);
    }
    return lines.join('\n') + '\n';
  };
  for (const n of [1000, 4097]) {
    const obj = join(scratch, `cone${n}.obj`), tables = join(scratch, `cone${n}.limn`);
    writeFileSync(obj, cone(n));
    execFileSync(tool('limn-classify'), ['-q', obj, '-o', join(scratch, `cone${n}_c.limn`)]);
    execFileSync(tool('limn-tables'), ['-q', '--depth', '1', join(scratch, `cone${n}_c.limn`), '-o', tables]);
    const surface = loadLimn(new Uint8Array(readFileSync(tables)));
    if (n === 4097) {
      assert.throws(() => computeSeams(surface.mesh, surface.uvs, surface.tables), /a vertex has 4097 different UVs in the faces around it/);
      continue;
    }
    const seams = join(scratch, `cone${n}_s.limn`);
    execFileSync(tool('limn-seams'), ['-q', tables, '-o', seams]);
    const ref = loadLimn(new Uint8Array(readFileSync(seams))).seams;
    const c = computeSeams(surface.mesh, surface.uvs, surface.tables);
    assert.equal(c.uvCount, ref.uvCount);
    assert.deepEqual(c.records, ref.records);
    assert.deepEqual(new Uint32Array(c.uvs.buffer), new Uint32Array(ref.uvs.buffer, ref.uvs.byteOffset, ref.uvs.length));
  }
});
