// Mouse, touch and keyboard on the view. Left drag (one finger) orbits; right or middle drag,
// or shift+drag, pans; the wheel and a two-finger pinch zoom (the pinch's midpoint pans).
// Keys: arrows orbit (with shift: pan), + and - zoom, F frame, R or Home reset, T turntable.
// `on` receives {orbit(dAz, dEl), pan(dx, dy), zoom(factor), key(name), end()}; distances in
// canvas pixels.
const DEG_PER_PIXEL = 0.4;

export function attachControls(canvas, stage, on) {
  const pointers = new Map();
  let mode = null, pinch = null;
  const scale = () => canvas.width / Math.max(canvas.clientWidth, 1);
  const midpoint = () => {
    const p = [...pointers.values()];
    return { x: (p[0].x + p[1].x) / 2, y: (p[0].y + p[1].y) / 2, d: Math.hypot(p[0].x - p[1].x, p[0].y - p[1].y) };
  };

  canvas.addEventListener('pointerdown', (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
    stage.focus({ preventScroll: true });
    if (pointers.size === 2) { mode = 'pinch'; pinch = midpoint(); }
    else if (pointers.size === 1) mode = e.button === 0 && !e.shiftKey ? 'orbit' : 'pan';
    canvas.style.cursor = 'grabbing';
    e.preventDefault();
  });
  canvas.addEventListener('pointermove', (e) => {
    const p = pointers.get(e.pointerId);
    if (!p) return;
    const dx = e.clientX - p.x, dy = e.clientY - p.y;
    p.x = e.clientX; p.y = e.clientY;
    if (mode === 'orbit') on.orbit(-dx * DEG_PER_PIXEL, dy * DEG_PER_PIXEL);
    else if (mode === 'pan') on.pan(dx * scale(), dy * scale());
    else if (mode === 'pinch' && pointers.size === 2) {
      const m = midpoint();
      if (pinch.d > 0 && m.d > 0) on.zoom(pinch.d / m.d);
      on.pan((m.x - pinch.x) * scale(), (m.y - pinch.y) * scale());
      pinch = m;
    }
  });
  const up = (e) => {
    if (!pointers.delete(e.pointerId)) return;
    if (pointers.size === 0) { mode = null; canvas.style.cursor = ''; on.end(); }
    else if (pointers.size === 1) mode = 'orbit';
  };
  canvas.addEventListener('pointerup', up);
  canvas.addEventListener('pointercancel', up);
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const lines = e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1;
    on.zoom(Math.exp(Math.max(-1, Math.min(1, e.deltaY * lines * 0.0015))));
    on.end();
  }, { passive: false });

  stage.addEventListener('keydown', (e) => {
    if (e.target !== stage || e.ctrlKey || e.metaKey || e.altKey) return;
    const step = 5, px = 20;
    const actions = {
      ArrowLeft: () => (e.shiftKey ? on.pan(-px, 0) : on.orbit(step, 0)),
      ArrowRight: () => (e.shiftKey ? on.pan(px, 0) : on.orbit(-step, 0)),
      ArrowUp: () => (e.shiftKey ? on.pan(0, -px) : on.orbit(0, -step)),
      ArrowDown: () => (e.shiftKey ? on.pan(0, px) : on.orbit(0, step)),
      '+': () => on.zoom(0.9), '=': () => on.zoom(0.9), '-': () => on.zoom(1 / 0.9), _: () => on.zoom(1 / 0.9),
      f: () => on.key('frame'), F: () => on.key('frame'), r: () => on.key('reset'), R: () => on.key('reset'),
      Home: () => on.key('reset'), t: () => on.key('turntable'), T: () => on.key('turntable'),
    };
    const act = actions[e.key];
    if (!act) return;
    e.preventDefault();
    act();
    on.end();
  });
}
