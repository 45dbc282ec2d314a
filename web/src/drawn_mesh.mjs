// The surface as drawn, read back from the GPU: what limn-render's --mesh-out writes
// (subdivision_pass.cpp drawnMesh, fixed_grids.cpp and adaptive_tess.cpp finishDrawnMesh), and the
// compute evaluation of tessellation vertices it uses.
import { ShaderCache } from './shaders.mjs';
import { LimnError } from './container.mjs';
import { TOTALS_WORDS } from './adaptive.mjs';

const MAX_GROUPS = 65535;
const STORAGE = 0x80, COPY_DST = 0x08, COPY_SRC = 0x04, UNIFORM = 0x40, MAP_READ = 0x01;
// An irregular face's quadtree node codes (lib/subdiv/tables.h): the kind in the top two bits.
const NODE_SUBPATCH = 0, NODE_LEAF = (2 << 30) >>> 0, NODE_BASIS = (3 << 30) >>> 0;
const NODE_NONE = 0xffffffff, NODE_INDEX = (1 << 30) - 1;
const PATCH_WORDS = 24;

/** `bytes` of `buffer` read back as a `Type` array. */
export async function readBuffer(device, buffer, bytes, Type) {
  const rb = device.createBuffer({ size: Math.max(bytes, 16), usage: MAP_READ | COPY_DST });
  const enc = device.createCommandEncoder();
  if (bytes) enc.copyBufferToBuffer(buffer, 0, rb, 0, bytes);
  device.queue.submit([enc.finish()]);
  await rb.mapAsync(1);
  const out = new Type(rb.getMappedRange().slice(0, bytes));
  rb.unmap();
  rb.destroy();
  return out;
}

/**
 * The frame's compute passes (without the view-adaptive ones), then surface_eval.comp (the vertex
 * stage's evaluation as a compute pass: limn-render's --eval compute and --mesh-out) over `n`
 * tessellation vertices in `tvb`. Returns positions and normals (vec4 each), info (uvec4: ptex,
 * u bits, v bits) and, with `withLimits`, the limit points (8 floats each).
 */
export async function evaluateVertices(r, tvb, n, withLimits = false) {
  const { device } = r;
  const { tables } = r.surface;
  r.evalPass ??= await device.createComputePipelineAsync({ layout: 'auto', compute: { module: await new ShaderCache(device).module('surface_eval.comp') } });
  const evalPass = r.evalPass, b = r.buffers;
  const pos = r.empty('evaluated positions', n * 16), nrm = r.empty('evaluated normals', n * 16), info = r.empty('evaluated ptex', n * 16);
  const push = r.empty('evaluate push', 256, UNIFORM);
  const groups = Math.ceil(Math.max(n, 1) / 64), y = Math.ceil(groups / MAX_GROUPS), x = Math.ceil(groups / y);
  device.queue.writeBuffer(push, 0, new Uint32Array([n, x * 64, 0, 0, tables.patchCount]));
  r.uploadControlPoints();
  const enc = device.createCommandEncoder();
  r.encodeCompute(enc, false);
  if (n > 0) {
    const cp = enc.beginComputePass();
    cp.setPipeline(evalPass);
    cp.setBindGroup(0, device.createBindGroup({ layout: evalPass.getBindGroupLayout(0), entries: [b.vertices, b.patches, b.irregular, b.limits, tvb, pos, nrm, info].map((buffer, binding) => ({ binding, resource: { buffer } })) }));
    cp.setBindGroup(3, device.createBindGroup({ layout: evalPass.getBindGroupLayout(3), entries: [{ binding: 0, resource: { buffer: push } }] }));
    cp.dispatchWorkgroups(x, y);
    cp.end();
  }
  const L = withLimits ? tables.limitCount : 0;
  const rb = device.createBuffer({ size: Math.max(n * 48 + L * 32, 16), usage: MAP_READ | COPY_DST });
  if (n > 0) {
    enc.copyBufferToBuffer(pos, 0, rb, 0, n * 16);
    enc.copyBufferToBuffer(nrm, 0, rb, n * 16, n * 16);
    enc.copyBufferToBuffer(info, 0, rb, n * 32, n * 16);
  }
  if (L > 0) enc.copyBufferToBuffer(b.limits, 0, rb, n * 48, L * 32);
  device.queue.submit([enc.finish()]);
  await rb.mapAsync(1);
  const bytes = rb.getMappedRange().slice(0);
  rb.unmap();
  for (const buf of [pos, nrm, info, push, rb]) buf.destroy();
  const f = new Float32Array(bytes);
  const out = { positions: f.subarray(0, 4 * n), normals: f.subarray(4 * n, 8 * n), info: new Uint32Array(bytes, n * 32, 4 * n), limits: f.subarray(12 * n) };
  toModel(r.origin, out.positions, 4);
  toModel(r.origin, out.limits, 8);
  return out;
}

/**
 * Points read back from the GPU (its coordinates are the model's minus renderer.origin) back in
 * the model's: each xyz plus the origin in double, rounded to float as renderer.cpp's drawnMesh.
 */
