// The viewer's panel: its controls built and wired to the viewer's state (`app`, viewer.mjs), and
// set from the state; a control the runtime refuses is disabled with the reason in words.
import { DEFAULTS, SHADE_NAMES } from './state.mjs';
import { frame } from './orbit.mjs';

const $ = (id) => document.getElementById(id);
// The view-adaptive segment length to return to from the fixed grids.
let lastEdgePixels = DEFAULTS.edgePixels;

export function setEnabled(input, why) {
  input.disabled = !!why;
  const label = input.closest('label');
  if (!label) return;
  label.classList.toggle('disabled', !!why);
  label.dataset.help ??= label.title; // the control's own help comes back when it is enabled
  label.title = why ?? label.dataset.help;
  let note = label.querySelector('.why');
  if (why && !note) note = label.appendChild(Object.assign(document.createElement('span'), { className: 'why' }));
  if (note) note.textContent = why ?? '';
  if (note && !why) note.remove();
}

export function buildPanel(app) {
  const shade = $('shade');
  for (const name of SHADE_NAMES) {
    const label = document.createElement('label');
    label.className = 'opt';
    label.innerHTML = `<input type="radio" name="shade" value="${name}"> ${name}`;
    shade.append(label);
    label.firstChild.addEventListener('change', () => app.commit({ ...app.state, shade: name }));
  }
  for (const t of [1, 2, 4, 8, 16, 32, 64, 128, 256]) $('tess').append(new Option(String(t), String(t)));
  $('tess').addEventListener('change', (e) => app.commit({ ...app.state, tess: +e.target.value }));
  $('samples').addEventListener('change', (e) => app.commit({ ...app.state, samples: +e.target.value }));
  $('sampleShading').addEventListener('change', (e) => app.commit({ ...app.state, sampleShading: e.target.checked }));
  $('wire').addEventListener('change', (e) => app.commit({ ...app.state, wire: e.target.checked }));
  $('mode-fixed').addEventListener('change', () => app.commit({ ...app.state, edgePixels: 0 }));
  $('mode-adaptive').addEventListener('change', () => app.commit({ ...app.state, edgePixels: lastEdgePixels }));
  $('maxError').addEventListener('change', (e) => {
    const v = +e.target.value;
    if (Number.isFinite(v) && v >= 0 && v <= 4096) app.commit({ ...app.state, maxError: v });
  });
  $('edgePixels').addEventListener('change', (e) => {
    const v = +e.target.value;
    if (Number.isFinite(v) && v > 0 && v <= 4096) { lastEdgePixels = v; app.commit({ ...app.state, edgePixels: v }); }
  });
  $('interiorError').addEventListener('change', (e) => {
    const v = +e.target.value;
    if (Number.isFinite(v) && v >= 0 && v <= 4096) app.commit({ ...app.state, interiorError: v });
  });
  $('pixelNormals').addEventListener('change', (e) => app.commit({ ...app.state, pixelNormals: e.target.checked }));
  for (const k of ['displaceScale', 'displaceMid']) {
    $(k).addEventListener('change', (e) => { const v = +e.target.value; if (Number.isFinite(v)) app.commit({ ...app.state, [k]: v }); });
  }
  $('seamFix').addEventListener('change', (e) => app.commit({ ...app.state, seamFix: e.target.checked }));
  $('reset').addEventListener('click', () => app.commit({ ...app.state, view: [...DEFAULTS.view], eye: null, target: null, up: null }, { immediate: true }));
  $('frame').addEventListener('click', () => app.commit(frame(app.state, app.camera()), { immediate: true }));
  $('turntable').addEventListener('change', (e) => app.setTurntable(e.target.checked));
}


export function syncPanel(app) {
  const s = app.supportedState(app.state);
  for (const input of $('shade').querySelectorAll('input')) {
    input.checked = input.value === s.shade;
    setEnabled(input, input.value === 'lit' ? null : app.refusal({ shade: input.value, ...app.textureSettings() }));
  }
  $('samples').value = String(s.samples);
  $('sampleShading').checked = s.sampleShading;
  setEnabled($('sampleShading'), s.samples === 1 ? 'with 4 samples only' : app.refusal({ sampleShading: true }));
  $('wire').checked = s.wire;
  if (s.edgePixels > 0) lastEdgePixels = s.edgePixels;
  $('mode-fixed').checked = s.edgePixels === 0;
  $('mode-adaptive').checked = s.edgePixels > 0;
  const adaptiveWhy = app.refusal({ edgePixels: lastEdgePixels });
  setEnabled($('mode-adaptive'), adaptiveWhy);
  $('edgePixels').value = String(lastEdgePixels);
  setEnabled($('edgePixels'), adaptiveWhy);
  $('maxError').value = String(s.maxError);
  setEnabled($('maxError'), adaptiveWhy);
  $('interiorError').value = String(s.interiorError);
  setEnabled($('interiorError'), adaptiveWhy);
  // The runtime draws per-pixel normals where limn-render does (renderer.mjs); elsewhere the
  // option draws as without, so the box says why instead of looking as if it did something
  // (in words that name no other control: a label's text is how a control is found).
  $('pixelNormals').checked = s.pixelNormals;
  setEnabled($('pixelNormals'), s.edgePixels === 0 ? 'not with the fixed grids' : s.shade !== 'lit' ? 'not with this shading mode'
    : s.wire ? 'not with the wireframe overlay' : app.map?.kind === 'displace' ? 'not with a displacement map' : adaptiveWhy);
  if (![...$('tess').options].some((o) => +o.value === s.tess)) $('tess').append(new Option(String(s.tess), String(s.tess)));
  $('tess').value = String(s.tess);
  $('displaceScale').value = String(s.displaceScale);
  $('displaceMid').value = String(s.displaceMid);
  $('seamFix').checked = s.seamFix;
  const displaceWhy = app.map?.kind !== 'displace' ? 'drop a height map image on the page first' : null;
  for (const k of ['displaceScale', 'displaceMid', 'seamFix']) setEnabled($(k), displaceWhy);
  $('turntable').checked = app.turntable;
  app.updateCameraText(s);
}
