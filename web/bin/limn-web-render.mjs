#!/usr/bin/env node
// limn-web-render: renders a .limn container with limn's passes on WebGPU (Dawn for Node), with
// limn-render's option names for what it supports. Exit codes as limn's tools: 0 ok, 1 bad input,
// 2 usage, 3 missing capability (no WebGPU adapter, or a feature not supported here).
import { loadLimn } from '../src/chunks.mjs';
import { LimnError } from '../src/container.mjs';
import { Renderer, SHADES } from '../src/renderer.mjs';
import { encodePng } from '../src/png.mjs';
import { encodePly } from '../src/ply.mjs';
import { requestNodeDevice, watchDevice } from '../src/node_device.mjs';
import { displayName, isStreamPath, planOutput, readInput, removeOutputsOnSignals, writeOutputs, writeStdout } from '../src/node_io.mjs';
import { GpuTimer } from '../src/gpu_timer.mjs';
import { readImageFile, decodePngImage, heightMap } from '../src/node_image.mjs';

const TOOL = 'limn-web-render';
const HELP = `usage: ${TOOL} [options] [IN.limn] [-o OUT.png] [--mesh-out FILE.ply]
Renders a .limn container (limn-classify | limn-tables [| limn-seams]) with limn's own passes on
WebGPU: per level the face-, edge- and vertex-point compute passes, the limit points, the
view-adaptive tessellation's passes (cull, rates, counts, scan, emit) or the fixed grids, and the
draw that evaluates the surface in the vertex stage (paper 000). The options are limn-render's;
what is not listed is not supported here. IN.limn: - (the default) is standard input.
  -o FILE                 the PNG to write (RGB, 8 bits); - (the default without --bench or
                          --mesh-out) for standard output; a device or pipe is written in
                          place, a symbolic link through to the file it names
  --mesh-out FILE         write the triangles as drawn, as limn-render's --mesh-out writes them
                          (PLY: positions, normals, ptex u v, the texture UV s t, and which
                          vertices are approximate); - for standard output; without -o, no image
  --mesh-ascii            write the --mesh-out PLY as ASCII (default binary little-endian)
  --size WxH              image size (default 1024x768)
  --view AZ,EL            auto-framed camera: azimuth, elevation in degrees (default -30,20)
  --eye X,Y,Z             explicit camera position (with --target, default the box centre,
                          and --up, default the world's up)
  --target X,Y,Z
  --up X,Y,Z
  --up-axis y|z           the world's up axis (default y)
  --fov DEG               vertical field of view (default 35)
  --light AZ,EL           key light relative to the camera (default -40,35)
  --samples 1|4           MSAA samples per pixel (default 4, as limn-render's)
  --sample-shading        shade each sample on its own (with --samples 4)
  --shade MODE            lit, normal, uv, levels, texture (default lit; texture with --texture
                          or a MATL chunk's base colour texture)
  --color R,G,B           base colour, sRGB 0..1 (default a MATL chunk's, else 0.8,0.8,0.8)
  --texture MAP           colour texture (PNG) [default: the MATL chunk's base colour texture]
  --displace MAP          displace the subdivision surface along its normal by a height map
                          (PNG; channel 0), sampled bilinearly with wrap-around at the mesh UVs;
                          the seam UVs from the SEAM chunk (limn-seams), else computed
  --displace-scale S|P%   world units per unit of map value, or P% of the control mesh's
                          bounding-box diagonal (default 1)
  --displace-mid M        the map value meaning zero (default 0)
  --no-seam-fix           sample the map with each face's own UV only (the cracks that the seam
                          fix of paper 000, 4.5 removes)
  --background R,G,B      sRGB 0..1 (default 0.2,0.2,0.2)
  --tess N                most segments per patch edge (default 64)
  --max-error PX          view-adaptive: each patch edge gets the fewest segments whose chords
                          stay within PX pixels of the surface (default 0.1); 0: segments of
                          about --edge-pixels
  --interior-error PX     view-adaptive: the --max-error allowed where an edge faces the eye
                          (every sample's normal within 70 degrees of the view ray), where the
                          error moves no outline, only where the shading lands; 0: --max-error
                          everywhere (docs/adaptive.md, per-pixel normals)
  --pixel-normals         view-adaptive, --shade lit: shade with the limit surface's normal at
                          each pixel (evaluated at the triangle's interpolated parameters)
                          instead of normals interpolated across the triangle; not with --wire,
                          --displace or --mesh-out (those draw as without)
  --edge-pixels P         view-adaptive: segments of at most P pixels (default 32); 0: the fixed
                          grids of 2^(depth-l) segments per level-l patch side
  --wire                  overlay the patch and face outlines (drawn on the fixed grids)
  --wire-triangles        overlay the edges of every triangle drawn (view-adaptive: the rates
                          this view chose)
  --bench N               render N frames after 3 warm-up ones, print limn-render's --bench
                          JSON fields on stdout (gpu_ms.total from timestamp queries, null
                          without them; cpu_ms the host's frame: record, submit, wait) and
                          js_ms, the JavaScript of the frame's recording and submission
  -q, --quiet             silence limn's warnings, as limn-render's -q (Dawn's own notes about
                          the adapter's limits are Dawn's, printed by it)
  --help, --version
Smooth face-varying UVs (TAGS fvar other than "all") are drawn, and displaced, from the
container's FVSF chunk (limn-tables writes it). Not supported here yet: BLND (blending
surfaces); images other than PNG; --mesh-out other than PLY.
Exit codes: 0 ok, 1 bad input, 2 usage, 3 missing capability.
`;

