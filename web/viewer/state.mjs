// The viewer's state and its URL: every option is named and means what limn-render's option of
// the same name does (camelCase for --kebab-case: edgePixels is --edge-pixels), so a shared link
// and `limn-render` with the same options show the same view. Pure functions, no DOM: tested in Node.

/** Defaults: limn-render's where the runtime supports them (viewer.mjs turns off what it lacks). */
export const DEFAULTS = Object.freeze({
  view: [-30, 20], eye: null, target: null, up: null, upAxis: 'y', fov: 35, light: [-40, 35],
  shade: 'lit', samples: 4, sampleShading: false, maxError: 0.1, edgePixels: 32, tess: 64, wire: false,
  interiorError: 0, pixelNormals: false,
  size: null, color: null, background: [0.2, 0.2, 0.2],
  displaceScale: 1, displaceMid: 0, seamFix: true,
});

export const SHADE_NAMES = ['lit', 'levels', 'normal', 'uv', 'texture'];

// Numbers in the URL are rounded so that what is drawn is exactly what the URL says: a reloaded
// link draws the same image.
const round = (x, digits) => { const v = +x.toFixed(digits); return Object.is(v, -0) ? 0 : v; };
export const roundAngle = (a) => round(a, 2);
export const roundPoint = (p) => p.map((x) => +x.toPrecision(6)).map((x) => (Object.is(x, -0) ? 0 : x));

class StateError extends Error {}

function list(name, text, n) {
  const parts = text.split(',').map((s) => (s.trim() === '' ? NaN : Number(s)));
  if (parts.length !== n || parts.some((x) => !Number.isFinite(x))) throw new StateError(`${name}=${text}: not ${n} comma-separated numbers`);
  return parts;
}
function number(name, text, lo, hi, integer = false) {
  const v = text.trim() === '' ? NaN : Number(text);
  if (!Number.isFinite(v) || v < lo || v > hi || (integer && !Number.isInteger(v))) {
    throw new StateError(`${name}=${text}: ${integer ? 'an integer' : 'a number'} from ${lo} to ${hi}`);
  }
  return v;
}
function flag(name, text) {
  if (['', '1', 'true', 'on'].includes(text)) return true;
  if (['0', 'false', 'off'].includes(text)) return false;
  throw new StateError(`${name}=${text}: 1 or 0`);
}

/**
 * Parses a query string (URLSearchParams or string). Returns {state, model, displace, texture,
 * bench, turntable, errors}: a bad parameter is reported in `errors` (in words) and keeps its
 * default, so one typo does not lose the rest of a link.
 */
export function parseQuery(query) {
  const p = typeof query === 'string' ? new URLSearchParams(query) : query;
  const state = { ...DEFAULTS };
  const errors = [];
  const take = (name, fn) => {
    if (!p.has(name)) return;
    try { fn(p.get(name)); } catch (e) { if (e instanceof StateError) errors.push(e.message); else throw e; }
  };
  take('view', (t) => {
    const [az, el] = list('view', t, 2);
    if (Math.abs(az) > 360 || Math.abs(el) > 90) throw new StateError(`view=${t}: azimuth -360 to 360, elevation -90 to 90`);
    state.view = [az, el];
  });
  take('eye', (t) => { state.eye = list('eye', t, 3); });
  take('target', (t) => { state.target = list('target', t, 3); });
  take('up', (t) => { state.up = list('up', t, 3); });
  take('upAxis', (t) => { if (t !== 'y' && t !== 'z') throw new StateError(`upAxis=${t}: y or z`); state.upAxis = t; });
  take('fov', (t) => { state.fov = number('fov', t, 1, 170); });
  take('light', (t) => { state.light = list('light', t, 2); });
  take('shade', (t) => { if (!SHADE_NAMES.includes(t)) throw new StateError(`shade=${t}: one of ${SHADE_NAMES.join(', ')}`); state.shade = t; });
  take('samples', (t) => { if (t !== '1' && t !== '4') throw new StateError(`samples=${t}: 1 or 4`); state.samples = +t; });
  take('sampleShading', (t) => { state.sampleShading = flag('sampleShading', t); });
  take('maxError', (t) => { state.maxError = number('maxError', t, 0, 4096); });
  take('edgePixels', (t) => { state.edgePixels = number('edgePixels', t, 0, 4096); });
  take('interiorError', (t) => { state.interiorError = number('interiorError', t, 0, 4096); });
  take('pixelNormals', (t) => { state.pixelNormals = flag('pixelNormals', t); });
  take('tess', (t) => { state.tess = number('tess', t, 1, 4096, true); });
  take('wire', (t) => { state.wire = flag('wire', t); });
  take('size', (t) => {
    const m = /^(\d+)x(\d+)$/.exec(t);
    if (!m || +m[1] < 1 || +m[2] < 1 || +m[1] > 16384 || +m[2] > 16384) throw new StateError(`size=${t}: WIDTHxHEIGHT, each 1 to 16384`);
    state.size = [+m[1], +m[2]];
  });
  take('color', (t) => { state.color = list('color', t, 3); });
  take('background', (t) => { state.background = list('background', t, 3); });
  take('displaceScale', (t) => { state.displaceScale = number('displaceScale', t, -1e6, 1e6); });
  take('displaceMid', (t) => { state.displaceMid = number('displaceMid', t, -1e6, 1e6); });
  take('seamFix', (t) => { state.seamFix = flag('seamFix', t); });
  if ((state.target || state.up) && !state.eye) {
    errors.push('target and up describe an explicit camera: give eye too (ignored)');
    state.target = state.up = null;
  }
  let bench = 0;
  take('bench', (t) => { bench = number('bench', t, 1, 100000, true); });
  return {
    state, errors, bench,
    model: p.get('model') || null, displace: p.get('displace') || null, texture: p.get('texture') || null,
    turntable: p.has('turntable') && p.get('turntable') !== '0',
  };
}

