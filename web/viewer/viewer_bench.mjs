// The viewer's ?bench=N: frame times of the fixed grids and the view-adaptive tessellation on the
// loaded model, one JSON line each on the console (web/bench/viewer.mjs reads them).
import { DEFAULTS } from './state.mjs';

export async function bench(app, frames) {
  const median = (a) => { const b = [...a].sort((x, y) => x - y); return b.length ? b[b.length >> 1] : null; };
  const configs = [{ tessellation: 'fixed', edgePixels: 0 }, { tessellation: 'adaptive', edgePixels: app.state.edgePixels > 0 ? app.state.edgePixels : DEFAULTS.edgePixels }];
  for (const c of configs) {
    const line = { bench: 'limn-viewer', model: app.model.name, depth: app.model.surface.tables.depth, tessellation: c.tessellation, edge_pixels: c.edgePixels, max_error: c.edgePixels > 0 ? app.state.maxError : null,
      interior_error: c.edgePixels > 0 ? app.state.interiorError : null, pixel_normals: c.edgePixels > 0 ? app.state.pixelNormals : null, tess: app.state.tess, samples: app.state.samples, size: app.canvasSize(), frames };
    const why = app.refusal({ edgePixels: c.edgePixels });
    if (why) { console.log(JSON.stringify({ ...line, unsupported: why })); continue; }
    app.state = { ...app.state, edgePixels: c.edgePixels };
    await app.exclusive(app.ensureRenderer);
    await app.exclusive(app.drawOnce); // pipelines and first uploads
    const t = { gpu: [], js: [], wall: [] };
    for (let f = 0; f < frames; f++) {
      const r = await app.exclusive(app.drawOnce);
      if (r.gpuMs !== null) t.gpu.push(r.gpuMs);
      t.js.push(r.js);
      t.wall.push(r.wall);
      t.triangles = r.triangles;
    }
    const fix = (x) => (x === null ? null : +x.toFixed(3));
    console.log(JSON.stringify({ ...line, triangles: t.triangles, gpu_ms: fix(median(t.gpu)), js_ms: fix(median(t.js)), wall_ms: fix(median(t.wall)), adapter: app.gpu.description }));
  }
  console.log('limn-viewer bench: done');
}