function toModel(origin, values, stride) {
  if (!origin || (origin[0] === 0 && origin[1] === 0 && origin[2] === 0)) return;
  for (let i = 0; i + 2 < values.length; i += stride) {
    for (let k = 0; k < 3; k++) values[i + k] += origin[k];
  }
}

/**
 * Whether a drawn point (element, s | t << 16 in 1/32768) is off the limit surface: drawn bilinear
 * within 2^-K of an extraordinary corner (docs/irregular.md), as subdivision_draw.cpp's
 * drawnPointIsApproximate walks the irregular face's quadtree in the patches buffer.
 */
export function drawnPointIsApproximate(tables, element, st) {
  const P = tables.patchCount, nodes = tables.patches;
  if (element < P) return false;
  const face = element - P, full = 32768, half = 16384;
  let S = st & 0xffff, T = st >>> 16;
  const corner = (a, b) => (a === 0 || a === full) && (b === 0 || b === full);
  if (corner(S, T)) return false;
  if (face >= tables.irregularNodeCount) return true; // no quadtree: bilinear
  const cv = (node, k) => nodes[PATCH_WORDS * node + k];
  let at = P + face;
  for (let k = 0; k < 17; k++) {
    const c = (S >= half ? 1 : 0) | (T >= half ? 2 : 0), code = cv(at, c);
    if (code === NODE_NONE) break;
    const kind = (code & ~NODE_INDEX) >>> 0, index = code & NODE_INDEX;
    if (kind === NODE_BASIS) { // a smooth face: bilinear only within 2^-bands of its corner
      if (cv(index, 5) > 0) { // below the root: in the quadrant's halved (s, t)
        S = 2 * S - (c & 1 ? full : 0);
        T = 2 * T - (c & 2 ? full : 0);
      }
      const r = cv(index, 1), K = cv(index, 3);
      let a = r === 0 ? S : r === 1 ? T : r === 2 ? full - S : full - T;
      let b = r === 0 ? T : r === 1 ? full - S : r === 2 ? full - T : S;
      if (a === 0 && b === 0) return false;
      for (let band = 1; Math.max(a, b) < half && band < K; ++band) { a *= 2; b *= 2; }
      return Math.max(a, b) < half;
    }
    S = 2 * S - (c & 1 ? full : 0);
    T = 2 * T - (c & 2 ? full : 0);
    if (kind === NODE_SUBPATCH) return false;
    if (kind === NODE_LEAF) return !corner(S, T);
    at = index;
  }
  // A face (or node) without children there: the face's corners' bilinear blend.
  return !corner(st & 0xffff, st >>> 16);
}

/**
 * The drawn surface, as limn-render --mesh-out reads it back after a frame: per vertex its
 * position and normal (vec4 each; displaced when displaced), info (uvec4: ptex, u bits, v bits),
 * tessellation vertex (uvec4: element, s | t << 16, texture u bits, v bits) and whether it is
 * approximate (drawnPointIsApproximate, a byte); the triangles; and whether the vertices carry
 * texture coordinates. View-adaptive: this view's emitted
 * tessellation (create the renderer with settings.meshOut, as limn-render evaluates every
 * triangle of an element that draws some for --mesh-out).
 */
export async function readDrawnMesh(r) {
  const { device, buffers: b } = r;
  let triangles = r.tess.indices, n = r.tess.vertexCount, tessVertices = r.tess.vertices.subarray(0, 4 * n);
  if (r.adaptive || r.s.displace) {
    r.uploadControlPoints();
    const enc = device.createCommandEncoder();
    r.encodeCompute(enc, true);
    device.queue.submit([enc.finish()]);
  }
  if (r.adaptive) {
    const t = await readBuffer(device, b.totals, TOTALS_WORDS * 4, Uint32Array);
    if (t[15] || t[22] || t[23]) throw new LimnError('--mesh-out: the view-adaptive tessellation of this view overflowed its buffers; nothing written: raise --max-error or --edge-pixels, or lower --tess', 'input');
    n = t[17];
    triangles = await readBuffer(device, b.triangles, t[16] * 12, Uint32Array);
    tessVertices = await readBuffer(device, b.tessVertices, n * 16, Uint32Array);
  }
  let drawn;
  if (r.s.displace) {
    // What the frame's passes evaluated and moved.
    drawn = {
      positions: await readBuffer(device, b.displaced, n * 16, Float32Array),
      normals: await readBuffer(device, b.displacedNormals, n * 16, Float32Array),
      info: await readBuffer(device, b.evalInfo, n * 16, Uint32Array),
    };
    toModel(r.origin, drawn.positions, 4);
  } else {
    drawn = await evaluateVertices(r, b.tessVertices, n);
  }
  const approximate = new Uint8Array(n);
  for (let i = 0; i < n; i++) approximate[i] = drawnPointIsApproximate(r.surface.tables, tessVertices[4 * i], tessVertices[4 * i + 1]) ? 1 : 0;
  return { ...drawn, tessVertices, triangles, approximate, hasTexCoords: !!r.surface.uvs };
}
