// Test helpers: Debian's chromium, headless, driven by playwright-core (scripts/setup.sh --tests
// installs both; Playwright's browser download is never used). WebGPU runs there on SwiftShader
// (docs: shared web.md): --enable-unsafe-webgpu --enable-features=Vulkan --use-angle=vulkan
// --use-vulkan=swiftshader; the other flags keep Chromium off the network, which is closed here.
import { existsSync, mkdirSync, symlinkSync } from 'node:fs';
import { spawn } from 'node:child_process';
import { join } from 'node:path';
import { repo, scratch } from '../../test/support.mjs';

export const CHROMIUM = process.env.LIMN_CHROMIUM ?? '/usr/bin/chromium';
export const FLAGS = [
  '--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-angle=vulkan', '--use-vulkan=swiftshader',
  '--no-sandbox', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync',
];

export async function launch() {
  if (!existsSync(CHROMIUM)) throw new Error(`${CHROMIUM} is missing: run scripts/setup.sh --tests (Debian's chromium)`);
  let chromium;
  try {
    ({ chromium } = await import('playwright-core'));
  } catch {
    throw new Error('playwright-core is missing in web/viewer/node_modules: run scripts/setup.sh --tests');
  }
  return chromium.launch({ executablePath: CHROMIUM, args: FLAGS });
}

/** A page that records console errors and warnings (and uncaught exceptions) in `problems`. */
export async function newPage(browser, viewport = { width: 700, height: 500 }) {
  const page = await browser.newPage({ viewport });
  page.problems = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') page.problems.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => page.problems.push(`exception: ${e.message}`));
  return page;
}

/** Waits until the page has loaded, drawn at least `frames` frames, and has nothing left to draw. */
export async function settled(page, frames = 1, timeout = 120000) {
  await page.waitForFunction((n) => {
    const d = document.body.dataset;
    return d.ready === '1' && !d.busy && d.idle === '1' && +(d.frames ?? 0) >= n;
  }, frames, { timeout });
}

export const frames = (page) => page.evaluate(() => +(document.body.dataset.frames ?? 0));
export const errorText = (page) => page.evaluate(() => document.getElementById('errors').textContent);

/**
 * Starts `limn-view DIR` over a scratch folder holding the viewer, the runtime and `models`
 * (name -> path), as out/web does; returns { url, stop }.
 */
export async function serveModels(models) {
  const root = join(scratch, `site-${Object.keys(models).join('-')}`);
  mkdirSync(join(root, 'models'), { recursive: true });
  for (const d of ['viewer', 'src', 'shaders']) if (!existsSync(join(root, d))) symlinkSync(join(repo, 'web', d), join(root, d));
  for (const [name, path] of Object.entries(models)) if (!existsSync(join(root, 'models', name))) symlinkSync(path, join(root, 'models', name));
  return startView([root]);
}

/** Runs limn-view with `args`; resolves with the URL it prints, or rejects with its stderr. */
export function startView(args) {
  const child = spawn(process.execPath, [join(repo, 'web/bin/limn-view.mjs'), ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
  return new Promise((resolve, reject) => {
    let out = '', err = '';
    child.stdout.on('data', (d) => {
      out += d;
      if (out.includes('\n')) resolve({ url: out.trim(), child, stop: () => child.kill('SIGTERM') });
    });
    child.stderr.on('data', (d) => { err += d; });
    child.on('exit', (code) => reject(Object.assign(new Error(`limn-view exited ${code}: ${err}`), { code, stderr: err })));
  });
}
