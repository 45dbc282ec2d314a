// The limn viewer: a .limn container drawn in the page by the web/ runtime (limn-render's passes
// and shaders on WebGPU). State lives in the URL (state.mjs); it draws only when something
// changed, or while the turntable turns; errors are shown in the panel, in words.
import { loadLimn, Renderer } from '../src/index.mjs';
import { surfaceFragmentStage } from '../src/renderer.mjs';
import { parseQuery, toQuery, renderCommand, DEFAULTS } from './state.mjs';
import { orbit, zoom, pan, frame, viewSpec } from './orbit.mjs';
import { attachControls } from './controls.mjs';
import { showError, clearError, clearErrors, describe } from './errors.mjs';
import { buildPanel, syncPanel as syncPanelOf } from './panel.mjs';
import { attachFiles } from './files.mjs';
import { bench } from './viewer_bench.mjs';
import { requestDevice, GpuTimer, ViewerError, imagePixels } from './gpu.mjs';

const $ = (id) => document.getElementById(id);
const canvas = $('view'), stage = $('stage');
const query = parseQuery(location.search);
let state = query.state;
const sources = { model: query.model, displace: query.displace, texture: query.texture };
let gpu = null, timer = null, context = null;
let model = null; // { surface, name }
let renderer = null, rendererKey = '';
let map = null; // { name, kind: 'displace' | 'texture', image: {width, height, rgb, values}, serial }
let turntable = query.turntable;
const stats = { frames: 0, fpsFrames: 0, fpsSince: 0 };
// Parameters the link asked for: an unsupported one is an error shown, a default one is not.
const asked = new Set(new URLSearchParams(location.search).keys());

// --- what the runtime supports ------------------------------------------------------------------
// The renderer's constructor refuses, in words, what the runtime cannot draw, before any GPU work:
// a control is disabled with that reason rather than drawing something else.
function refusal(overrides) {
  if (!gpu || !model) return null;
  try {
    // Each option is probed alone, on settings the runtime draws, so that one refusal does not hide another.
    const base = { ...rendererSettings(state), edgePixels: 0, shade: 'lit', sampleShading: false, displace: undefined, texture: undefined };
    new Renderer(gpu.device, model.surface, { ...base, ...overrides });
    return null;
  } catch (e) {
    return describe(e);
  }
}

function rendererSettings(s) {
  const [width, height] = canvasSize();
  return {
    width, height, samples: s.samples, sampleShading: s.sampleShading, shade: s.shade, maxError: s.maxError, edgePixels: s.edgePixels, tess: s.tess,
    interiorError: s.interiorError, pixelNormals: s.pixelNormals,
    wire: s.wire ? 'triangles' : undefined, // limn-render --wire-triangles: the edges of the triangles drawn
    view: viewSpec(s), color: s.color ?? undefined, background: s.background,
    lightAzimuthDeg: s.light[0], lightElevationDeg: s.light[1],
    ...mapSettings(s),
  };
}

// The dropped map as a displacement (scale, mid and the seam fix from the panel) or a colour
// texture; without one, a glTF's base colour texture (MATL), as limn-render draws it.
function mapSettings(s) {
  if (map?.kind === 'displace') {
    const { width, height, values } = map.image;
    return { displace: { map: { width, height, values }, scale: s.displaceScale, mid: s.displaceMid, seamFix: s.seamFix } };
  }
  if (map?.kind === 'texture') return { texture: map.image };
  if (model?.texture) return { texture: model.texture };
  return {};
}
const textureSettings = () => { const m = mapSettings(state); return m.texture ? { texture: m.texture } : {}; };

// Options the runtime refuses fall back to ones it draws; a link that asked for them says so.
function supportedState(s) {
  const out = { ...s };
  const fallback = (key, value, why) => {
    if (asked.has(key)) showError(`fallback-${key}`, `${key}=${s[key]}: ${why}; drawing ${key}=${value} instead`);
    out[key] = value;
  };
  if (out.edgePixels > 0) { const why = refusal({ edgePixels: out.edgePixels }); if (why) fallback('edgePixels', 0, why); }
  if (out.shade !== 'lit') { const why = refusal({ shade: out.shade, ...textureSettings() }); if (why) fallback('shade', 'lit', why); }
  return out;
}

// --- canvas and renderer ------------------------------------------------------------------------
function canvasSize() {
  if (state.size) return state.size;
  const r = devicePixelRatio || 1;
  return [Math.max(1, Math.round(stage.clientWidth * r)), Math.max(1, Math.round(stage.clientHeight * r))];
}