class Usage extends Error {}

// limn-render's real-valued options (lib/base/cli.cpp, Parser::real): the same words and exit
// code. Its std::from_chars takes a plain decimal or exponent form only (no '+', no spaces, no
// hex), and a value out of double's range (1e400, 1e-400) is "not a number" there.
function real(opt, v, lo, hi, metavar) {
  if (v === '') throw new Usage(`${opt}: the value is empty; give ${metavar} (see --help)`);
  let x = /^-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(v) ? Number(v) : NaN;
  if (x === 0 && /[1-9]/.test(v.replace(/[eE].*/, ''))) x = NaN; // underflow
  if (!Number.isFinite(x)) throw new Usage(`${opt}: '${v}' is not a number (see --help)`);
  if (x < lo || x > hi) throw new Usage(`${opt}: ${v} is out of range ${lo} to ${hi} (see --help)`);
  return x;
}

function numbers(opt, v, n) {
  const parts = v.split(',').map(Number);
  if (parts.length !== n || parts.some((x) => !Number.isFinite(x))) throw new Usage(`${opt}: '${v}' is not ${n} comma-separated numbers`);
  return parts;
}

function parseArgs(argv) {
  const o = { settings: { view: {}, samples: 4, width: 1024, height: 768, shade: 'lit', edgePixels: 32, maxError: 0.1, tess: 64 }, bench: 0 };
  const s = o.settings;
  let onlyPositionals = false;
  const given = new Set();
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    // As limn-render's: after --, every argument is a file ('-- -x.limn'); - alone is standard
    // input, a file named - is ./-.
    if (!onlyPositionals && a === '--') { onlyPositionals = true; continue; }
    if (onlyPositionals || a === '-' || !a.startsWith('-')) {
      if (a === '') throw new Usage('an empty argument where IN.limn goes (use - for standard input)');
      if (o.input !== undefined) throw new Usage(`unexpected argument '${a}' (see --help)`);
      o.input = a;
      continue;
    }
    const value = () => {
      if (i + 1 >= argv.length) throw new Usage(`${a} needs a value`);
      // As limn-render's: an option given twice is a mistake, not "the last one wins" (-o a -o b).
      const name = a === '-o' ? '--output' : a;
      if (given.has(name)) throw new Usage(`${name} given more than once (see --help)`);
      given.add(name);
      return argv[++i];
    };
    switch (a) {
      case '--help': case '-h': o.help = true; break;
      case '--version': o.version = true; break;
      case '-q': case '--quiet': o.quiet = true; break;
      case '-o': case '--output': o.output = value(); break;
      case '--mesh-out': o.meshOut = value(); break;
      case '--mesh-ascii': o.meshAscii = true; break;
      case '--size': {
        const m = /^(\d+)x(\d+)$/.exec(value());
        if (!m || +m[1] < 1 || +m[2] < 1 || +m[1] > 16384 || +m[2] > 16384) throw new Usage(`--size: '${argv[i]}' is not WIDTHxHEIGHT with each 1 to 16384`);
        s.width = +m[1]; s.height = +m[2];
        break;
      }
      case '--view': { const [az, el] = numbers(a, value(), 2); s.view.azimuthDeg = az; s.view.elevationDeg = el; o.viewGiven = true; break; }
      case '--eye': s.view.eye = numbers(a, value(), 3); break;
      case '--target': s.view.target = numbers(a, value(), 3); break;
      case '--up': s.view.up = numbers(a, value(), 3); break;
      case '--up-axis': { const v = value(); if (v !== 'y' && v !== 'z') throw new Usage('--up-axis: y or z'); s.view.zUp = v === 'z'; break; }
      case '--fov': { const [f] = numbers(a, value(), 1); if (f < 1 || f > 170) throw new Usage('--fov: 1 to 170'); s.view.fovDeg = f; break; }
      case '--light': { const [az, el] = numbers(a, value(), 2); s.lightAzimuthDeg = az; s.lightElevationDeg = el; break; }
      case '--samples': { const v = value(); if (v !== '1' && v !== '4') throw new Usage(`--samples: '${v}' is not 1 or 4 (the MSAA counts WebGPU offers)`); s.samples = +v; break; }
      case '--sample-shading': s.sampleShading = true; break;
      case '--shade': { const v = value(); if (!(v in SHADES)) throw new Usage(`--shade: '${v}' is not one of ${Object.keys(SHADES).join(', ')}`); s.shade = v; break; }
      case '--color': s.color = numbers(a, value(), 3); break;
      case '--background': s.background = numbers(a, value(), 3); break;
      case '--tess': { const [t] = numbers(a, value(), 1); if (!Number.isInteger(t) || t < 1 || t > 4096) throw new Usage('--tess: an integer from 1 to 4096'); s.tess = t; break; }
      case '--max-error': s.maxError = real(a, value(), 0, 4096, 'PX'); break;
      case '--interior-error': s.interiorError = real(a, value(), 0, 4096, 'PX'); break;
      case '--pixel-normals': s.pixelNormals = true; break;
      case '--edge-pixels': { const [p] = numbers(a, value(), 1); if (p < 0 || p > 4096) throw new Usage('--edge-pixels: 0 to 4096'); s.edgePixels = p; break; }
      case '--bench': { const [n] = numbers(a, value(), 1); if (!Number.isInteger(n) || n < 0 || n > 100000) throw new Usage('--bench: 0 to 100000 frames'); o.bench = n; break; }
      case '--displace': o.displace = value(); break;
      case '--texture': o.texture = value(); break;
      case '--displace-scale': {
        const v = value(), percent = v.endsWith('%'), x = Number(percent ? v.slice(0, -1) : v);
        if ((percent ? v.length < 2 : v === '') || !Number.isFinite(x) || Math.abs(x) > 1e6) throw new Usage(`--displace-scale: '${v}' is not a number (or a percentage like 2%) within -1e6 to 1e6`);
        o.displaceScale = x; o.displaceScalePercent = percent;
        break;
      }
      case '--displace-mid': { const [m] = numbers(a, value(), 1); if (Math.abs(m) > 1e6) throw new Usage('--displace-mid: -1e6 to 1e6'); o.displaceMid = m; break; }
      case '--no-seam-fix': o.noSeamFix = true; break;
      case '--wire': s.wire = 'outlines'; break;
      case '--wire-triangles': s.wire = 'triangles'; break;
      default:
        throw new Usage(`unknown option ${a} (see --help)`);
    }
  }
  if (o.help || o.version) return o;
  o.input ??= '-';
  // As limn-render's: the image goes to standard output unless --bench or --mesh-out is the
  // output asked for.
  if (!o.output && !o.bench && !o.meshOut) o.output = '-';
  if (o.output === '-' && o.bench) throw new Usage('--bench prints JSON on standard output; write the image with -o FILE');
  if (o.output) {
    // As limn-render: the extension, case-insensitive (X.PNG is a PNG); EXR is limn-render's
    // other image format, not written here (exit 3, as --mesh-out .obj); anything else is usage.
    // Standard output, a device or a pipe (-o /dev/null) is PNG whatever its name.
    const ext = o.output === '-' || isStreamPath(o.output) ? 'png' : /\.([^./]*)$/.exec(o.output)?.[1].toLowerCase();
    if (ext === 'exr') throw new LimnError(`-o ${o.output}: ${TOOL} writes PNG only (name it .png); limn-render writes .exr`, 'capability');
    if (ext !== 'png') throw new Usage(`-o ${o.output}: only PNG is written here (name it .png)`);
  }
  if (o.meshOut) {
    // limn-render's meshFormatFromPath: the extension, case-insensitive; - is PLY.
    const ext = o.meshOut === '-' ? 'ply' : /\.([^./]*)$/.exec(o.meshOut)?.[1].toLowerCase();
    if (!['ply', 'obj', 'gltf', 'glb'].includes(ext)) throw new Usage(`${o.meshOut}: --mesh-out: unknown extension; limn-render writes .ply, .obj, .gltf, .glb`);
    if (ext !== 'ply') throw new LimnError(`--mesh-out ${o.meshOut}: ${TOOL} writes PLY only (name it .ply); limn-render writes .${ext}`, 'capability');
    if (o.meshOut === '-' && (o.bench || o.output === '-')) throw new Usage('--mesh-out - and the image (or --bench JSON) cannot share standard output');
    o.settings.meshOut = true;
  }
  if (o.meshAscii && !o.meshOut) throw new Usage('--mesh-ascii applies to a .ply --mesh-out; give --mesh-out FILE.ply');
  if (s.view.eye && o.viewGiven) throw new Usage('--view and --eye exclude each other');
  if (argv.includes('--wire') && argv.includes('--wire-triangles')) throw new Usage('--wire and --wire-triangles exclude each other');
  if ((s.view.target || s.view.up) && !s.view.eye) throw new Usage('--target and --up describe an explicit camera; give --eye too');
  return o;
}

