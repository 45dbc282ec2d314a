// Image comparison of the criterion: of the covered pixels (either image differs from
// the background), the fraction whose largest channel difference exceeds 8/255.
import { readFileSync } from 'node:fs';
import { decodePng } from '../src/png.mjs';

export function compareImages(a, b, background = [51, 51, 51]) {
  if (a.width !== b.width || a.height !== b.height) throw new Error(`sizes differ: ${a.width}x${a.height} and ${b.width}x${b.height}`);
  let covered = 0, off = 0, worst = 0;
  for (let i = 0; i < a.width * a.height; i++) {
    let bgA = true, bgB = true, d = 0;
    for (let c = 0; c < 3; c++) {
      bgA &&= a.rgba[4 * i + c] === background[c];
      bgB &&= b.rgba[4 * i + c] === background[c];
      d = Math.max(d, Math.abs(a.rgba[4 * i + c] - b.rgba[4 * i + c]));
    }
    if (bgA && bgB) continue;
    covered++;
    if (d > 8) off++;
    worst = Math.max(worst, d);
  }
  return { covered, off, fraction: covered ? off / covered : 0, worst };
}

if (process.argv[1]?.endsWith('compare.mjs')) {
  const [x, y] = process.argv.slice(2).map((p) => decodePng(readFileSync(p)));
  console.log(JSON.stringify(compareImages(x, y)));
}