function layoutCanvas() {
  const [w, h] = canvasSize();
  canvas.width = w; canvas.height = h;
  const r = state.size ? 1 : devicePixelRatio || 1;
  canvas.style.width = `${w / r}px`; canvas.style.height = `${h / r}px`;
}

// What needs a new renderer (buffers, pipelines, targets); the rest is set on the one there.
// (View-adaptive tessellation shares points across UV seams unless the shading needs the UVs.)
// The shading's fragment stage is the renderer's (lit and texture have their own).
// A displacement's scale, mid and seam fix are set up with the renderer (its framing, the fixed
// grids' sample UVs), so changing them makes a new one. So are the view-adaptive rates' errors
// and the per-pixel normals' pipelines (the renderer's adaptive options).
const keyOf = (s) => JSON.stringify([canvasSize(), s.samples, s.sampleShading, s.edgePixels, s.tess, s.wire, s.edgePixels > 0 && ['uv', 'texture'].includes(s.shade), surfaceFragmentStage(s.shade), model?.serial, map?.serial,
  s.edgePixels > 0 ? [s.maxError, s.interiorError, s.pixelNormals] : null,
  map?.kind === 'displace' ? [s.displaceScale, s.displaceMid, s.seamFix] : null]);

async function ensureRenderer() {
  const s = supportedState(state);
  const key = keyOf(s);
  if (renderer && key === rendererKey) return renderer;
  renderer?.destroy();
  renderer = null;
  layoutCanvas();
  context.configure({ device: gpu.device, format: 'rgba8unorm', usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_DST, alphaMode: 'opaque' });
  // Created framed (limn-render's hull framing needs the surface samples), then given the view.
  const settings = rendererSettings(s);
  setBusy(true);
  try {
    renderer = await Renderer.create(gpu.device, model.surface, { ...settings, view: viewSpec({ ...s, eye: null }) });
  } finally {
    setBusy(false);
  }
  rendererKey = key;
  return renderer;
}

// One GPU job at a time: a frame, a new renderer (a model dropped while the turntable turns) or
// the benchmark never use a renderer that another is replacing.
let gpuWork = Promise.resolve();
function exclusive(job) {
  const run = gpuWork.then(job, job);
  gpuWork = run.catch(() => {});
  return run;
}

function setBusy(on) { $('busy').hidden = !on; document.body.dataset.busy = on ? '1' : ''; }

// --- drawing: only when something changed -------------------------------------------------------
let dirty = false, drawing = false;
function requestDraw() {
  dirty = true;
  document.body.dataset.idle = '';
  if (!drawing) requestAnimationFrame(drawLoop);
}

async function drawLoop() {
  if (drawing || !model || !gpu) return;
  drawing = true;
  try {
    while (dirty) {
      dirty = false;
      await exclusive(drawOnce);
      if (turntable) { state = orbit(state, 0.5, 0, renderer.camera); dirty = true; scheduleUrl(); }
      if (dirty) await new Promise(requestAnimationFrame);
    }
  } catch (e) {
    showError('render', `drawing failed: ${describe(e)}`);
  } finally {
    drawing = false;
    document.body.dataset.frames = stats.frames;
    if (!dirty) document.body.dataset.idle = '1';
  }
}

async function drawOnce() {
  const r = await ensureRenderer();
  const s = supportedState(state);
  const t0 = performance.now();
  Object.assign(r.s, { shade: s.shade, background: s.background, color: s.color ?? undefined, lightAzimuthDeg: s.light[0], lightElevationDeg: s.light[1] });
  r.setView(viewSpec(s));
  timer.begin();
  r.frame();
  const enc = gpu.device.createCommandEncoder({ label: 'to canvas' });
  enc.copyTextureToTexture({ texture: r.color }, { texture: context.getCurrentTexture() }, [r.s.width, r.s.height]);
  gpu.device.queue.submit([enc.finish()]);
  timer.end();
  const js = performance.now() - t0;
  await gpu.device.queue.onSubmittedWorkDone();
  const wall = performance.now() - t0;
  const gpuMs = await timer.read();
  const triangles = await r.drawnTriangles();
  clearError('render');
  stats.frames++;
  const now = performance.now();
  if (!stats.fpsSince || now - stats.fpsSince > 2000) { stats.fpsSince = now; stats.fpsFrames = 0; }
  stats.fpsFrames++;
  const fps = now > stats.fpsSince ? (1000 * (stats.fpsFrames - 1)) / (now - stats.fpsSince) : 0;
  $('st-tris').textContent = triangles.toLocaleString('en-US');
  $('st-gpu').textContent = gpuMs === null ? (timer.available ? '–' : 'no timestamp queries') : gpuMs.toFixed(2);
  $('st-js').textContent = js.toFixed(2);
  $('st-wall').textContent = wall.toFixed(1);
  $('st-fps').textContent = stats.fpsFrames > 1 ? fps.toFixed(1) : '–';
  $('st-size').textContent = `${r.s.width}×${r.s.height}, ${r.s.samples} sample${r.s.samples > 1 ? 's' : ''}`;
  updateCameraText(s);
  document.body.dataset.frames = stats.frames;
  return { gpuMs, js, wall, triangles };
}

