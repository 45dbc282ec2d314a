// Test helpers: limn's own tools from the build (LIMN_BUILD_DIR, default build/ at the repository
// root) make the containers; tests fail, naming what is missing, when they are not built.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';

export const repo = fileURLToPath(new URL('../../', import.meta.url));
export const buildDir = process.env.LIMN_BUILD_DIR ?? join(repo, 'build');
export const scratch = join(tmpdir(), `limn-web-test-${process.pid}`);
mkdirSync(scratch, { recursive: true });
process.on('exit', () => rmSync(scratch, { recursive: true, force: true }));

export function tool(name) {
  const p = join(buildDir, 'bin', name);
  if (!existsSync(p)) throw new Error(`${p} is missing: build limn first (scripts/build.sh release)`);
  return p;
}

/** Runs limn-classify | limn-tables | [limn-seams] on a mesh of tests/data; returns the path. */
export function container(mesh, { depth = 2, seams = false, tablesArgs = [], classifyArgs = [], name } = {}) {
  const out = join(scratch, name ?? `${mesh.replace(/[/.]/g, '_')}_d${depth}${seams ? '_s' : ''}.limn`);
  if (existsSync(out)) return out;
  const src = mesh.startsWith('/') ? mesh : join(repo, 'tests/data', mesh);
  let bytes = execFileSync(tool('limn-classify'), [...classifyArgs, src, '-o', '-'], { maxBuffer: 1 << 30 });
  bytes = execFileSync(tool('limn-tables'), ['--depth', String(depth), ...tablesArgs, '-', '-o', '-'], { input: bytes, maxBuffer: 1 << 30 });
  if (seams) bytes = execFileSync(tool('limn-seams'), ['-', '-o', '-'], { input: bytes, maxBuffer: 1 << 30 });
  writeFileSync(out, bytes);
  return out;
}

export const read = (p) => new Uint8Array(readFileSync(p));

/**
 * The README's displacement example (Makefile.examples): quad_sphere from limn-examples, with
 * tables at depth 3 and seams, its surface height map (continuous across UV seams) and the UV
 * noise map (different texels on the two sides of every seam), 256 texels square. Made once.
 */
export function quadSphere() {
  const limn = join(scratch, 'quad_sphere_d3_s.limn');
  const height = join(scratch, 'quad_sphere.height.png'), noise = join(scratch, 'uv-noise.png');
  if (existsSync(noise)) return { limn, height, noise };
  execFileSync(tool('limn-examples'), ['-q', '-o', scratch, '--only', 'quad_sphere']);
  container(join(scratch, 'quad_sphere.obj'), { depth: 3, seams: true, name: 'quad_sphere_d3_s.limn' });
  execFileSync(tool('limn-heightmap'), ['-q', '--kind', 'surface', '--size', '256', limn, '-o', height]);
  execFileSync(tool('limn-heightmap'), ['-q', '--kind', 'uv', '--size', '256', '-o', noise]);
  return { limn, height, noise };
}

// The paper's demo sphere (tests/support/paper_sphere.h): 16 segments x 16 rings, fans at the poles.
export function paperSphereObj() {
  const S = 16, R = 16, v = ['v 0 1 0'], f = [];
  for (let i = 1; i < R; i++) {
    for (let j = 0; j < S; j++) {
      const th = (Math.PI * i) / R, ph = (2 * Math.PI * j) / S;
      v.push(`v ${Math.sin(th) * Math.cos(ph)} ${Math.cos(th)} ${-Math.sin(th) * Math.sin(ph)}`);
    }
  }
  v.push('v 0 -1 0');
  const idx = (i, j) => 1 + (i - 1) * S + (j % S) + 1; // OBJ is 1-based
  for (let j = 0; j < S; j++) f.push(`f 1 ${idx(1, j)} ${idx(1, j + 1)}`);
  for (let i = 1; i + 1 < R; i++) for (let j = 0; j < S; j++) f.push(`f ${idx(i, j)} ${idx(i + 1, j)} ${idx(i + 1, j + 1)} ${idx(i, j + 1)}`);
  for (let j = 0; j < S; j++) f.push(`f ${idx(R - 1, j)} ${v.length} ${idx(R - 1, j + 1)}`);
  const path = join(scratch, 'paper_sphere.obj');
  writeFileSync(path, `${v.join('\n')}\n${f.join('\n')}\n`);
  return path;
}

// A container of `chunks` ({type, version, payload}), each padded to 8 bytes.
export function build(chunks) {
  const size = 24 + chunks.reduce((n, c) => n + 16 + Math.ceil(c.payload.length / 8) * 8, 0);
  const out = new Uint8Array(size);
  const view = new DataView(out.buffer);
  out.set([0x4c, 0x49, 0x4d, 0x4e, 0x0d, 0x0a, 0x1a, 0x0a]);
  view.setUint32(8, 1, true);
  view.setBigUint64(16, BigInt(size), true);
  let o = 24;
  for (const c of chunks) {
    out.set([...c.type].map((ch) => ch.charCodeAt(0)), o);
    view.setUint32(o + 4, c.version, true);
    view.setBigUint64(o + 8, BigInt(c.payload.length), true);
    out.set(c.payload, o + 16);
    o += 16 + Math.ceil(c.payload.length / 8) * 8;
  }
  return out;
}

// Where TBLS v6's irregular-surface section starts (formats/limn.md): after the header, levels,
// the repeated levels' bits, the stencil tables of the others (their palettes and streams), the
// patch stream and the irregular faces, walked over the payload's own length fields. Version 9
// (`version`): the levels a stream, no table of no rows.
export function irregularSectionOffset(t, payload, version = 6) {
  const v = new DataView(payload.buffer, payload.byteOffset, payload.byteLength);
  const stream = (o) => o + 4 + Math.ceil(v.getUint32(o, true) / 4) * 4;
  let o = version >= 9 ? stream(40) : 40 + 24 * t.levels.length;
  const repeats = v.getUint32(o, true);
  o += 4;
  for (let l = 1; l < t.levels.length; l++) {
    if ((repeats >>> l) & 1) continue;
    const L = t.levels[l], rows = [L.facePoints, L.edgePoints, L.vertexPoints];
    for (let k = 0; k < 3; k++) if (version < 9 || rows[k] > 0) o = stream(o + 16 + 4 * v.getUint32(o + 12, true));
  }
  return { at: stream(o) + 32 * t.irregularCount, stream };
}
