// limn-render's frame on WebGPU, pass for pass (lib/render/renderer.cpp, subdivision_pass.cpp,
// subdivision_draw.cpp), with the same WGSL that gen-shaders.mjs makes from limn's GLSL:
//   per level l = 1..N: face points, then edge points and vertex points (paper 000, 3.3 and 4.2);
//   limit points (4.4); then the draw of the fixed watertight tessellation, whose vertices the
//   vertex stage evaluates from their patch's 16 control points (the bicubic B-spline, eq. 1) or
//   their irregular face's limit points (4.3), into a 4x multisampled sRGB target.
// The control points go straight into the level-0 range of the vertex buffer (queue.writeBuffer:
// what limn-render's staging copy and copy_points.comp do on Vulkan).
import { ShaderCache, groupLayout, loadShader as loadShaderText } from './shaders.mjs';
import { PtexMap, buildTessellation } from './tessellation.mjs';
import { SmoothChartUVs, smoothSeamRecords } from './smooth_uvs.mjs';
import { boundsOf, frameCamera, viewMatrix, projectionMatrix, multiply, normalize, mul, add } from './camera.mjs';
import { LimnError } from './container.mjs';
import { buildEdgePieces, adaptiveData, adaptivePushes, surfaceOrientation, TOTALS_WORDS, INDEXED_DRAW_ARGS, DRAW_ARGS, DISPATCH_ARGS, WIRE_DRAW_ARGS } from './adaptive.mjs';
import { evaluateVertices, readBuffer, readDrawnMesh } from './drawn_mesh.mjs';
import { surfaceSamples } from './framing.mjs';
import { appendRows, cached, checkFixedSize, checkTableSize } from './table_buffers.mjs';
import { addWirePass } from './wire.mjs';
import { textureWords, fixedDisplacementPlan, checkDisplacement, checkMapSize, addComputeEvaluation, addDisplacementPasses, computeSeams } from './displacement.mjs';

const PUSH_SLOT = 256; // WebGPU's minUniformBufferOffsetAlignment
const MAX_GROUPS = 65535;
const STORAGE = 0x80, COPY_DST = 0x08, COPY_SRC = 0x04, INDEX = 0x10, UNIFORM = 0x40, MAP_READ = 0x01;
const RENDER_ATTACHMENT = 0x10, TEX_COPY_SRC = 0x01, INDIRECT = 0x100;

export const SHADES = { lit: 0, normal: 1, uv: 2, levels: 3, texture: 4 };
const DEFAULT_BASE = 0.8;

const srgbToLinear = (c) => (c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4));
/**
 * Where the GPU's coordinates are centred: the middle of the control points' box, as
 * lib/render/gpu_origin.h's renderOrigin (why there: float keeps 24 bits of a coordinate, and a small face
 * far from the origin lost its small differences). The same expression, so both upload the same
 * bits.
 */
export function renderOrigin(positions) {
  if (positions.length < 3) return [0, 0, 0];
  const lo = [positions[0], positions[1], positions[2]], hi = [...lo];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], positions[i + k]);
      hi[k] = Math.max(hi[k], positions[i + k]);
    }
  }
  return [0, 1, 2].map((k) => (lo[k] + hi[k]) * 0.5);
}

/**
 * viewProj * translate(origin), column-major: term by term in gpu_origin.h's translatedViewProjection
 * order, so both round the same doubles to float.
 */
function translated(vp, o) {
  const out = [...vp];
  for (let r = 0; r < 4; r++) out[12 + r] = ((vp[12 + r] + vp[r] * o[0]) + vp[4 + r] * o[1]) + vp[8 + r] * o[2];
  return out;
}

function packSrgb8(c) {
  let packed = 0;
  for (let i = 0; i < 3; i++) packed |= Math.round(Math.min(Math.max(c[i], 0), 1) * 255) << (8 * i);
  return packed >>> 0;
}

/**
 * A renderer for one loaded surface (chunks.mjs's loadLimn). settings: {width, height, samples
 * (1|4), shade, edgePixels (0: fixed grids; else the longest segment allowed), maxError (pixels
 * between the drawn chords and the surface, at most; limn-render's --max-error, default 0.1; 0:
 * segments of about edgePixels), interiorError (the maxError allowed where a piece faces the
 * eye; 0: maxError everywhere), pixelNormals (lit: the limit normal at each pixel), tess, view
 * {azimuthDeg, elevationDeg, fovDeg, zUp, eye, target, up}, color, background, sampleShading}.
 */
