// The WGSL that web/tools/gen-shaders.mjs generates from limn's GLSL (web/shaders/, one file per
// shader, named after it: surface.vert -> surface_vert.wgsl). Read from the package's own folder:
// with fetch in a browser, from the file system in Node; no bundler needed.

/** The WGSL text of one shader, by its GLSL file name ('surface.vert'). */
export async function loadShader(name) {
  const url = new URL(`../shaders/${name.replace('.', '_')}.wgsl`, import.meta.url);
  if (url.protocol === 'file:') {
    const { readFile } = await import('node:fs/promises');
    return readFile(url, 'utf8');
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return response.text();
}

/** Shader modules by GLSL name, each compiled once per device. */
export class ShaderCache {
  constructor(device) {
    this.device = device;
    this.modules = new Map();
  }

  async module(name) {
    let m = this.modules.get(name);
    if (!m) {
      m = this.device.createShaderModule({ label: name, code: await loadShader(name) });
      this.modules.set(name, m);
    }
    return m;
  }
}

// An explicit bind group layout for group 0 of a generated shader, from its declarations (an
// 'auto' layout leaves out what the entry point does not use, and limn binds by position).
export function groupLayout(device, wgsl, visibility) {
  const entries = [];
  for (const m of wgsl.matchAll(/@group\(0\) @binding\((\d+)\)\s*\nvar<storage, (read|read_write)>/g)) {
    entries.push({ binding: Number(m[1]), visibility, buffer: { type: m[2] === 'read' ? 'read-only-storage' : 'storage' } });
  }
  return device.createBindGroupLayout({ entries: entries.sort((a, b) => a.binding - b.binding) });
}
