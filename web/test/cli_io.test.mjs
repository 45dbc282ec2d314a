// limn-web-render's files and standard streams against limn-render's, run side by side on the
// same commands: a discarded or vanished standard output, `-` against a file named `-`, an output
// that is a symbolic link, a signal while an output waits, and a WebGPU failure in one line.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawn, spawnSync } from 'node:child_process';
import { lstatSync, mkdirSync, readdirSync, readFileSync, symlinkSync } from 'node:fs';
import { join } from 'node:path';
import { container, scratch, repo, tool } from './support.mjs';
import { privateIcd, requestNodeDevice, watchDevice } from '../src/node_device.mjs';

const cli = join(repo, 'web/bin/limn-web-render.mjs');
const env = { ...process.env, VK_ICD_FILENAMES: process.env.VK_ICD_FILENAMES ?? privateIcd };
// Both tools on one shell command line; `$T` is the tool, `$IN` the container. Bounded: 120 s.
function both(command, options = {}) {
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 });
  const run = (t) => spawnSync('bash', ['-c', `set -o pipefail; ${command}`], { encoding: 'buffer', timeout: 120000, cwd: options.cwd ?? scratch, env: { ...env, T: t, IN: limn }, input: options.input });
  const native = run(tool('limn-render')), web = run(`${process.execPath} ${cli}`);
  const text = (r) => r.stderr.toString().split('\n').filter((l) => !l.startsWith('Warning: ')).join('\n').replace(/^limn-(web-)?render: /gm, 'TOOL: ');
  return { native, web, nativeErr: text(native), webErr: text(web) };
}

test('standard output discarded, or its reader gone: limn-render\'s exit and message', () => {
  // Discarded by the parent (/dev/null opened read-write, as Python's DEVNULL and Node's 'ignore'
  // hand it over, and as Node reopens a closed one): the run succeeds.
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 });
  const ignored = spawnSync(process.execPath, [cli, limn, '--size', '32x32', '--mesh-out', '-'], { stdio: ['ignore', 'ignore', 'pipe'], encoding: 'utf8', timeout: 120000, env });
  assert.equal(ignored.status, 0, ignored.stderr);
  // The reader gone before the PNG comes (| head -c0): SIGPIPE ends both (128 + 13), no message.
  const r = both('$T "$IN" --size 32x32 | head -c0');
  assert.equal(r.native.status, 141, r.nativeErr);
  assert.equal(r.web.status, 141, r.webErr);
  assert.equal(r.webErr, r.nativeErr);
});

test('- is standard input or output, ./- a file; a symbolic link is written through; errors as limn-render\'s', () => {
  const dir = join(scratch, 'links');
  mkdirSync(dir, { recursive: true });
  for (const t of ['native', 'web']) {
    mkdirSync(join(dir, t));
    symlinkSync('real.png', join(dir, t, 'link.png'));
    symlinkSync('loop_b.png', join(dir, t, 'loop_a.png'));
    symlinkSync('loop_a.png', join(dir, t, 'loop_b.png'));
  }
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 });
  // The container on standard input while a file named - holds other bytes, the image through
  // the link (it stays a link); then the file named - (now the container) while standard input
  // holds other bytes, the image on standard output.
  const cmd = (t) => `cd ${t} && echo other > ./- && $T - --size 32x32 -o link.png < "$IN" && cp "$IN" ./- && $T ./- --size 32x32 -o - > stdout.png`;
  for (const t of ['native', 'web']) {
    const r = spawnSync('bash', ['-c', cmd(t)], { encoding: 'utf8', timeout: 120000, cwd: dir, env: { ...env, T: t === 'web' ? `${process.execPath} ${cli}` : tool('limn-render'), IN: limn }, input: 'not a container' });
    assert.equal(r.status, 0, `${t}: ${r.stderr}`);
    assert.ok(lstatSync(join(dir, t, 'link.png')).isSymbolicLink(), `${t}: the link was replaced by a file`);
    assert.ok(readFileSync(join(dir, t, 'real.png')).equals(readFileSync(join(dir, t, 'stdout.png'))), `${t}: the image through the link is not the one on standard output`);
  }
  // Refused before any GPU work, with limn-render's codes (and messages, but for the image
  // format's wording: limn-render also writes EXR).
  for (const [command, status, same] of [['$T "$IN" -o ./-', 2, false], ['$T "$IN" --mesh-out ./-', 2, true], ['$T "$IN" -o loop_a.png', 1, true],
    ['$T "$IN" -o nodir/x.png', 1, true], ['$T absent.limn -o x.png', 1, true], ['$T - -o x.png < /dev/null', 1, true], ['$T -- - --size 8x8', 2, true]]) {
    const r = both(command, { cwd: join(dir, 'web') });
    assert.equal(r.native.status, status, `${command}: ${r.nativeErr}`);
    assert.equal(r.web.status, status, `${command}: ${r.webErr}`);
    if (same) assert.equal(r.webErr, r.nativeErr, command);
  }
  assert.deepEqual(readdirSync(join(dir, 'web')).filter((f) => f.includes('limn-tmp') || f === 'x.png'), []);
});

