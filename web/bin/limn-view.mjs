#!/usr/bin/env node
// limn-view: serves the browser viewer (web/viewer) and one .limn container on this machine only
// (127.0.0.1), and prints the URL to open. A user needs no web server of their own; the page
// needs http(s) anyway (browsers give WebGPU and module scripts only to secure pages, and
// http://127.0.0.1 is one). Exit codes as limn's tools: 0 ok, 1 bad input or the port is taken,
// 2 usage.
import http from 'node:http';
import { closeSync, openSync, readSync, readFileSync, statSync } from 'node:fs';
import { basename, extname, join, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const TOOL = 'limn-view';
const HELP = `usage: ${TOOL} MODEL.limn|DIR [--port P] [--displace MAP [--displace-scale S] [--displace-mid M] | --texture MAP]
Serves limn's browser viewer and MODEL.limn on http://127.0.0.1 (this machine only) and prints
the URL that opens it; the model is read again at every request, so a reload shows a rebuilt file.
With a directory (make -f Makefile.examples STAGES=web writes out/web), serves that directory,
which holds the viewer and an index page of examples. Stop it with Ctrl-C.
  --port P              the port (1 to 65535; default 0: any free port)
  --displace MAP        open the model displaced by this height map (limn-render's option; the
                        page's panel turns the seam fix off and on)
  --displace-scale S    world units per unit of map value (default 1)
  --displace-mid M      the map value meaning zero (default 0)
  --texture MAP         open the model with this colour texture
  --help, --version
Open the printed URL in a browser with WebGPU (Chrome or Edge 113+; on Linux Chrome/Chromium with
--enable-unsafe-webgpu --enable-features=Vulkan).
Exit codes: 0 ok, 1 bad input or the port cannot be used, 2 usage.
`;
const web = fileURLToPath(new URL('..', import.meta.url));
const TYPES = {
  '.html': 'text/html; charset=utf-8', '.mjs': 'text/javascript; charset=utf-8', '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8', '.wgsl': 'text/plain; charset=utf-8', '.json': 'application/json',
  '.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.webp': 'image/webp', '.limn': 'application/octet-stream',
  '.txt': 'text/plain; charset=utf-8', '.md': 'text/plain; charset=utf-8',
};

class Failure extends Error { constructor(message, code) { super(message); this.code = code; } }

function parseArgs(argv) {
  const o = { port: 0 };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === '--help' || a === '-h') o.help = true;
    else if (a === '--version') o.version = true;
    else if (a === '--port' || a.startsWith('--port=')) {
      const v = a.includes('=') ? a.slice(7) : argv[++i];
      if (v === undefined) throw new Failure('--port needs a value', 2);
      if (!/^\d+$/.test(v) || +v > 65535) throw new Failure(`--port: '${v}' is not a port number (0 to 65535)`, 2);
      o.port = +v;
    } else if (['--displace', '--texture', '--displace-scale', '--displace-mid'].includes(a)) {
      const v = argv[++i];
      if (v === undefined) throw new Failure(`${a} needs a value`, 2);
      if (a.startsWith('--displace-') && !(v.trim() !== '' && Number.isFinite(Number(v)) && Math.abs(Number(v)) <= 1e6)) throw new Failure(`${a}: '${v}' is not a number within -1e6 to 1e6`, 2);
      o[{ '--displace': 'displace', '--texture': 'texture', '--displace-scale': 'displaceScale', '--displace-mid': 'displaceMid' }[a]] = v;
    } else if (a.startsWith('-') && a !== '-') throw new Failure(`unknown option ${a} (see --help)`, 2);
    else if (o.input) throw new Failure(`one model or directory, not '${o.input}' and '${a}'`, 2);
    else o.input = a;
  }
  if (!o.help && !o.version && !o.input) throw new Failure('no model given (see --help)', 2);
  if (o.displace && o.texture) throw new Failure('one map: --displace or --texture, not both', 2);
  if (!o.displace && (o.displaceScale !== undefined || o.displaceMid !== undefined)) throw new Failure('--displace-scale and --displace-mid shape the --displace map; give --displace MAP', 2);
  return o;
}

// The first bytes of a .limn container (formats/limn.md): refuse other files before serving.
function checkContainer(path) {
  let fd;
  try {
    fd = openSync(path, 'r');
  } catch (e) {
    throw new Failure(`${path}: cannot read it (${e.code}); give a .limn container (limn-classify | limn-tables)`, 1);
  }
  const magic = Buffer.alloc(8);
  const n = readSync(fd, magic, 0, 8, 0);
  closeSync(fd);
  if (n < 8 || !magic.equals(Buffer.from([0x4c, 0x49, 0x4d, 0x4e, 0x0d, 0x0a, 0x1a, 0x0a]))) {
    throw new Failure(`${path}: not a .limn container (no LIMN magic); make one with limn-classify MESH | limn-tables --depth 3`, 1);
  }
}

