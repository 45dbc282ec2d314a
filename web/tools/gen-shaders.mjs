#!/usr/bin/env node
// Generates web/shaders/*.wgsl from limn's GLSL shaders, so that limn-render (Vulkan) and the
// WebGPU runtime run the same shader code: the GLSL under lib/**/shaders is the one source a person
// edits; the WGSL is mechanical output and is committed so that the package needs no compiler.
//
//   GLSL --glslangValidator -V --target-env vulkan1.1--> SPIR-V --naga (npm naga-wasm)--> WGSL
//
// (vulkan1.2 output uses OpCopyLogical, which naga does not parse.) naga's WGSL needs four
// mechanical fixes, each made from facts read out of the SPIR-V, never guessed from names:
//   0. naga's SPIR-V reader negates gl_Position.y (it assumes Vulkan's y-down clip space); limn's
//      clip space is already WebGPU's, y up (lib/gpu flips the Vulkan viewport instead), so the
//      negation in each vertex entry point is taken out again;
//   1. storage buffers declared `readonly` come out `read_write`, which WebGPU refuses in the vertex
//      and fragment stages: a buffer whose SPIR-V block is NonWritable becomes `var<storage, read>`;
//   2. push constants become `var<immediate>` (Dawn allows 64 bytes; limn pushes up to 128): they
//      become a uniform buffer at @group(PUSH_GROUP) @binding(0), which the host fills per pass;
//   3. `@interpolate(flat)` becomes `@interpolate(flat, either)`: the only form WebGPU's
//      compatibility mode (Dawn on OpenGL ES) accepts, and valid in core, where limn's flat values
//      are the same at every vertex of a primitive anyway;
//   4. naga drops SPIR-V's `Sample` decoration (GLSL `sample in`, the per-sample shading of
//      --sample-shading): each fragment input that had it gets `@interpolate(perspective, sample)`.
//      WebGPU (unlike Vulkan) wants the vertex output to say the same, so each vertex shader with
//      smooth outputs also gets a variant, NAME_per_sample.vert, whose smooth outputs say it.
//
// Usage: node web/tools/gen-shaders.mjs [--check]
//   writes web/shaders/ (and removes .wgsl files no shader generates); with --check writes nothing
//   and exits 1 when a committed file differs from what would be generated (the freshness test).
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync, existsSync, mkdirSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, relative, dirname, basename } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseSpirv, validate, writeWgsl } from 'naga-wasm';

export const PUSH_GROUP = 3; // limn's shaders use descriptor sets 0..1; WebGPU allows groups 0..3

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const outDir = join(root, 'web', 'shaders');
const stages = new Set(['.comp', '.vert', '.frag']);

// Every folder named `shaders` under lib/, at any depth: the shaders may move between libraries.
function shaderDirs(dir, found = []) {
  for (const e of readdirSync(dir, { withFileTypes: true }).sort((a, b) => (a.name < b.name ? -1 : 1))) {
    if (!e.isDirectory()) continue;
    const p = join(dir, e.name);
    if (e.name === 'shaders') found.push(p);
    shaderDirs(p, found);
  }
  return found;
}

export function findShaders() {
  const dirs = shaderDirs(join(root, 'lib'));
  const shaders = [];
  const seen = new Map();
  for (const d of dirs) {
    for (const f of readdirSync(d).sort()) {
      const ext = f.slice(f.lastIndexOf('.'));
      if (!stages.has(ext)) continue;
      const path = join(d, f);
      if (seen.has(f)) throw new Error(`two shaders named ${f}: ${seen.get(f)} and ${relative(root, path)}`);
      seen.set(f, relative(root, path));
      shaders.push({ name: f, path, dir: d });
    }
  }
  return { shaders, dirs };
}

// --- SPIR-V facts naga loses -------------------------------------------------------------------
const Op = { TypeStruct: 30, TypePointer: 32, Variable: 59, Decorate: 71, MemberDecorate: 72 };
const Dec = { Sample: 17, NonWritable: 24, Location: 30, Binding: 33, DescriptorSet: 34 };
const StorageClass = { Input: 1, Uniform: 2, StorageBuffer: 12 };