const linearToSrgb = (c) => { c = Math.min(Math.max(c, 0), 1); return c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055; };

// tools/render/input.cpp: the maps, and a MATL chunk's base colour (factor and texture).
function applyMaps(o, surface) {
  const s = o.settings;
  if (!o.displace && !o.quiet && (o.displaceScale !== undefined || o.displaceMid !== undefined || o.noSeamFix)) {
    process.stderr.write(`${TOOL}: warning: --displace-scale, --displace-mid and --no-seam-fix shape the --displace map; without --displace they do nothing\n`);
  }
  if (o.displace) {
    let scale = o.displaceScale ?? 1;
    if (o.displaceScalePercent) {
      const P = surface.mesh.positions, lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < P.length; i++) { lo[i % 3] = Math.min(lo[i % 3], P[i]); hi[i % 3] = Math.max(hi[i % 3], P[i]); }
      scale = (scale / 100) * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    }
    s.displace = { map: heightMap(readImageFile(o.displace, '--displace')), scale, mid: o.displaceMid ?? 0, seamFix: !o.noSeamFix };
  }
  if (o.texture) {
    s.texture = readImageFile(o.texture, '--texture');
    if (s.shade === 'lit') s.shade = 'texture';
  }
  const m = surface.material;
  if (m) {
    if (!s.color) s.color = m.baseColorFactor.slice(0, 3).map(linearToSrgb);
    const drawn = surface.uvs && (s.shade === 'lit' || s.shade === 'texture');
    if (!o.texture && m.texture.length && drawn) {
      try {
        // The format name is a hint (a file name or extension); the bytes decide.
        const png = [0x89, 0x50, 0x4e, 0x47].every((b, i) => m.texture[i] === b);
        if (!png) throw new Error(`'${m.textureFormat}' is not a PNG, and PNG is what limn-web-render decodes`);
        s.texture = decodePngImage(m.texture, 'the MATL base colour texture');
        s.shade = 'texture';
      } catch (e) {
        if (!o.quiet) process.stderr.write(`${TOOL}: warning: ${inputName}: the base colour texture cannot be read (${e.detail ?? e.message}); drawing the base colour factor instead\n`);
      }
    }
  }
}

