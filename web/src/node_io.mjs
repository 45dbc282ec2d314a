// limn-web-render's files and standard streams, as limn-render's lib/base/io.cpp and cli.cpp
// treat them (Node-only): `-` is standard input or output (a file named `-` is `./-`); an
// output goes to a temporary file beside its target, renamed over it once every output is
// written, through a symbolic link to the file it names, and in place where the target is a
// device or a pipe; a closed standard output fails what is written there; a signal removes the
// temporary files and the process dies of it.
//
// Every wait (reading the input, opening a FIFO, a full pipe) is asynchronous, on libuv's
// threads: the event loop keeps running, so a signal's handler runs at once. A synchronous open
// of a FIFO without a reader blocked the loop, and Ctrl-C did nothing.
import fs from 'node:fs';
import os, { hostname } from 'node:os';
import tty from 'node:tty';
import { dirname, join, isAbsolute } from 'node:path';
import { promisify } from 'node:util';
import { LimnError } from './container.mjs';

const read = promisify(fs.read), write = promisify(fs.write), open = promisify(fs.open), close = promisify(fs.close);

export const isStdio = (path) => path === '-';
/** An input's name in messages: <stdin> for standard input. */
export const displayName = (path) => (isStdio(path) ? '<stdin>' : path);

// glibc's strerror text, as limn-render prints it: libuv's own text capitalised, except where
// the two say it differently.
const STRERROR = {
  EISDIR: 'Is a directory', EEXIST: 'File exists', ELOOP: 'Too many levels of symbolic links',
  EIO: 'Input/output error', ENAMETOOLONG: 'File name too long', EXDEV: 'Invalid cross-device link',
  ENOTDIR: 'Not a directory', EBUSY: 'Device or resource busy', ETXTBSY: 'Text file busy', EDQUOT: 'Disk quota exceeded',
};
/** A system error's text as C's strerror gives it ("No such file or directory"). */
export function systemMessage(e) {
  if (STRERROR[e.code]) return STRERROR[e.code];
  const m = /^[A-Z0-9_]+: ([^,]+)/.exec(e.message ?? '');
  return m ? m[1][0].toUpperCase() + m[1].slice(1) : (e.code ?? String(e.message ?? e));
}
const fail = (file, what, e) => new LimnError(`${file}: ${what}: ${systemMessage(e)}`, 'output');

/** Reads a whole input file, or standard input for `-`, without blocking the event loop. */
export async function readInput(path) {
  const name = displayName(path);
  let fd = 0;
  if (!isStdio(path)) {
    try {
      fd = await open(path, fs.constants.O_RDONLY);
    } catch (e) {
      throw new LimnError(`${name}: cannot open: ${systemMessage(e)}`, 'input');
    }
  }
  try {
    if (fs.fstatSync(fd).isDirectory()) throw new LimnError(`${name}: is a directory, not a file`, 'input');
    // Inputs are read whole; an endless one (/dev/zero) stops at limn's limit, with its name.
    const chunks = [];
    let total = 0;
    for (;;) {
      const chunk = Buffer.allocUnsafe(1 << 20);
      let n;
      try {
        ({ bytesRead: n } = await read(fd, chunk, 0, chunk.length, null));
      } catch (e) {
        if (e.code === 'EAGAIN') { await new Promise((r) => setTimeout(r, 5)); continue; }
        throw new LimnError(`${name}: cannot read: ${systemMessage(e)}`, 'input');
      }
      if (n === 0) break;
      total += n;
      if (total > 2 ** 32) throw new LimnError(`${name}: larger than 4 GiB, more than limn reads as one input`, 'input');
      chunks.push(chunk.subarray(0, n));
    }
    // Nothing on standard input is nearly always a failed command earlier in the pipe.
    if (total === 0 && isStdio(path)) throw new LimnError('empty input on <stdin> (did the command before it in the pipe fail?)', 'input');
    const bytes = Buffer.concat(chunks, total);
    return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  } finally {
    if (fd !== 0) fs.closeSync(fd);
  }
}

// Standard output. Node opens /dev/null read-write in place of a closed one (`>&-`), so a run
// with standard output closed writes into /dev/null and exits 0, where limn-render fails
// (it puts /dev/full there). Telling the two apart is not possible: a parent that discards the
// output hands over /dev/null opened read-write too (Python's DEVNULL, Node's 'ignore'), and
// that must keep working. So descriptor 1 is written as it is.
const STDOUT = 1;

export const stdoutIsTerminal = () => tty.isatty(STDOUT);

/** Writes bytes to standard output; a reader gone (EPIPE) ends the process by SIGPIPE, as limn-render's. */
export async function writeStdout(bytes) {
  const data = Buffer.isBuffer(bytes) ? bytes : Buffer.from(bytes);
  for (let at = 0; at < data.length;) {
    try {
      at += (await write(STDOUT, data, at, data.length - at)).bytesWritten;
    } catch (e) {
      if (e.code === 'EAGAIN') { await new Promise((r) => setTimeout(r, 5)); continue; }
      if (e.code === 'EPIPE') dieOf('SIGPIPE');
      throw new LimnError(`<stdout>: cannot write: ${systemMessage(e)}`, 'output');
    }
  }
}

// Temporary files not yet renamed into place, removed by the signal handler.
const temps = new Set();

/** Ends the process by `signal` (default action), with the temporary files removed first. */
export function dieOf(signal) {
  for (const t of temps) fs.rmSync(t, { force: true });
  // Node ignores SIGPIPE and handles the others itself: a listener added and removed gives the
  // signal its default action back.
  const none = () => {};
  process.on(signal, none);
  process.off(signal, none);
  process.kill(process.pid, signal);
  process.exit(128 + os.constants.signals[signal]); // not reached: the signal ends the process
}