/**
 * The surface's fragment stage for a shading: lit and texture have their own, without the other
 * modes' code (lavapipe runs both sides of every branch; why in draw_common.glsl), the rest
 * share the general one. A renderer draws the shadings of the stage it was made with: a caller
 * that changes `shade` on a renderer (the viewer) makes a new one when this changes.
 */
export const surfaceFragmentStage = (shade) => (shade === 'lit' || shade === 'texture' ? `surface_${shade}` : 'surface');

export class Renderer {
  static async create(device, surface, settings) {
    const r = new Renderer(device, surface, settings);
    await r.init();
    return r;
  }

  constructor(device, surface, settings) {
    this.device = device;
    this.surface = surface;
    this.s = { width: 800, height: 600, samples: 4, shade: 'lit', edgePixels: 0, maxError: 0.1, tess: 64, view: {}, background: [0.2, 0.2, 0.2], ...settings };
    const s = this.s;
    if (s.samples !== 1 && s.samples !== 4) throw new LimnError(`--samples must be 1 or 4 (the counts WebGPU offers), not ${s.samples}`, 'usage');
    if (!(s.shade in SHADES)) throw new LimnError(`--shade ${s.shade}: one of ${Object.keys(SHADES).join(', ')}`, 'usage');
    if (s.shade === 'uv' && !surface.uvs) throw new LimnError('--shade uv: the mesh has no texture coordinates (no FVUV chunk); use --shade lit or normal', 'input');
    if (s.shade === 'texture' && !s.texture) throw new LimnError('--shade texture needs --texture MAP', 'usage');
    if (s.wire && s.wire !== 'triangles' && s.wire !== 'outlines') throw new LimnError(`wire '${s.wire}': 'outlines' (limn-render --wire) or 'triangles' (--wire-triangles)`, 'usage');
    if (s.texture) checkMapSize('--texture', s.texture);
    if ((s.texture || s.displace) && !surface.uvs) throw new LimnError('--texture and --displace need texture coordinates; the mesh has none', 'input');
    // Smooth face-varying UVs (TAGS fvar other than "all") come from the FVSF chunk; without it
    // the linear charts would be drawn where limn-render draws the smooth UVs.
    this.smooth = surface.uvs && surface.tables.options.fvar !== 5 ? surface.fvarSurface : null;
    if (surface.uvs && surface.tables.options.fvar !== 5 && !this.smooth && (s.shade === 'uv' || s.shade === 'texture' || s.meshOut || s.displace)) {
      const what = s.displace ? '--displace' : s.meshOut ? '--mesh-out' : `--shade ${s.shade}`;
      throw new LimnError(`smooth face-varying UVs (TAGS fvar other than "all") under ${what} need their surface, the FVSF chunk, which this container lacks; re-run limn-tables on it`, 'input');
    }
    if (s.displace) checkDisplacement(s.displace);
    this.timings = { js: 0 };
  }

