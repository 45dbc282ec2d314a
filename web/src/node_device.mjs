// A WebGPU device in Node: Dawn (npm `webgpu`) on the private Mesa 25 lavapipe that
// scripts/setup.sh --tests unpacks into web/.mesa (Dawn refuses Debian 12's Mesa 22.3 over
// Vulkan). An explicit VK_ICD_FILENAMES is kept. LIMN_WEB_DAWN_FLAGS adds Dawn's create() flags
// (space-separated, e.g. "enable-dawn-features=disable_robustness") for experiments.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { create, globals } from 'webgpu';
import { LimnError } from './container.mjs';

export const privateIcd = fileURLToPath(new URL('../.mesa/icd.json', import.meta.url));

// Dawn crashes in InstanceBase::ProcessEvents when the object create() returns is collected while
// its adapter lives: keep every one for the life of the program.
const navigators = [];

/**
 * Returns { device, adapter } or throws an Error whose `capability` is true when no adapter or
 * device is there (limn's exit code 3). `backend`: 'vulkan' (default) or 'null' (validation only).
 * `features`: the optional ones wanted (e.g. 'timestamp-query'), requested where the adapter has them.
 */
export async function requestNodeDevice({ backend = 'vulkan', limits = {}, features = [] } = {}) {
  if (!process.env.VK_ICD_FILENAMES && existsSync(privateIcd)) process.env.VK_ICD_FILENAMES = privateIcd;
  process.env.XDG_RUNTIME_DIR ??= '/tmp';
  Object.assign(globalThis, globals);
  pollQuietly();
  const gpu = create([backend === 'null' ? 'backend=null' : 'backend=vulkan', ...(process.env.LIMN_WEB_DAWN_FLAGS ? process.env.LIMN_WEB_DAWN_FLAGS.split(' ') : [])]);
  navigators.push(gpu);
  const adapter = await gpu.requestAdapter();
  if (!adapter) {
    const e = new Error(`no WebGPU adapter (Dawn, ${backend}); run scripts/setup.sh --tests for the Mesa 25 lavapipe in web/.mesa`);
    e.capability = true;
    throw e;
  }
  const required = {};
  for (const [k, v] of Object.entries(limits)) required[k] = Math.min(v, adapter.limits[k]);
  const requiredFeatures = features.filter((f) => adapter.features.has(f));
  const device = await adapter.requestDevice({ requiredLimits: required, requiredFeatures });
  return { device, adapter };
}

/**
 * Watches a device for what ends a run: a loss (not by destroy() here) or an uncaptured WebGPU
 * error (the first one; the rest follow from it). Both become a LimnError of one line
 * (where 'gpu'), and Dawn does not print the error itself. check() throws it; guard(promise)
 * awaits a promise and throws it instead of what the promise did, also while a wait that a lost
 * device never ends is pending; destroy() destroys the device without it counting as a loss.
 */
export function watchDevice(device) {
  let failure = null, destroying = false, fail;
  const failed = new Promise((resolve, reject) => { fail = reject; });
  failed.catch(() => {});
  const record = (message) => {
    if (failure) return;
    failure = new LimnError(message.split('\n')[0].trim(), 'gpu');
    fail(failure);
  };
  device.lost.then((info) => {
    if (!destroying) record(`the WebGPU device was lost (${info.reason}): ${info.message || 'no reason given'}`);
  });
  device.onuncapturederror = (e) => {
    e.preventDefault?.();
    record(`WebGPU ${e.error.constructor?.name === 'GPUOutOfMemoryError' ? 'ran out of memory' : 'error'}: ${e.error.message}`);
  };
  return {
    check() { if (failure) throw failure; },
    async guard(promise) {
      try {
        await Promise.race([promise, failed]);
      } catch (e) {
        throw failure ?? e;
      }
      if (failure) throw failure;
    },
    destroy() { destroying = true; device.destroy(); },
  };
}

/**
 * dawn.node settles its promises (mapAsync, onSubmittedWorkDone, create*PipelineAsync) by calling
 * wgpuInstanceProcessEvents from setImmediate for as long as one is pending, so the event loop
 * spins while the GPU works. On a CPU device (lavapipe) that spin takes a core from the
 * rasterizer's threads: on 2 cores a frame took 1.4-2.2x limn-render's (docs/benchmarks-web.md). From
 * the first device on, every turn of the event loop first sleeps here: Dawn still polls once a
 * turn, and the thread is idle in between. The sleep grows with the wait, a twentieth of it so far
 * (0.1 to 1 ms): a settled promise is seen at most about 5% (or 1 ms) late, with few wake-ups on
 * long frames (a fixed 0.2 ms cost the car's 150 ms frame about 10% more CPU than 1 ms). A wait
 * starts when anything else ran between two turns. The immediate is unref'd: it keeps nothing
 * alive, and while the loop blocks on anything else (timers, I/O) it runs once a wake-up. Node
 * only (in a browser the GPU runs in another process).
 */
let quietPolling = false;
function pollQuietly() {
  if (quietPolling) return;
  quietPolling = true;
  const cell = new Int32Array(new SharedArrayBuffer(4));
  let since = 0, last = 0;
  const turn = () => {
    const now = performance.now();
    if (now - last > 0.1) since = now;
    Atomics.wait(cell, 0, 0, Math.min(Math.max((now - since) / 20, 0.1), 1));
    last = performance.now();
    setImmediate(turn).unref();
  };
  setImmediate(turn).unref();
}