/** SIGINT, SIGTERM, SIGHUP: the temporary files are removed, then the process dies of the signal. */
export function removeOutputsOnSignals() {
  for (const signal of ['SIGINT', 'SIGTERM', 'SIGHUP']) process.once(signal, () => dieOf(signal));
}

// Where writing `path` really goes: through a chain of symbolic links to the file it names, so
// that an output that is a link updates its file instead of replacing the link (resolveLinks).
function resolveLinks(path) {
  let p = path;
  for (let hops = 0; hops < 40; hops++) {
    let st;
    try { st = fs.lstatSync(p); } catch { return p; }
    if (!st.isSymbolicLink()) return p;
    const target = fs.readlinkSync(p);
    p = isAbsolute(target) ? target : join(dirname(p), target);
  }
  throw fail(path, 'cannot resolve output', { code: 'ELOOP' });
}

/**
 * An output, checked before the render as limn-render opens it: standard output (`-`), a
 * device or pipe written in place, or a file staged beside the one its links name. A directory
 * is refused, and binary bytes for a terminal (a usage error: `usage` is true).
 */
export function planOutput(path, binary) {
  const refuseTerminal = () => { throw new LimnError('refusing to write binary output to a terminal; use -o FILE or a pipe', 'usage'); };
  if (isStdio(path)) {
    if (binary && stdoutIsTerminal()) refuseTerminal();
    return { path, stdout: true };
  }
  let st = null;
  try { st = fs.statSync(path); } catch { /* absent, or a dangling link: written new */ }
  if (st?.isDirectory()) throw new LimnError(`${path}: is a directory, not a file`, 'output');
  if (st && !st.isFile()) {
    // A device or FIFO (/dev/null, /dev/stdout): renaming a file over it would replace it.
    if (binary && st.isCharacterDevice()) {
      let fd = -1;
      try { fd = fs.openSync(path, fs.constants.O_WRONLY | fs.constants.O_NONBLOCK | fs.constants.O_NOCTTY); } catch { /* found out when written */ }
      const terminal = fd >= 0 && tty.isatty(fd);
      if (fd >= 0) fs.closeSync(fd);
      if (terminal) refuseTerminal();
    }
    return { path, inPlace: true };
  }
  const target = resolveLinks(path);
  // The folder it goes into must be there (limn-render creates the temporary file now).
  try {
    if (!fs.statSync(dirname(target)).isDirectory()) throw Object.assign(new Error(), { code: 'ENOTDIR' });
  } catch (e) {
    throw fail(path, 'cannot create output', e);
  }
  return { path, target, mode: st ? st.mode & 0o7777 : null };
}

/** True when `path` names a device or a pipe (-o /dev/null): a stream, written as PNG whatever its name. */
export function isStreamPath(path) {
  try { const st = fs.statSync(path); return st.isCharacterDevice() || st.isFIFO(); } catch { return false; }
}

const owner = `${(hostname() || 'host').replace(/[^A-Za-z0-9.-]/g, '_').slice(0, 32)}-${process.pid}-`;

async function writeAll(fd, bytes) {
  for (let at = 0; at < bytes.length;) at += (await write(fd, bytes, at, bytes.length - at)).bytesWritten;
}

/**
 * Writes [plan, bytes] pairs: the staged files to temporary files (created exclusively, named
 * .limn-tmp-HOST-PID-XXXXXX as limn-render's), then the in-place and standard-output ones, then
 * every temporary file is renamed over its target. A failure leaves none of the staged files.
 */
export async function writeOutputs(outputs) {
  const staged = [];
  try {
    for (const [plan, bytes] of outputs) {
      if (plan.stdout || plan.inPlace) continue;
      let fd = -1, tmp = '';
      for (let attempt = 0; fd < 0; attempt++) {
        tmp = join(dirname(plan.target), `.limn-tmp-${owner}${Math.random().toString(36).slice(2, 8).padEnd(6, '0')}`);
        temps.add(tmp);
        try {
          fd = await open(tmp, fs.constants.O_WRONLY | fs.constants.O_CREAT | fs.constants.O_EXCL, 0o666);
        } catch (e) {
          temps.delete(tmp);
          if (e.code !== 'EEXIST' || attempt >= 100) throw fail(plan.path, 'cannot create output', e);
        }
      }
      staged.push([tmp, plan]);
      try {
        // An existing file keeps its permissions; a new one gets 0666 less the umask.
        if (plan.mode !== null) fs.fchmodSync(fd, plan.mode);
        await writeAll(fd, bytes);
      } catch (e) {
        throw fail(plan.path, 'cannot write', e);
      } finally {
        await close(fd);
      }
    }
    for (const [plan, bytes] of outputs) {
      if (plan.stdout) { await writeStdout(bytes); continue; }
      if (!plan.inPlace) continue;
      let fd;
      try { fd = await open(plan.path, fs.constants.O_WRONLY); } catch (e) { throw fail(plan.path, 'cannot open output', e); }
      try { await writeAll(fd, bytes); } catch (e) { throw fail(plan.path, 'cannot write', e); } finally { await close(fd); }
    }
    for (const [tmp, plan] of staged) {
      try { fs.renameSync(tmp, plan.target); } catch (e) { throw fail(plan.path, 'cannot rename into place', e); }
      temps.delete(tmp);
    }
  } finally {
    for (const [tmp] of staged) if (temps.delete(tmp)) fs.rmSync(tmp, { force: true });
  }
}