  buffer(label, data, usage = STORAGE) {
    const size = Math.max(Math.ceil(data.byteLength / 4) * 4, 16);
    const b = this.device.createBuffer({ label, size, usage: usage | COPY_DST, mappedAtCreation: true });
    new Uint8Array(b.getMappedRange()).set(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    b.unmap();
    return b;
  }

  empty(label, size, usage = STORAGE) {
    return this.device.createBuffer({ label, size: Math.max(size, 16), usage: usage | COPY_DST | COPY_SRC });
  }

  async init() {
    const { device, surface, s } = this;
    const { mesh, tables } = surface;
    const shaders = new ShaderCache(device);
    const compute = async (name) => device.createComputePipelineAsync({ label: name, layout: 'auto', compute: { module: await shaders.module(name) } });

    // Tables: every level's face-point rows, edge- and vertex-point rows, the limit stencils.
    const face = appendRows(tables.facePoints, false);
    const stencil = appendRows(tables.edgePoints.flatMap((e, l) => [e, tables.vertexPoints[l]]), true);
    const limit = appendRows([tables.limitPosition, tables.limitTangent1, tables.limitTangent2], true);
    checkTableSize(tables, face, stencil);
    if (limit.index.byteLength > 128 << 20) throw new LimnError('limit tables over 128 MiB (they come in chunks in limn-render) are not supported here', 'capability');
    this.levels = [];
    for (let l = 1; l < tables.levels.length; l++) { // with the irregular faces' extra levels
      const L = tables.levels[l];
      this.levels.push({
        level: l,
        face: { firstOut: L.first, firstRow: face.firstRows[l - 1], count: L.facePoints },
        edge: { firstOut: L.first + L.facePoints, firstRow: stencil.firstRows[2 * (l - 1)], count: L.edgePoints },
        vertex: { firstOut: L.first + L.facePoints + L.edgePoints, firstRow: stencil.firstRows[2 * (l - 1) + 1], count: L.vertexPoints },
      });
    }
    // renderer.cpp: the element outlines exist for the fixed grids only, so --wire draws those.
    this.adaptive = s.edgePixels > 0 && s.wire !== 'outlines';
    // adaptive_options.cpp: per-pixel normals from the vertex stage's lit draw only (the
    // evaluated draws bind the evaluated vertices, not the surface), each element's own vertices.
    this.pixelNormals = this.adaptive && !!s.pixelNormals && s.shade === 'lit' && !s.meshOut && !s.wire && !s.displace;
    let tess = { vertices: new Uint32Array(4), indices: new Uint32Array(3), triangleLevels: new Uint32Array(1), vertexCount: 0 };
    if (this.adaptive) {
      // Smooth UVs: the elements' corners in their own chart and, displaced, the seam records of
      // the smooth UVs, from one ChartUVs in element order (as subdivision_draw.cpp builds them).
      const full = !!s.displace, smoothKey = this.smooth ? (full ? ' smooth seams' : ' smooth corners') : '';
      this.smoothSeams = this.smooth ? cached(tables, `smooth seam records${smoothKey}`, () =>
        smoothSeamRecords(tables, new SmoothChartUVs(this.smooth, new PtexMap({ ...mesh, uvs: surface.uvs }, 2 ** tables.depth)), full)) : null;
      const ep = cached(tables, `edge pieces${smoothKey}`, () => buildEdgePieces({ ...mesh, uvs: surface.uvs }, tables, this.smoothSeams?.own));
      let minimum = 0;
      for (const e of ep.elements) for (let k = 0; k < 4; k++) minimum += e.sideCount[k];
      const p = Math.max(s.maxError > 0 ? Math.min(s.edgePixels, 4) : s.edgePixels, 0.25); // as renderer.cpp
      const viewBudget = Math.max(Math.floor((32 * s.width * s.height) / (p * p)), 2 ** 20);
      // adaptive_options.cpp: the sample test only with the cull, which displacement turns off,
      // and never under a wireframe (its lines light pixels no triangle covers).
      const samplePositions = s.wire || s.displace ? [] : s.samples === 1 ? [[0.5, 0.5]] : [[0.375, 0.875], [0.875, 0.625], [0.125, 0.375], [0.625, 0.125]];
      this.adaptiveOptions = {
        edgePixels: s.edgePixels, maxError: s.maxError, tess: s.tess, samplePositions,
        // --mesh-out (evaluated): every triangle of an element that draws some, no shared slots.
        // and with displacement: the compute passes read the whole capacity (zeroed slots included).
        evaluated: !!s.meshOut || !!s.displace || !!s.wire,
        sharePoints: !s.meshOut && !s.displace && !s.wire && s.shade !== 'uv' && s.shade !== 'texture' && !this.pixelNormals,
        pixelNormals: this.pixelNormals, interiorError: s.interiorError ?? 0,
        // Displacement moves the surface off its control points' hull: no culling then.
        cull: !s.displace,
        // With a displacement map, at least a segment per texel (up to one per 2 pixels).
        texelsPerUV: s.displace ? Math.max(s.displace.map.width, s.displace.map.height) : 0,
        maxVertices: minimum + ep.elements.length + viewBudget, maxTriangles: minimum + 2 * viewBudget,
        smooth: this.smooth,
      };
      this.adaptiveData = adaptiveData(ep, tables, this.adaptiveOptions);
      this.closed = ep.pieces.length > 0 && ep.pieces.every((pc) => pc.users[1] !== 0xffffffff);
      this.orientation = this.closed && !s.displace ? surfaceOrientation(mesh) : 0;
    } else {
      checkFixedSize(tables, s.tess);
      const cap = 2 ** Math.floor(Math.log2(Math.max(s.tess, 1)));
      tess = cached(tables, `fixed ${cap}`, () => ({ ...buildTessellation({ ...mesh, uvs: surface.uvs }, tables, cap, !!surface.uvs, this.smooth), key: `fixed ${cap}` }));
    }
    this.tess = tess;
    const b = this.buffers = {
      vertices: this.empty('table vertices', tables.totalVertices * 16),
      faceStarts: this.buffer('face-point starts', face.starts),
      faceIndices: this.buffer('face-point indices', face.index),
      stencilStarts: this.buffer('stencil starts', stencil.starts),
      stencilIndices: this.buffer('stencil indices', stencil.index),
      stencilWeights: this.buffer('stencil weights', stencil.weight),
      limitStarts: this.buffer('limit starts', limit.starts),
      limitIndices: this.buffer('limit indices', limit.index),
      limitWeights: this.buffer('limit weights', limit.weight),
      limits: this.empty('limit points', Math.max(tables.limitCount, 1) * 32),
      patches: this.buffer('patches', tables.patches),
      irregular: this.buffer('irregular faces', tables.irregular),
      tessVertices: this.buffer('tessellation vertices', tess.vertices),
      triangles: this.buffer('triangle indices', tess.indices, STORAGE | INDEX),
      triangleLevels: this.buffer('triangle levels', tess.triangleLevels),
      texture: this.buffer('colour texture', textureWords(s.texture)),
      push: this.empty('push constants', PUSH_SLOT * (12 + 3 * (tables.levels.length - 1)), UNIFORM),
    };
    if (this.adaptive) {
      const d = this.adaptiveData;
      Object.assign(b, {
        elements: this.buffer('adaptive elements', d.elements),
        pieces: this.buffer('adaptive edge pieces', d.pieces),
        cull: this.empty('adaptive cull flags', d.elementCount * 4),
        rates: this.empty('adaptive edge rates', d.pieceCount * 4),
        pieceEnds: this.empty('adaptive piece ends', d.pieceCount * 16),
        // Per element, then (shared points) per edge piece, four a record (adaptive_tess.cpp).
        info: this.empty('adaptive element offsets', d.elementCount * 16 + Math.ceil(d.pieceCount / 4) * 16),
        totals: this.empty('adaptive totals', TOTALS_WORDS * 4, STORAGE | INDIRECT),
        tessVertices: this.empty('adaptive tessellation vertices', d.capV * 16),
        triangles: this.empty('adaptive triangle indices', d.capT * 12, STORAGE | INDEX),
        triangleLevels: this.empty('adaptive triangle levels', d.capT * 4),
      });
    }
    // The GPU works relative to the box's middle (renderOrigin): the control points, eye and view
    // go up minus it, the drawn mesh comes back plus it (drawn_mesh.mjs).
    const o = renderOrigin(mesh.positions);
    this.origin = o;
    this.controlPoints = new Float32Array(mesh.vertexCount * 4);
    for (let i = 0; i < mesh.vertexCount; i++) {
      this.controlPoints.set([mesh.positions[3 * i] - o[0], mesh.positions[3 * i + 1] - o[1], mesh.positions[3 * i + 2] - o[2], 1], 4 * i);
    }
    const [facePass, stencilPass, limitPass] = await Promise.all(['subdiv_face_points.comp', 'subdiv_stencils.comp', 'subdiv_limit.comp'].map(compute));
    const perSample = s.sampleShading && s.samples > 1;
    // Displaced: the vertices were evaluated and moved by compute passes; the draw fetches them.
    // Per-pixel normals: the vertex stage also hands the fragment stage each triangle's element
    // net (subdivision_pass.cpp surfaceVertex; the same bindings as surface.vert).
    const vertexStage = s.displace ? 'surface_fetch' : this.pixelNormals ? 'surface_pixel' : 'surface';
    const vs = await shaders.module(perSample ? `${vertexStage}_per_sample.vert` : `${vertexStage}.vert`);
    // Lit and texture shading: the fragment stage without the other modes' code, as limn-render
    // picks it (subdivision_pass.cpp surfaceFragment; why in draw_common.glsl).
    const fragmentStage = surfaceFragmentStage(s.shade);
    this.fragmentStage = fragmentStage;
    const fragmentShader = this.pixelNormals ? 'surface_lit_pixel' : fragmentStage;
    const fs = await shaders.module(perSample ? `${fragmentShader}_per_sample.frag` : `${fragmentShader}.frag`);
    const drawGroupLayouts = [
      groupLayout(device, (await loadShaderText(`${vertexStage}.vert`)) + (await loadShaderText('surface.frag')), 1 | 2),
      device.createBindGroupLayout({ entries: [] }), device.createBindGroupLayout({ entries: [] }),
      device.createBindGroupLayout({ entries: [{ binding: 0, visibility: 1 | 2, buffer: { type: 'uniform' } }] })];
    const drawLayout = device.createPipelineLayout({ bindGroupLayouts: drawGroupLayouts });
    drawLayout.groups = drawGroupLayouts;
    const drawPipeline = (cullMode) => device.createRenderPipelineAsync({
      label: `surface (cull ${cullMode})`, layout: drawLayout,
      vertex: { module: vs },
      fragment: { module: fs, targets: [{ format: 'rgba8unorm-srgb' }] },
      primitive: { topology: 'triangle-list', cullMode, frontFace: 'ccw' },
      depthStencil: { format: 'depth32float', depthWriteEnabled: true, depthCompare: 'less' },
      multisample: { count: s.samples },
    });
    this.drawPipeline = await drawPipeline('none');
    // View-adaptive on a closed surface seen from outside: the rasterizer drops back faces, as
    // limn-render's culled draw does (subdivision_pass.cpp culledPipeline).
    if (this.adaptive && this.closed && this.orientation !== 0) {
      this.culledPipeline = await drawPipeline(this.orientation > 0 ? 'back' : 'front');
    }
    const group = (pipeline, index, buffers) => device.createBindGroup({
      layout: pipeline.getBindGroupLayout(index),
      entries: buffers.map((buf, binding) => (buf ? { binding, resource: buf.buffer ? buf : { buffer: buf } } : null)).filter(Boolean),
    });
    // Each pass gets its own 256-byte slot of push constants (written once per frame).
    let slot = 0;
    const pushGroup = this.pushGroup = (pipeline) => {
      const offset = PUSH_SLOT * slot++;
      return { offset, group: device.createBindGroup({ layout: pipeline.getBindGroupLayout(3), entries: [{ binding: 0, resource: { buffer: b.push, offset, size: PUSH_SLOT } }] }) };
    };
    const faceGroup = group(facePass, 0, [b.vertices, b.faceStarts, b.faceIndices]);
    const stencilGroup = group(stencilPass, 0, [b.vertices, b.stencilStarts, b.stencilIndices, b.stencilWeights]);
    this.passes = [];
    this.pushData = new Uint32Array((PUSH_SLOT / 4) * (12 + 3 * (tables.levels.length - 1)));
    const dispatch = (pipeline, bindGroup, count, fields, label) => {
      if (count === 0) return;
      const groups = Math.ceil(count / 64);
      const y = Math.ceil(groups / MAX_GROUPS), x = Math.ceil(groups / y);
      const p = pushGroup(pipeline);
      this.pushData.set([count, x * 64, 0, 0, ...fields], p.offset / 4);
      this.passes.push({ pipeline, bindGroup, push: p.group, x, y, label, pushOffset: p.offset });
    };
    this.dispatch = dispatch;
    for (const L of this.levels) {
      dispatch(facePass, faceGroup, L.face.count, [L.face.firstOut, L.face.firstRow], `face points L${L.level}`);
      dispatch(stencilPass, stencilGroup, L.edge.count, [L.edge.firstOut, L.edge.firstRow], `edge points L${L.level}`);
      dispatch(stencilPass, stencilGroup, L.vertex.count, [L.vertex.firstOut, L.vertex.firstRow], `vertex points L${L.level}`);
    }
    dispatch(limitPass, group(limitPass, 0, [b.vertices, b.limitStarts, b.limitIndices, b.limitWeights, b.limits]), tables.limitCount,
      [tables.limitCount, 0], 'limit points');
    if (this.adaptive) {
      // The five passes (adaptive_tess.cpp); their push constants depend on the view (setView).
      const d = this.adaptiveData;
      const bindings = {
        'adaptive_cull.comp': [b.vertices, b.patches, b.irregular, b.limits, b.cull],
        'adaptive_rates.comp': [b.vertices, b.patches, b.irregular, b.limits, b.pieces, b.cull, b.rates, b.pieceEnds],
        'adaptive_counts.comp': [b.elements, b.pieces, b.rates, b.cull, b.info, b.pieceEnds],
        'adaptive_scan.comp': [b.info, b.totals],
        'adaptive_emit.comp': [b.elements, b.totals, b.pieces, b.rates, b.info, b.tessVertices, b.triangles, b.triangleLevels],
      };
      this.adaptivePasses = [];
      for (const [name, count] of [['adaptive_cull.comp', d.elementCount], ['adaptive_rates.comp', d.pieceCount], ['adaptive_counts.comp', d.elementCount], ['adaptive_scan.comp', 1], ['adaptive_emit.comp', d.elementCount]]) {
        const module = await shaders.module(name);
        const layout0 = groupLayout(device, await loadShaderText(name), 4 /* COMPUTE */);
        const layout3 = device.createBindGroupLayout({ entries: [{ binding: 0, visibility: 4, buffer: { type: 'uniform' } }] });
        const pipeline = await device.createComputePipelineAsync({ label: name, layout: device.createPipelineLayout({ bindGroupLayouts: [layout0, device.createBindGroupLayout({ entries: [] }), device.createBindGroupLayout({ entries: [] }), layout3] }), compute: { module } });
        const bindGroup = device.createBindGroup({ layout: layout0, entries: bindings[name].map((buffer, binding) => ({ binding, resource: { buffer } })) });
        const before = this.passes.length;
        dispatch(pipeline, bindGroup, count, [], name);
        if (this.passes.length > before) this.adaptivePasses.push({ name, pass: this.passes[this.passes.length - 1], count });
      }
    }
    if (s.displace || s.wire) await addComputeEvaluation(this, compute, group);
    if (s.displace) {
      // The SEAM chunk's records, or the same computed here (limn-render does so too).
      // Smooth UVs: view-adaptive, the seam records of the smooth UVs; fixed grids, the plan takes
      // every face's smooth UV from the tessellation's charts.
      this.seams = this.smooth ? this.smoothSeams : surface.seams ?? cached(tables, 'seams', () => computeSeams(mesh, surface.uvs, tables));
      const plan = this.adaptive ? null : cached(tables, `displacement ${tess.key} ${!!s.displace.seamFix}`, () => fixedDisplacementPlan(tess, this.seams, s.displace.seamFix, tables));
      await addDisplacementPasses(this, compute, group, plan);
    }
    const drawPush = pushGroup(this.drawPipeline);
    this.drawPushOffset = drawPush.offset;
    const drawBuffers = s.displace
      ? [b.displaced, b.displacedNormals, b.tessVertices, b.triangles, b.triangleLevels, null, null, b.texture]
      : [b.vertices, b.patches, b.irregular, b.limits, b.tessVertices, b.triangles, b.triangleLevels, b.texture];
    this.drawGroups = [group(this.drawPipeline, 0, drawBuffers), drawPush.group];
    if (s.wire) await addWirePass(this, shaders, drawLayout);

    // Framing: the control points' box and sphere (boundsOf), the hull samples when auto-framed.
    const points = [];
    for (let i = 0; i < mesh.vertexCount; i++) points.push([mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]]);
    this.bounds = boundsOf(points);
    if (s.displace) {
      // renderer.cpp: the displaced surface leaves the hull; frame the box padded by half the
      // scale instead of the surface samples.
      const pad = Math.abs(s.displace.scale) * 0.5;
      this.bounds.min = this.bounds.min.map((x) => x - pad);
      this.bounds.max = this.bounds.max.map((x) => x + pad);
      if (this.bounds.sphereRadius > 0) this.bounds.sphereRadius += pad;
      this.bounds.hull = [];
    } else {
      this.bounds.hull = s.view.eye ? [] : surfaceSamples(this.surface);
    }
    this.setView(s.view);

    const w = s.width, h = s.height;
    this.color = device.createTexture({ size: [w, h], format: 'rgba8unorm-srgb', usage: RENDER_ATTACHMENT | TEX_COPY_SRC, sampleCount: 1 });
    if (s.samples > 1) this.msaa = device.createTexture({ size: [w, h], format: 'rgba8unorm-srgb', usage: RENDER_ATTACHMENT, sampleCount: s.samples });
    this.depth = device.createTexture({ size: [w, h], format: 'depth32float', usage: RENDER_ATTACHMENT, sampleCount: s.samples });
    this.rowBytes = Math.ceil((w * 4) / 256) * 256;
    this.readback = device.createBuffer({ size: this.rowBytes * h, usage: MAP_READ | COPY_DST });
  }