// --- state changes ----------------------------------------------------------------------------
let urlTimer = 0;
// Chromium refuses (with a console warning) more than ~100 history updates in 10 s: coalesce.
function scheduleUrl() {
  if (!urlTimer) urlTimer = setTimeout(writeUrl, 250);
}
function writeUrl() {
  clearTimeout(urlTimer);
  urlTimer = 0;
  const q = toQuery(state, sources);
  const extra = turntable ? `${q ? '&' : ''}turntable=1` : '';
  history.replaceState(null, '', `${location.pathname}?${q}${extra}`);
  document.body.dataset.url = location.search;
}

function commit(next, { immediate = false } = {}) {
  state = next;
  immediate ? writeUrl() : scheduleUrl();
  syncPanel();
  requestDraw();
}

function camera() { return renderer?.camera ?? { eye: [0, 0, 1], target: [0, 0, 0], up: [0, 1, 0] }; }
function updateCameraText(s) {
  $('camera-text').textContent = s.eye ? `eye ${s.eye.join(', ')}  target ${(s.target ?? camera().target.map((x) => +x.toPrecision(6))).join(', ')}` : `view ${s.view.join(', ')} (framed)`;
  const [w, h] = canvasSize();
  $('command').textContent = renderCommand(s, { modelName: model?.name ?? 'MODEL.limn', width: w, height: h, displace: map?.kind === 'displace' && map.name, texture: map?.kind === 'texture' && map.name });
}

// --- loading ------------------------------------------------------------------------------------
let serial = 0;
async function openModel(bytes, name) {
  let surface;
  try {
    surface = loadLimn(new Uint8Array(bytes));
  } catch (e) {
    showError('model', `${name}: ${describe(e)}`);
    return false;
  }
  clearError('model');
  clearErrors('fallback-');
  const previous = model;
  model = { surface, name, serial: ++serial, texture: await materialTexture(surface, name) };
  if (surface.material && !state.color && !asked.has('color')) {
    // limn-render's base colour from MATL (linear factor, drawn as sRGB) unless --color is given.
    const srgb = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055);
    state = { ...state, color: surface.material.baseColorFactor.slice(0, 3).map((c) => +srgb(c).toFixed(4)) };
  }
  $('model-name').textContent = `${name}: ${surface.mesh.vertexCount} control points, depth ${surface.tables.depth}`;
  $('welcome').hidden = true;
  try {
    await exclusive(ensureRenderer);
  } catch (e) {
    showError('model', `${name}: ${describe(e)}`);
    model = previous;
    rendererKey = '';
    return false;
  }
  syncPanel();
  requestDraw();
  return true;
}

// A MATL chunk's base colour texture, decoded by the browser; null (with the reason shown) if it
// cannot be: the geometry is still drawn, in the base colour factor, as limn-render does.
async function materialTexture(surface, name) {
  const m = surface.material;
  if (!m || !m.texture.length || !surface.uvs) return null;
  try {
    return await imagePixels(gpu.device, await createImageBitmap(new Blob([m.texture]), { colorSpaceConversion: 'none', premultiplyAlpha: 'none' }));
  } catch (e) {
    showError('material', `${name}: the base colour texture cannot be decoded (${e.message}); drawing the base colour factor instead`);
    return null;
  }
}

async function fetchBytes(url, what) {
  let response;
  try {
    response = await fetch(url);
  } catch (e) {
    throw new ViewerError(`${what}=${url}: cannot fetch it (${e.message}); is the server running, and does it allow this page to read it?`);
  }
  if (!response.ok) throw new ViewerError(`${what}=${url}: the server answered ${response.status} ${response.statusText}`);
  return response.arrayBuffer();
}

