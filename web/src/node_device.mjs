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
 */
export async function requestNodeDevice({ backend = 'vulkan', limits = {} } = {}) {
  if (!process.env.VK_ICD_FILENAMES && existsSync(privateIcd)) process.env.VK_ICD_FILENAMES = privateIcd;
  process.env.XDG_RUNTIME_DIR ??= '/tmp';
  Object.assign(globalThis, globals);
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
  const device = await adapter.requestDevice({ requiredLimits: required });
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
