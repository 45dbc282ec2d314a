#!/usr/bin/env node
// The viewer's frame times in headless Chromium (WebGPU on SwiftShader here), for the paper's
// demo sphere (tests/support/paper_sphere.h: 16 segments x 16 rings, fans at the poles) at
// 1280x720 from eye (0, 12, 22), depths 1-6: the page's ?bench=N mode prints one JSON line per
// configuration (fixed grids, view-adaptive) on the console; this prints them on stdout.
// Usage: node web/bench/viewer.mjs [FRAMES] [DEPTHS]   (default 5 frames, depths 1,2,3,4,5,6)
// Needs build/ (limn-classify, limn-tables; LIMN_BUILD_DIR) and scripts/setup.sh --tests.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createRequire } from 'node:module';

const repo = fileURLToPath(new URL('../../', import.meta.url));
const bin = join(process.env.LIMN_BUILD_DIR ?? join(repo, 'build'), 'bin');
const frames = +(process.argv[2] ?? 5);
const depths = (process.argv[3] ?? '1,2,3,4,5,6').split(',').map(Number);
const require = createRequire(join(repo, 'web/viewer/package.json'));
const { chromium } = require('playwright-core');
const { FLAGS, CHROMIUM, startView } = await import('../viewer/test/browser.mjs');

function paperSphereObj() {
  const S = 16, R = 16, v = ['v 0 1 0'], f = [];
  for (let i = 1; i < R; i++) {
    for (let j = 0; j < S; j++) {
      const th = (Math.PI * i) / R, ph = (2 * Math.PI * j) / S;
      v.push(`v ${Math.sin(th) * Math.cos(ph)} ${Math.cos(th)} ${-Math.sin(th) * Math.sin(ph)}`);
    }
  }
  v.push('v 0 -1 0');
  const idx = (i, j) => 1 + (i - 1) * S + (j % S) + 1;
  for (let j = 0; j < S; j++) f.push(`f 1 ${idx(1, j)} ${idx(1, j + 1)}`);
  for (let i = 1; i + 1 < R; i++) for (let j = 0; j < S; j++) f.push(`f ${idx(i, j)} ${idx(i + 1, j)} ${idx(i + 1, j + 1)} ${idx(i, j + 1)}`);
  for (let j = 0; j < S; j++) f.push(`f ${idx(R - 1, j)} ${v.length} ${idx(R - 1, j + 1)}`);
  return `${v.join('\n')}\n${f.join('\n')}\n`;
}

const dir = mkdtempSync(join(tmpdir(), 'limn-viewer-bench-'));
const site = join(dir, 'site');
try {
  execFileSync('mkdir', ['-p', join(site, 'models')]);
  for (const d of ['viewer', 'src', 'shaders']) execFileSync('ln', ['-s', join(repo, 'web', d), join(site, d)]);
  writeFileSync(join(dir, 'sphere.obj'), paperSphereObj());
  const classified = execFileSync(join(bin, 'limn-classify'), [join(dir, 'sphere.obj'), '-o', '-'], { maxBuffer: 1 << 30 });
  for (const d of depths) {
    writeFileSync(join(site, 'models', `paper_sphere_d${d}.limn`), execFileSync(join(bin, 'limn-tables'), ['--depth', String(d), '-', '-o', '-'], { input: classified, maxBuffer: 1 << 30 }));
  }
  const view = await startView([site]);
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: FLAGS });
  try {
    for (const d of depths) {
      const page = await browser.newPage({ viewport: { width: 1600, height: 800 } });
      const done = new Promise((resolve) => page.on('console', (m) => {
        const text = m.text();
        if (text.startsWith('{')) process.stdout.write(`${text}\n`);
        else if (text.startsWith('limn-viewer bench: done')) resolve();
        else if (m.type() === 'error' || m.type() === 'warning') process.stderr.write(`depth ${d}: ${text}\n`);
      }));
      await page.goto(`${view.url}viewer/?model=../models/paper_sphere_d${d}.limn&eye=0,12,22&target=0,0,0&size=1280x720&bench=${frames}`);
      await Promise.race([done, page.waitForFunction(() => document.getElementById('errors').textContent !== '', null, { timeout: 0 })
        .then(async () => process.stderr.write(`depth ${d}: ${await page.locator('#errors').textContent()}\n`))]);
      await page.close();
    }
  } finally {
    await browser.close();
    view.stop();
  }
} finally {
  rmSync(dir, { recursive: true, force: true });
}