// Stopped by SIGINT, SIGTERM or SIGHUP: no temporary file is left, and the process dies of it.
removeOutputsOnSignals();

// The input's name for messages about its contents: the parsed one (the first argument without
// a dash may be an option's value, '--size 64x48 in.limn').
let inputName = '';

async function main(argv) {
  const o = parseArgs(argv);
  inputName = displayName(o.input ?? '');
  if (o.help) { await writeStdout(HELP); return 0; }
  if (o.version) { await writeStdout(`${TOOL} 0.1.0\n`); return 0; }
  // Outputs that cannot be written are refused before the render, as limn-render opens them.
  const image = o.output ? planOutput(o.output, true) : null;
  const mesh = o.meshOut ? planOutput(o.meshOut, !o.meshAscii) : null;
  const surface = loadLimn(await readInput(o.input));
  applyMaps(o, surface);
  const s = o.settings;
  const { device, adapter } = await requestNodeDevice({
    limits: { maxTextureDimension2D: Math.max(s.width, s.height) },
    features: o.bench ? ['timestamp-query'] : [],
  });
  if (Math.max(s.width, s.height) > device.limits.maxTextureDimension2D) {
    throw new LimnError(`--size ${s.width}x${s.height}: this WebGPU device draws images of at most ${device.limits.maxTextureDimension2D} pixels a side`, 'capability');
  }
  // A lost device or a WebGPU error is the run's error, in one line (watchDevice).
  const gpu = watchDevice(device);
  await gpu.guard(render(o, surface, { device, adapter, gpu, image, mesh }));
  return 0;
}