export function spirvFacts(words) {
  if (words[0] !== 0x07230203) throw new Error('not a SPIR-V module');
  const decor = new Map(); // id -> Map(decoration -> literal)
  const memberNonWritable = new Map(); // struct id -> count of NonWritable members
  const memberCount = new Map();
  const pointee = new Map(); // pointer type id -> pointee id
  const vars = []; // {id, type, storage}
  for (let i = 5; i < words.length;) {
    const count = words[i] >>> 16, op = words[i] & 0xffff;
    if (count === 0) throw new Error('malformed SPIR-V');
    if (op === Op.Decorate) {
      const m = decor.get(words[i + 1]) ?? new Map();
      m.set(words[i + 2], words[i + 3]);
      decor.set(words[i + 1], m);
    } else if (op === Op.MemberDecorate && words[i + 3] === Dec.NonWritable) {
      memberNonWritable.set(words[i + 1], (memberNonWritable.get(words[i + 1]) ?? 0) + 1);
    } else if (op === Op.TypeStruct) {
      memberCount.set(words[i + 1], count - 2);
    } else if (op === Op.TypePointer) {
      pointee.set(words[i + 1], words[i + 3]);
    } else if (op === Op.Variable) {
      vars.push({ type: words[i + 1], id: words[i + 2], storage: words[i + 3] });
    }
    i += count;
  }
  const readonly = new Set(); // "group,binding" of read-only storage buffers
  const sampleLocations = new Set();
  for (const v of vars) {
    const d = decor.get(v.id) ?? new Map();
    const block = pointee.get(v.type);
    const storageBuffer = v.storage === StorageClass.StorageBuffer ||
      (v.storage === StorageClass.Uniform && decor.get(block)?.has(3 /* BufferBlock */));
    if (storageBuffer && d.has(Dec.Binding)) {
      const all = memberCount.get(block) > 0 && memberNonWritable.get(block) === memberCount.get(block);
      if (d.has(Dec.NonWritable) || all) readonly.add(`${d.get(Dec.DescriptorSet) ?? 0},${d.get(Dec.Binding)}`);
    }
    if (v.storage === StorageClass.Input && d.has(Dec.Sample) && d.has(Dec.Location)) {
      sampleLocations.add(d.get(Dec.Location));
    }
  }
  return { readonly, sampleLocations };
}

// --- the mechanical fixes ----------------------------------------------------------------------
export function fixWgsl(wgsl, facts, name) {
  let flips = 0;
  let out = wgsl.replace(/\n\s*let (_e\d+) = (\w+)\.gl_Position\.y;\n\s*\2\.gl_Position\.y = -\(\1\);/g, () => {
    flips++;
    return '';
  });
  const vertex = /@vertex/.test(wgsl) && /@builtin\(position\)/.test(wgsl);
  if (flips !== (vertex ? 1 : 0)) throw new Error(`${name}: ${flips} y flips of gl_Position in naga's WGSL, expected ${vertex ? 1 : 0}`);
  out = out.replace(/@group\((\d+)\) @binding\((\d+)\)\s*\nvar<storage, read_write>/g, (m, g, b) =>
    facts.readonly.has(`${g},${b}`) ? m.replace('read_write', 'read') : m);
  let pushes = 0;
  out = out.replace(/var<immediate> /g, () => {
    pushes++;
    return `@group(${PUSH_GROUP}) @binding(0) var<uniform> `;
  });
  if (pushes > 1) throw new Error(`${name}: ${pushes} push-constant blocks`);
  out = out.replace(/@interpolate\(flat\)/g, '@interpolate(flat, either)');
  if (facts.sampleLocations.size > 0) {
    let fixed = 0;
    out = out.replace(/@location\((\d+)\)( @interpolate\([^)]*\))? (\w+): /g, (m, loc, interp, ident) => {
      if (!facts.sampleLocations.has(Number(loc)) || interp) return m;
      fixed++;
      return `@location(${loc}) @interpolate(perspective, sample) ${ident}: `;
    });
    // Each input location appears once, in the fragment entry point's parameters.
    if (fixed !== facts.sampleLocations.size) {
      throw new Error(`${name}: ${facts.sampleLocations.size} per-sample inputs in SPIR-V, ${fixed} found in naga's WGSL`);
    }
  }
  return out;
}