// A signal while an output waits for its reader (a FIFO nobody opens): the temporary file of the
// other output is removed and the process dies of the signal (130), as limn-render. The open
// waited synchronously, the signal's handler never ran, and the run hung.
test('SIGINT while an output waits leaves no file and ends the run by the signal', async () => {
  const dir = join(scratch, 'signal');
  mkdirSync(dir, { recursive: true });
  execFileSync('mkfifo', [join(dir, 'fifo.png')]);
  const limn = container('quad/osd_catmark_fvar_bound1.obj', { depth: 2 });
  for (const [name, command] of [['limn-render', [tool('limn-render')]], ['limn-web-render', [process.execPath, cli]]]) {
    const child = spawn(command[0], [...command.slice(1), limn, '--size', '32x32', '-o', 'fifo.png', '--mesh-out', 'm.ply'], { cwd: dir, env, stdio: 'ignore' });
    const ended = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal })));
    // limn-render opens its outputs before it renders; the web one renders, writes the PLY's
    // temporary file, then waits on the FIFO: wait for that file (or, native, a second).
    for (let i = 0; i < 300 && !readdirSync(dir).some((f) => f.includes('limn-tmp')); i++) {
      await new Promise((r) => setTimeout(r, 100));
      if (name === 'limn-render' && i === 10) break;
    }
    if (name === 'limn-web-render') assert.ok(readdirSync(dir).some((f) => f.includes('limn-tmp')), 'the PLY was never staged');
    child.kill('SIGINT');
    const timer = setTimeout(() => child.kill('SIGKILL'), 30000);
    const { code, signal } = await ended;
    clearTimeout(timer);
    assert.equal(signal, 'SIGINT', `${name}: exit ${code}`);
    assert.deepEqual(readdirSync(dir), ['fifo.png'], name);
  }
});

// What a lost device or an uncaptured WebGPU error becomes: one line, the cause kept (Dawn's
// message is several lines; it printed them itself, then the run died with a stack).
test('a WebGPU error or a lost device is one LimnError line', async () => {
  const { device } = await requestNodeDevice();
  const gpu = watchDevice(device);
  gpu.check();
  device.createTexture({ size: [device.limits.maxTextureDimension2D + 1, 1], format: 'rgba8unorm', usage: GPUTextureUsage.TEXTURE_BINDING });
  await assert.rejects(gpu.guard(device.queue.onSubmittedWorkDone()), (e) => {
    assert.equal(e.where, 'gpu');
    assert.match(e.detail, /^WebGPU error: Texture size .* exceeded maximum texture size/);
    assert.doesNotMatch(e.detail, /\n/);
    return true;
  });
  const other = await requestNodeDevice();
  const watched = watchDevice(other.device);
  // Lost while a wait that never ends is pending: the guard ends with the loss.
  other.device.destroy();
  await assert.rejects(watched.guard(new Promise(() => {})), /^LimnError: gpu: the WebGPU device was lost \(destroyed\): [^\n]+$/);
  const mine = await requestNodeDevice();
  const quiet = watchDevice(mine.device);
  quiet.destroy();
  await mine.device.lost;
  quiet.check(); // destroyed here: no failure
});