// url: where the map came from (it goes into the page's URL); null for a dropped file.
async function openMap(blob, name, kind, url = null) {
  let image;
  try {
    const bitmap = await createImageBitmap(blob, { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
    image = await imagePixels(gpu.device, bitmap);
    bitmap.close();
  } catch (e) {
    showError('map', `${name}: the browser cannot decode this image (${e.message}); use PNG, JPEG or WebP`);
    return;
  }
  clearError('map');
  const previous = { map, displace: sources.displace, texture: sources.texture };
  map = { name, kind, image, serial: ++serial };
  sources.displace = sources.texture = null;
  sources[kind] = url;
  $('map-name').textContent = `${name}: ${image.width}×${image.height}, as ${kind === 'displace' ? 'displacement' : 'colour'} map`;
  const why = refusal(mapSettings(state));
  if (why) {
    showError('map', `${name} decoded (${image.width}×${image.height}), but it cannot be used: ${why}`);
    ({ map } = previous);
    sources.displace = previous.displace;
    sources.texture = previous.texture;
  } else if (kind === 'texture' && state.shade === 'lit') {
    state = { ...state, shade: 'texture' }; // as limn-render's --texture
  }
  writeUrl();
  syncPanel();
  requestDraw();
}

const baseName = (url) => decodeURIComponent(url.split(/[?#]/)[0].split('/').pop() || url);

function setTurntable(on) {
  turntable = on;
  $('turntable').checked = on;
  writeUrl();
  if (on) requestDraw();
}

// --- files: drop anywhere, or the pickers (files.mjs) ---------------------------------------------
async function openFile(file) {
  if (/\.limn$/i.test(file.name) || !file.type.startsWith('image/')) {
    const bytes = await file.arrayBuffer();
    if (await openModel(bytes, file.name)) {
      sources.model = null; // a local file has no URL to share
      writeUrl();
    }
  } else {
    await openMap(file, file.name, $('map-kind').value);
  }
}


// What the panel (panel.mjs) and ?bench (viewer_bench.mjs) see of the viewer and may change.
const app = {
  get state() { return state; },
  set state(s) { state = s; },
  get model() { return model; },
  get map() { return map; },
  get gpu() { return gpu; },
  get turntable() { return turntable; },
  commit, refusal, supportedState, textureSettings, camera, setTurntable, updateCameraText, canvasSize,
  exclusive, ensureRenderer, drawOnce,
};
const syncPanel = () => syncPanelOf(app);

// --- start ---------------------------------------------------------------------------------------
async function start() {
  $('boot')?.remove();
  buildPanel(app);
  attachFiles(openFile, openMap);
  for (const e of query.errors) showError(`url-${e}`, `in the link: ${e}`);
  try {
    gpu = await requestDevice();
  } catch (e) {
    showError('gpu', describe(e));
    document.body.dataset.ready = '1';
    return;
  }
  $('st-adapter').textContent = gpu.description;
  timer = new GpuTimer(gpu.device);
  gpu.device.lost.then((info) => { if (info.reason !== 'destroyed') showError('gpu', `the WebGPU device was lost: ${info.message || info.reason}; reload the page`); });
  gpu.device.addEventListener('uncapturederror', (e) => showError('gpu-error', `WebGPU error: ${e.error.message}`));
  context = canvas.getContext('webgpu');
  attachControls(canvas, stage, {
    orbit: (dAz, dEl) => commit(orbit(state, dAz, dEl, camera())),
    pan: (dx, dy) => commit(pan(state, dx, dy, camera(), canvas.height)),
    zoom: (f) => commit(zoom(state, f, camera())),
    key: (k) => (k === 'turntable' ? setTurntable(!turntable) : k === 'frame' ? commit(frame(state, camera())) : commit({ ...state, view: [...DEFAULTS.view], eye: null, target: null, up: null })),
    end: () => writeUrl(),
  });
  if (!state.size) {
    let resizeTimer = 0;
    new ResizeObserver(() => { clearTimeout(resizeTimer); resizeTimer = setTimeout(() => model && requestDraw(), 150); }).observe(stage);
  }
  syncPanel();
  if (sources.model) {
    try {
      await openModel(await fetchBytes(sources.model, 'model'), baseName(sources.model));
    } catch (e) {
      showError('model', describe(e));
    }
  } else {
    $('welcome').hidden = false;
  }
  const mapUrl = sources.displace ?? sources.texture;
  if (mapUrl) {
    try {
      const bytes = await fetchBytes(mapUrl, sources.displace ? 'displace' : 'texture');
      await openMap(new Blob([bytes]), baseName(mapUrl), sources.displace ? 'displace' : 'texture', mapUrl);
    } catch (e) {
      showError('map', describe(e));
    }
  }
  document.body.dataset.ready = '1';
  if (query.bench && model) await bench(app, query.bench);
}

start();