  // The frame's compute passes, then surface_eval.comp over `n` tessellation vertices
  // (drawn_mesh.mjs).
  evaluate(tvb, n, withLimits = false) { return evaluateVertices(this, tvb, n, withLimits); }

  /**
   * The drawn surface, as limn-render --mesh-out reads it back (drawn_mesh.mjs readDrawnMesh):
   * positions and normals (4 floats each), info, tessellation vertices, approximate flags and
   * triangles. View-adaptive: this view's emitted tessellation (create with settings.meshOut).
   * Displaced: the displaced positions.
   */
  drawnMesh() { return readDrawnMesh(this); }

  readBuffer(buffer, bytes, Type) { return readBuffer(this.device, buffer, bytes, Type); }

  setView(view) {
    const s = this.s, aspect = s.width / s.height;
    const cam = frameCamera(view, this.bounds, aspect);
    this.camera = cam;
    const v = viewMatrix(cam);
    const vp = translated(multiply(projectionMatrix(cam, aspect), v), this.origin);
    const eye = [0, 1, 2].map((i) => cam.eye[i] - this.origin[i]); // the GPU's coordinates
    const right = [v[0], v[4], v[8]], up = [v[1], v[5], v[9]], forward = [-v[2], -v[6], -v[10]];
    const az = ((s.lightAzimuthDeg ?? -40) * Math.PI) / 180, el = ((s.lightElevationDeg ?? 35) * Math.PI) / 180;
    const light = s.shade === 'levels'
      ? normalize(add(add(mul(forward, -1), mul(up, 0.45)), mul(right, -0.3)))
      : normalize(add(add(mul(forward, -Math.cos(el) * Math.cos(az)), mul(right, Math.cos(el) * Math.sin(az))), mul(up, Math.sin(el))));
    const push = new DataView(new ArrayBuffer(128));
    for (let i = 0; i < 16; i++) push.setFloat32(4 * i, vp[i], true);
    for (let i = 0; i < 3; i++) {
      push.setFloat32(64 + 4 * i, eye[i], true);
      push.setFloat32(80 + 4 * i, light[i], true);
      push.setFloat32(96 + 4 * i, 0.006, true);
    }
    // renderer.cpp: a texture is drawn as it is (white base) unless a colour is given.
    const base = s.color ?? (s.texture ? [1, 1, 1] : [DEFAULT_BASE, DEFAULT_BASE, DEFAULT_BASE]);
    push.setUint32(76, packSrgb8(base), true);
    if (surfaceFragmentStage(s.shade) !== this.fragmentStage) {
      throw new Error(`internal: --shade ${s.shade} drawn by a renderer made for ${this.fragmentStage}; make a new renderer`);
    }
    push.setUint32(112, SHADES[s.shade], true);
    push.setFloat32(116, 2e-3, true);
    push.setUint32(120, this.surface.tables.patchCount, true);
    push.setUint32(124, (s.shade === 'levels' ? 1 : 0) | (view.zUp ? 4 : 0), true);
    this.pushData.set(new Uint32Array(push.buffer), this.drawPushOffset / 4);
    if (this.adaptive) {
      // Back faces may be culled only on a closed surface seen from outside the control points' box.
      const bb = this.bounds, e = cam.eye;
      const outside = [0, 1, 2].some((i) => e[i] < bb.min[i] || e[i] > bb.max[i]);
      const facing = outside ? this.orientation : 0;
      this.facing = facing;
      const pushes = adaptivePushes(this.adaptiveData, this.surface.tables, this.adaptiveOptions,
        { viewProj: vp, eye, facing, width: s.width, height: s.height });
      for (const { name, pass } of this.adaptivePasses) {
        const words = pushes.find((q) => q[0] === name)[2];
        // The dispatch header (count, row invocations) stays; the pass's own fields follow at 16.
        this.pushData.set(words, pass.pushOffset / 4 + 4);
      }
    }
    this.clear = [...s.background.map(srgbToLinear), 1];
  }

