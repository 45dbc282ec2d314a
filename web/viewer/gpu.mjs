// The page's WebGPU device, and GPU time per frame from timestamp queries where the adapter
// offers them ('timestamp-query'). Errors say what to enable, in words.

export class ViewerError extends Error {}

/** What to do without WebGPU, for this browser and page. */
export function noWebGpuAdvice() {
  if (!globalThis.isSecureContext) {
    return `WebGPU needs a secure page: this one is ${location.protocol}//${location.host}. Open it through http://localhost ` +
      '(node web/bin/limn-view.mjs MODEL.limn serves it there) or https.';
  }
  return 'WebGPU is not available in this browser (navigator.gpu is missing). Use Chrome or Edge 113 or later; on Linux ' +
    'start Chrome/Chromium with --enable-unsafe-webgpu --enable-features=Vulkan (or turn on chrome://flags/#enable-unsafe-webgpu). ' +
    'Firefox 141 or later has it on Windows (elsewhere set dom.webgpu.enabled in about:config); Safari 26 or later has it.';
}

/** Returns {device, adapter, description}; throws ViewerError in words. */
export async function requestDevice() {
  if (!navigator.gpu) throw new ViewerError(noWebGpuAdvice());
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) {
    throw new ViewerError('WebGPU is there but offers no adapter (no usable GPU, or the GPU is blocklisted). In Chrome see ' +
      'chrome://gpu; on Linux try --enable-unsafe-webgpu --enable-features=Vulkan, and without a GPU also ' +
      '--use-angle=vulkan --use-vulkan=swiftshader (a software device).');
  }
  const requiredFeatures = adapter.features.has('timestamp-query') ? ['timestamp-query'] : [];
  const requiredLimits = {};
  for (const k of ['maxStorageBufferBindingSize', 'maxBufferSize', 'maxStorageBuffersPerShaderStage']) requiredLimits[k] = adapter.limits[k];
  const device = await adapter.requestDevice({ requiredFeatures, requiredLimits });
  const info = adapter.info ?? {};
  const description = [info.description, info.vendor, info.architecture, info.isFallbackAdapter ? '(software fallback)' : ''].filter(Boolean).join(' ') || 'WebGPU adapter';
  return { device, adapter, description };
}

/**
 * GPU time of what is submitted between begin() and end(): each writes a timestamp from an empty
 * compute pass of its own submission, so the renderer's own passes need no hooks. read() gives
 * milliseconds, or null where the adapter has no timestamps (or a read is still in flight).
 */
export class GpuTimer {
  constructor(device) {
    this.device = device;
    this.available = device.features.has('timestamp-query');
    if (!this.available) return;
    this.querySet = device.createQuerySet({ type: 'timestamp', count: 2 });
    this.resolved = device.createBuffer({ size: 16, usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC });
    this.readback = device.createBuffer({ size: 16, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    this.reading = false;
    this.pending = false;
  }

  stamp(index, resolve) {
    if (!this.available || this.reading) return;
    const enc = this.device.createCommandEncoder({ label: 'gpu timer' });
    const writes = index === 0 ? { beginningOfPassWriteIndex: 0 } : { endOfPassWriteIndex: 1 };
    enc.beginComputePass({ timestampWrites: { querySet: this.querySet, ...writes } }).end();
    if (resolve) {
      enc.resolveQuerySet(this.querySet, 0, 2, this.resolved, 0);
      enc.copyBufferToBuffer(this.resolved, 0, this.readback, 0, 16);
      this.pending = true;
    }
    this.device.queue.submit([enc.finish()]);
  }

  begin() { this.stamp(0, false); }
  end() { this.stamp(1, true); }

  async read() {
    if (!this.available || !this.pending || this.reading) return null;
    this.reading = true;
    this.pending = false;
    try {
      await this.readback.mapAsync(GPUMapMode.READ);
      const [a, b] = new BigInt64Array(this.readback.getMappedRange());
      this.readback.unmap();
      const ms = Number(b - a) / 1e6;
      return ms > 0 ? ms : null;
    } finally {
      this.reading = false;
    }
  }
}