// Maps a URL path to a file under one of the roots, never outside them.
function fileFor(roots, urlPath) {
  let path;
  try { path = decodeURIComponent(urlPath.split('?')[0]); } catch { return null; }
  // Only the page and what it loads: no dot files, no installed packages (the viewer's tests').
  if (path.includes('\0') || path.split('/').some((part) => part.startsWith('.') || part === 'node_modules')) return null;
  for (const [prefix, dir] of roots) {
    if (prefix.endsWith('/') ? !path.startsWith(prefix) : path !== prefix) continue;
    const full = prefix.endsWith('/') ? resolve(dir, `.${path.slice(prefix.length - 1)}`) : dir;
    if (prefix.endsWith('/') && full !== resolve(dir) && !full.startsWith(resolve(dir) + sep)) return null;
    return full;
  }
  return null;
}

function serve(roots, redirect) {
  return http.createServer((req, res) => {
    if (req.method !== 'GET' && req.method !== 'HEAD') { res.writeHead(405, { Allow: 'GET, HEAD' }).end(); return; }
    const path = req.url.split('?')[0];
    if (path === '/' && redirect) { res.writeHead(302, { Location: redirect }).end(); return; }
    let file = fileFor(roots, path);
    try {
      if (file && statSync(file).isDirectory()) file = join(file, 'index.html');
      const body = file ? readFileSync(file) : null;
      if (!body) throw new Error('outside');
      res.writeHead(200, { 'Content-Type': TYPES[extname(file).toLowerCase()] ?? 'application/octet-stream', 'Content-Length': body.length, 'Cache-Control': 'no-cache' });
      res.end(req.method === 'HEAD' ? undefined : body);
    } catch {
      res.writeHead(404, { 'Content-Type': 'text/plain; charset=utf-8' }).end(`not found: ${path}\n`);
    }
  });
}

async function main(argv) {
  const o = parseArgs(argv);
  if (o.help) { process.stdout.write(HELP); return; }
  if (o.version) { process.stdout.write(`${TOOL} 0.1.0\n`); return; }
  let stat;
  try { stat = statSync(o.input); } catch (e) { throw new Failure(`${o.input}: cannot read it (${e.code})`, 1); }
  let roots, path, redirect = null;
  if (stat.isDirectory()) {
    roots = [['/', resolve(o.input)]];
    path = '/';
  } else {
    checkContainer(o.input);
    const name = encodeURIComponent(basename(o.input));
    roots = [['/viewer/', join(web, 'viewer')], ['/src/', join(web, 'src')], ['/shaders/', join(web, 'shaders')], [`/model/${name}`, resolve(o.input)]];
    path = `/viewer/?model=/model/${name}`;
    const map = o.displace ?? o.texture;
    if (map) {
      // The map as the model is: served at a path of its own, read again at every request.
      try { statSync(map); } catch (e) { throw new Failure(`${map}: cannot read it (${e.code})`, 1); }
      const mapName = encodeURIComponent(basename(map));
      roots.push([`/map/${mapName}`, resolve(map)]);
      path += `&${o.displace ? 'displace' : 'texture'}=/map/${mapName}`;
      if (o.displaceScale !== undefined) path += `&displaceScale=${Number(o.displaceScale)}`;
      if (o.displaceMid !== undefined) path += `&displaceMid=${Number(o.displaceMid)}`;
    }
    redirect = path;
  }
  const server = serve(roots, redirect);
  await new Promise((done, fail) => {
    server.once('error', (e) => {
      if (e.code === 'EADDRINUSE') fail(new Failure(`port ${o.port} on 127.0.0.1 is in use (another limn-view or server?); give another with --port P, or --port 0 for any free one`, 1));
      else if (e.code === 'EACCES') fail(new Failure(`port ${o.port} on 127.0.0.1 is not allowed to this user; use a port above 1023`, 1));
      else fail(new Failure(`cannot listen on 127.0.0.1:${o.port}: ${e.message}`, 1));
    });
    server.listen(o.port, '127.0.0.1', done);
  });
  process.stdout.write(`http://127.0.0.1:${server.address().port}${path}\n`);
  const stop = () => server.close(() => process.exit(0));
  process.on('SIGINT', stop);
  process.on('SIGTERM', stop);
}

try {
  await main(process.argv.slice(2));
} catch (e) {
  process.stderr.write(`${TOOL}: error: ${e.message}\n`);
  process.exitCode = e instanceof Failure ? e.code : 1;
}