  uploadControlPoints() {
    this.device.queue.writeBuffer(this.buffers.vertices, 0, this.controlPoints);
    this.device.queue.writeBuffer(this.buffers.push, 0, this.pushData);
  }

  encodeCompute(enc, withAdaptive = true) {
    // One compute pass per dispatch: WebGPU orders their storage accesses like limn's barriers.
    for (const p of this.passes) {
      if (!withAdaptive && (p.indirect || p.label.startsWith('adaptive'))) continue;
      const cp = enc.beginComputePass({ label: p.label });
      cp.setPipeline(p.pipeline);
      cp.setBindGroup(0, p.bindGroup);
      cp.setBindGroup(3, p.push);
      if (p.indirect) cp.dispatchWorkgroupsIndirect(this.buffers.totals, DISPATCH_ARGS); else cp.dispatchWorkgroups(p.x, p.y);
      cp.end();
    }
  }

  /** Records and submits one frame (upload, compute passes, draw, copy to the readback buffer). */
  frame() {
    const t0 = performance.now();
    const { device, s } = this;
    this.uploadControlPoints();
    const enc = device.createCommandEncoder();
    this.encodeCompute(enc);
    this.views ??= { target: (this.msaa ?? this.color).createView(), resolve: this.msaa ? this.color.createView() : undefined, depth: this.depth.createView() };
    const rp = enc.beginRenderPass({
      colorAttachments: [{
        view: this.views.target, resolveTarget: this.views.resolve,
        clearValue: this.clear, loadOp: 'clear', storeOp: this.msaa ? 'discard' : 'store',
      }],
      depthStencilAttachment: { view: this.views.depth, depthClearValue: 1, depthLoadOp: 'clear', depthStoreOp: 'discard' },
    });
    rp.setPipeline(this.culledPipeline && this.facing ? this.culledPipeline : this.drawPipeline);
    rp.setBindGroup(0, this.drawGroups[0]);
    rp.setBindGroup(3, this.drawGroups[1]);
    const count = this.tess.indices.length;
    if (this.adaptive && s.shade === 'levels') {
      rp.drawIndirect(this.buffers.totals, DRAW_ARGS);
    } else if (this.adaptive) {
      rp.setIndexBuffer(this.buffers.triangles, 'uint32');
      rp.drawIndexedIndirect(this.buffers.totals, INDEXED_DRAW_ARGS);
    } else if (s.shade === 'levels') {
      rp.draw(count);
    } else {
      rp.setIndexBuffer(this.buffers.triangles, 'uint32');
      rp.drawIndexed(count);
    }
    if (this.wirePipeline) {
      rp.setPipeline(this.wirePipeline);
      rp.setBindGroup(0, this.wireGroup);
      rp.setBindGroup(3, this.drawGroups[1]);
      if (this.wireLineCount !== undefined) {
        rp.setIndexBuffer(this.buffers.wireLines, 'uint32');
        rp.drawIndexed(this.wireLineCount);
      } else if (this.adaptive) rp.drawIndirect(this.buffers.totals, WIRE_DRAW_ARGS); else rp.draw(2 * count);
    }
    rp.end();
    enc.copyTextureToBuffer({ texture: this.color }, { buffer: this.readback, bytesPerRow: this.rowBytes }, [s.width, s.height]);
    device.queue.submit([enc.finish()]);
    this.timings.js = performance.now() - t0;
  }

  /** The frame's pixels, RGBA8 rows top to bottom (sRGB, as the PNG holds them). */
  async pixels() {
    const { s } = this;
    await this.readback.mapAsync(1);
    const src = new Uint8Array(this.readback.getMappedRange());
    const out = new Uint8Array(s.width * s.height * 4);
    for (let y = 0; y < s.height; y++) out.set(src.subarray(y * this.rowBytes, y * this.rowBytes + s.width * 4), y * s.width * 4);
    this.readback.unmap();
    return out;
  }

  triangleCount() { return this.tess.indices.length / 3; }

  /** Triangles the last frame drew (view-adaptive: read back from the scan's totals). */
  async drawnTriangles() {
    return this.adaptive ? (await this.readBuffer(this.buffers.totals, 16, Uint32Array))[0] / 3 : this.triangleCount();
  }

  destroy() {
    for (const buf of Object.values(this.buffers)) buf.destroy();
    for (const t of [this.color, this.msaa, this.depth]) t?.destroy();
    this.readback.destroy();
  }
}
