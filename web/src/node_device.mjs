// A WebGPU device in Node: Dawn (npm `webgpu`) on the private Mesa 25 lavapipe that
// scripts/setup.sh --tests unpacks into web/.mesa (Dawn refuses Debian 12's Mesa 22.3 over
// Vulkan). An explicit VK_ICD_FILENAMES is kept. LIMN_WEB_DAWN_FLAGS adds Dawn's create() flags
// (space-separated, e.g. "enable-dawn-features=disable_robustness") for experiments.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { create, globals } from 'webgpu';

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