// The per-sample twin of a vertex shader's WGSL (null: no smooth outputs).
export function perSampleVertex(wgsl) {
  let n = 0;
  const out = wgsl.replace(/^(\s+@location\(\d+\)) (\w+: )/gm, (m, loc, rest) => {
    n++;
    return `${loc} @interpolate(perspective, sample) ${rest}`;
  });
  return n ? out : null;
}

async function glslang(args) {
  try {
    await promisify(execFile)('glslangValidator', args);
  } catch (e) {
    throw new Error(`glslangValidator ${args.at(-1)}: ${e.stdout ?? ''}${e.stderr ?? e.message}`);
  }
}

export async function generate() {
  const { shaders, dirs } = findShaders();
  const tmp = mkdtempSync(join(tmpdir(), 'limn-wgsl-'));
  const files = new Map();
  try {
    // Include path as limn_embed_shaders: the shader's own folder, lib/gpu/shaders, then the rest.
    const spvOf = (s) => join(tmp, `${s.name}.spv`);
    await Promise.all(shaders.map((s) => glslang(['--quiet', '-V', '--target-env', 'vulkan1.1',
      ...[s.dir, ...dirs.filter((d) => d !== s.dir)].map((d) => `-I${d}`), '-o', spvOf(s), s.path])));
    for (const s of shaders) {
      const spv = spvOf(s);
      const buf = readFileSync(spv);
      const words = new Uint32Array(buf.buffer, buf.byteOffset, buf.byteLength / 4);
      let wgsl;
      try {
        const module = parseSpirv(words);
        wgsl = writeWgsl(module, validate(module));
      } catch (e) {
        throw new Error(`naga ${s.name}: ${e.formatted ?? e.message}`);
      }
      const header = (what) => `// Generated by web/tools/gen-shaders.mjs from ${s.name} (GLSL under lib/, the source to edit):\n` +
        `// glslang -> SPIR-V -> naga -> WGSL and mechanical fixes${what}. Do not edit.\n`;
      const fixed = fixWgsl(wgsl, spirvFacts(words), s.name);
      files.set(`${s.name.replace('.', '_')}.wgsl`, header('') + fixed);
      const twin = s.name.endsWith('.vert') ? perSampleVertex(fixed) : null;
      if (twin) files.set(`${s.name.replace('.vert', '_per_sample_vert')}.wgsl`, header(', smooth outputs per sample') + twin);
    }
  } finally {
    rmSync(tmp, { recursive: true, force: true });
  }
  return files;
}

// The differences between the committed web/shaders and freshly generated files (empty: fresh).
export function staleShaders(files) {
  const stale = [];
  const committed = existsSync(outDir) ? readdirSync(outDir).filter((f) => f.endsWith('.wgsl')) : [];
  for (const [f, text] of files) {
    const p = join(outDir, f);
    if (!existsSync(p)) stale.push(`${f}: missing`);
    else if (readFileSync(p, 'utf8') !== text) stale.push(`${f}: differs`);
  }
  for (const f of committed) if (!files.has(f)) stale.push(`${f}: no shader generates it`);
  return stale;
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const files = await generate();
  if (process.argv.includes('--check')) {
    const stale = staleShaders(files);
    for (const s of stale) console.error(`gen-shaders: stale: web/shaders/${s}`);
    if (stale.length) console.error('gen-shaders: run node web/tools/gen-shaders.mjs and commit web/shaders');
    process.exit(stale.length ? 1 : 0);
  }
  mkdirSync(outDir, { recursive: true });
  for (const f of readdirSync(outDir)) if (f.endsWith('.wgsl') && !files.has(f)) rmSync(join(outDir, f));
  for (const [f, text] of files) {
    const p = join(outDir, f);
    if (!existsSync(p) || readFileSync(p, 'utf8') !== text) writeFileSync(p, text);
  }
  console.error(`gen-shaders: ${files.size} shaders in web/shaders`);
}
