// limn-render's wireframes over the drawn surface (subdivision_draw.cpp, wire*.vert): --wire, the
// elements' outlines on the fixed grids, and --wire-triangles, the edges of every triangle drawn.
import { groupLayout, loadShader } from './shaders.mjs';
import { cached } from './table_buffers.mjs';

const INDEX = 0x10;

// subdivision_draw.cpp: the elements' outline segments, each once (an edge two elements share is
// listed by both), in the order first seen.
function wireLines(outline) {
  const seen = new Set(), out = [];
  for (let i = 0; i + 1 < outline.length; i += 2) {
    const a = outline[i], b = outline[i + 1], key = Math.min(a, b) * 2 ** 32 + Math.max(a, b);
    if (!seen.has(key)) { seen.add(key); out.push(a, b); }
  }
  return Uint32Array.from(out);
}

/**
 * The wire pipeline of renderer `r` (settings.wire 'outlines' or 'triangles'): its lines at the
 * positions the draw read (evaluated or displaced), pulled towards the eye, with the draw's push
 * constants (the draw pipeline layout's groups 1-3).
 */
export async function addWirePass(r, shaders, drawLayout) {
  const { device, s, buffers: b, tess } = r, { tables } = r.surface;
  const outlines = s.wire === 'outlines', wireVert = outlines ? 'wire.vert' : 'wire_triangles.vert';
  const wireLayout = groupLayout(device, await loadShader(wireVert), 1);
  r.wirePipeline = await device.createRenderPipelineAsync({
    label: `wire (${s.wire})`,
    layout: device.createPipelineLayout({ bindGroupLayouts: [wireLayout, drawLayout.groups[1], drawLayout.groups[2], drawLayout.groups[3]] }),
    vertex: { module: await shaders.module(wireVert) },
    fragment: { module: await shaders.module('wire.frag'), targets: [{ format: 'rgba8unorm-srgb' }] },
    primitive: { topology: 'line-list' },
    depthStencil: { format: 'depth32float', depthWriteEnabled: false, depthCompare: 'less-equal' },
    multisample: { count: s.samples },
  });
  const drawn = s.displace ? b.displaced : b.evalPositions;
  r.wireGroup = device.createBindGroup({ layout: wireLayout, entries: (outlines ? [drawn] : [drawn, b.triangles]).map((buffer, binding) => ({ binding, resource: { buffer } })) });
  if (outlines) {
    const lines = cached(tables, `outline ${tess.key}`, () => wireLines(tess.outline));
    r.wireLineCount = lines.length;
    b.wireLines = r.buffer('wire lines', lines, INDEX);
  }
}
