// The WGSL in web/shaders is what gen-shaders.mjs makes of the GLSL today, and every module and
// pipeline builds in Dawn (backend=null: Dawn's validation, no GPU work).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync } from 'node:fs';
import { staleShaders, generate, spirvFacts, fixWgsl } from '../tools/gen-shaders.mjs';
import { requestNodeDevice } from '../src/node_device.mjs';
import { loadShader } from '../src/shaders.mjs';

test('web/shaders is fresh (node web/tools/gen-shaders.mjs regenerates it)', async () => {
  assert.deepEqual(staleShaders(await generate()), []);
});

test('per-sample inputs keep their Sample decoration', async () => {
  const perSample = await loadShader('surface_per_sample.frag');
  const perPixel = await loadShader('surface.frag');
  assert.equal((perSample.match(/@interpolate\(perspective, sample\)/g) ?? []).length, 3);
  assert.equal(perPixel.includes('sample)'), false);
});

test('a fix that cannot be made is an error, not a silent loss', () => {
  const facts = { readonly: new Set(), sampleLocations: new Set([5]) };
  assert.throws(() => fixWgsl('fn main(@location(0) a: f32) {}', facts, 'x.frag'), /per-sample inputs/);
  assert.throws(() => spirvFacts(new Uint32Array([1, 2, 3, 4, 5])), /not a SPIR-V/);
});

test('every shader builds in Dawn', async () => {
  const { device } = await requestNodeDevice({ backend: 'null' });
  const names = readdirSync(new URL('../shaders/', import.meta.url)).filter((f) => f.endsWith('.wgsl'));
  assert.ok(names.length >= 20);
  const modules = new Map();
  for (const f of names) {
    const name = f.replace(/_(comp|vert|frag)\.wgsl$/, '.$1');
    assert.ok(f.endsWith('.wgsl') && name !== f, f);
    device.pushErrorScope('validation');
    const module = device.createShaderModule({ code: await loadShader(name), label: name });
    const info = await module.getCompilationInfo();
    const errors = info.messages.filter((m) => m.type === 'error').map((m) => `${m.lineNum}: ${m.message}`);
    assert.deepEqual(errors, [], name);
    if (name.endsWith('.comp')) device.createComputePipeline({ layout: 'auto', compute: { module } });
    const e = await device.popErrorScope();
    assert.equal(e?.message, undefined, name);
    modules.set(name, module);
  }
  // The draw pipelines limn-render builds: each vertex stage with its fragment stages.
  const pairs = [['surface.vert', 'surface.frag'], ['surface_per_sample.vert', 'surface_per_sample.frag'],
    ['surface_fetch.vert', 'surface.frag'], ['surface_fetch_per_sample.vert', 'surface_per_sample.frag'],
    ['mesh.vert', 'mesh.frag'], ['wire.vert', 'wire.frag'], ['wire_triangles.vert', 'wire.frag'],
    ['blend.vert', 'blend.frag'], ['blend_fetch_per_sample.vert', 'blend_per_sample.frag'], ['blend_per_sample.vert', 'blend_per_sample.frag']];
  for (const [v, f] of pairs) {
    device.pushErrorScope('validation');
    device.createRenderPipeline({
      layout: 'auto',
      vertex: { module: modules.get(v) },
      fragment: { module: modules.get(f), targets: [{ format: 'rgba8unorm-srgb' }] },
      depthStencil: { format: 'depth32float', depthWriteEnabled: true, depthCompare: 'less' },
      multisample: { count: 4 },
    });
    const e = await device.popErrorScope();
    assert.equal(e?.message, undefined, `${v} + ${f}`);
  }
});