async function render(o, surface, { device, adapter, gpu, image, mesh }) {
  const renderer = await Renderer.create(device, surface, o.settings);
  // --bench as limn-render's: 3 warm-up frames (pipeline compiles, first uploads), then per
  // measured frame the GPU time from timestamps, the host time (record, submit, wait) and, of
  // that, the JavaScript that records and submits.
  const warmup = o.bench ? 3 : 0, frames = Math.max(o.bench, 1);
  const timer = o.bench ? new GpuTimer(device) : null;
  const gpuMs = [], wall = [], js = [];
  for (let f = -warmup; f < frames; f++) {
    const t0 = performance.now();
    timer?.begin();
    renderer.frame();
    timer?.end();
    await device.queue.onSubmittedWorkDone();
    const ms = performance.now() - t0, frameGpuMs = timer ? await timer.read() : null;
    if (f < 0) continue;
    wall.push(ms);
    js.push(renderer.timings.js);
    gpuMs.push(frameGpuMs);
  }
  const pixels = await renderer.pixels();
  // Everything is read back before anything is written: a failure leaves no file.
  const ply = o.meshOut ? encodePly(await renderer.drawnMesh(), !!o.meshAscii) : null;
  gpu.check();
  const files = [];
  if (image) files.push([image, encodePng(o.settings.width, o.settings.height, pixels)]);
  if (ply) files.push([mesh, ply]);
  await writeOutputs(files);
  if (o.bench) {
    const median = (a) => { const b = [...a].sort((x, y) => x - y), n = b.length; return n % 2 ? b[n >> 1] : (b[n / 2 - 1] + b[n / 2]) / 2; };
    const ms = (a) => (a.includes(null) ? null : +median(a).toFixed(3));
    const s = o.settings;
    const report = {
      frames: o.bench, samples: s.samples, sample_shading: !!s.sampleShading, supersample: 1,
      size: `${s.width}x${s.height}`,
      gpu_ms: { compute: null, draw: null, total: ms(gpuMs) },
      passes: {},
      cpu_ms: ms(wall),
      js_ms: ms(js),
      triangles: await renderer.drawnTriangles(),
      vertices_evaluated: surface.tables.totalVertices - surface.tables.levels[0].count + surface.tables.limitCount + renderer.tess.vertexCount,
      buffer_bytes: Object.values(renderer.buffers).reduce((n, b) => n + b.size, 0),
      peak_rss_mb: +(process.resourceUsage().maxRSS / 1024).toFixed(1),
      device: adapter.info.description || adapter.info.device,
    };
    gpu.check();
    await writeStdout(`${JSON.stringify(report)}\n`);
  }
  renderer.destroy();
  gpu.destroy();
}

try {
  process.exitCode = await main(process.argv.slice(2));
} catch (e) {
  const file = e instanceof LimnError && !['usage', 'capability', 'output', 'input', 'gpu'].includes(e.where) ? `${inputName}: ` : '';
  if (e instanceof Usage) {
    process.stderr.write(`${TOOL}: error: ${e.message}\n`);
    process.exitCode = 2;
  } else if (e instanceof LimnError) {
    const what = ['usage', 'capability', 'output', 'input', 'gpu'].includes(e.where) ? e.detail : e.message;
    process.stderr.write(`${TOOL}: error: ${file}${what}\n`);
    process.exitCode = e.where === 'usage' ? 2 : e.where === 'capability' || e.capability ? 3 : 1;
  } else if (e.capability) {
    process.stderr.write(`${TOOL}: error: ${e.message}\n`);
    process.exitCode = 3;
  } else {
    // As limn-render's: a failure not foreseen is one line, not a stack.
    process.stderr.write(`${TOOL}: error: internal error: ${String(e?.message ?? e).split('\n')[0]}\n`);
    process.exitCode = 1;
  }
}