const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

/** The query string of a state: the model, then every option that differs from the defaults. */
export function toQuery(state, { model, displace, texture } = {}) {
  const q = [];
  const put = (k, v) => q.push(`${k}=${encodeURIComponent(v).replace(/%2C/g, ',').replace(/%2F/g, '/')}`);
  if (model) put('model', model);
  if (state.eye) {
    put('eye', roundPoint(state.eye).join(','));
    if (state.target) put('target', roundPoint(state.target).join(','));
    if (state.up) put('up', roundPoint(state.up).join(','));
  } else {
    put('view', state.view.map(roundAngle).join(','));
  }
  for (const k of ['upAxis', 'fov', 'light', 'shade', 'samples', 'sampleShading', 'maxError', 'edgePixels', 'interiorError', 'pixelNormals', 'tess', 'wire', 'color', 'background']) {
    if (state[k] !== null && !same(state[k], DEFAULTS[k])) put(k, typeof state[k] === 'boolean' ? (state[k] ? 1 : 0) : Array.isArray(state[k]) ? state[k].join(',') : state[k]);
  }
  if (state.size) put('size', `${state.size[0]}x${state.size[1]}`);
  if (displace) {
    put('displace', displace);
    for (const k of ['displaceScale', 'displaceMid', 'seamFix']) if (!same(state[k], DEFAULTS[k])) put(k, typeof state[k] === 'boolean' ? (state[k] ? 1 : 0) : state[k]);
  }
  if (texture) put('texture', texture);
  return q.join('&');
}

/** The limn-render command line that draws this view (the options limn-render has). */
export function renderCommand(state, { modelName = 'MODEL.limn', width, height, displace, texture } = {}) {
  const a = ['limn-render', modelName, '-o', 'view.png', '--size', `${width}x${height}`];
  if (state.eye) {
    a.push('--eye', roundPoint(state.eye).join(','));
    if (state.target) a.push('--target', roundPoint(state.target).join(','));
    if (state.up) a.push('--up', roundPoint(state.up).join(','));
  } else {
    a.push('--view', state.view.map(roundAngle).join(','));
  }
  if (state.upAxis !== 'y') a.push('--up-axis', state.upAxis);
  if (state.fov !== DEFAULTS.fov) a.push('--fov', String(state.fov));
  if (!same(state.light, DEFAULTS.light)) a.push('--light', state.light.join(','));
  a.push('--shade', state.shade, '--samples', String(state.samples));
  // --max-error only where it means something: the view-adaptive tessellation (edge pixels > 0).
  if (state.edgePixels > 0) a.push('--max-error', String(state.maxError));
  a.push('--edge-pixels', String(state.edgePixels), '--tess', String(state.tess));
  // Per-pixel normals and the coarser interior, as --max-error: view-adaptive only.
  if (state.edgePixels > 0 && state.interiorError > 0) a.push('--interior-error', String(state.interiorError));
  if (state.edgePixels > 0 && state.pixelNormals) a.push('--pixel-normals');
  if (state.sampleShading) a.push('--sample-shading');
  if (state.wire) a.push('--wire-triangles');
  if (state.color) a.push('--color', state.color.join(','));
  if (!same(state.background, DEFAULTS.background)) a.push('--background', state.background.join(','));
  if (displace) {
    a.push('--displace', displace, '--displace-scale', String(state.displaceScale), '--displace-mid', String(state.displaceMid));
    if (!state.seamFix) a.push('--no-seam-fix');
  }
  if (texture) a.push('--texture', texture);
  return a.map((x) => (/^[\w.,\-/=:%]+$/.test(x) ? x : `'${x.replace(/'/g, "'\\''")}'`)).join(' ');
}
