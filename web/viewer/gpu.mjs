// The page's WebGPU device (with 'timestamp-query' where the adapter offers it, for GpuTimer's
// GPU time per frame). Errors say what to enable, in words.

export { GpuTimer } from '../src/gpu_timer.mjs';

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
 * An ImageBitmap's texels as limn-render's image reader gives them (lib/image: v / 255 or
 * v / 65535, no colour conversion): copied by WebGPU into an rgba32float texture (channel values
 * at the precision the browser decoded, 16-bit PNGs included where it keeps them) and read back.
 * Returns {width, height, rgb (3 a texel), values (channel 0)}, rows top to bottom.
 */
export async function imagePixels(device, bitmap) {
  const { width, height } = bitmap;
  const texture = device.createTexture({ size: [width, height], format: 'rgba32float', usage: GPUTextureUsage.COPY_DST | GPUTextureUsage.COPY_SRC | GPUTextureUsage.RENDER_ATTACHMENT });
  const rowBytes = Math.ceil((width * 16) / 256) * 256;
  const buffer = device.createBuffer({ size: rowBytes * height, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  try {
    device.queue.copyExternalImageToTexture({ source: bitmap }, { texture, premultipliedAlpha: false }, [width, height]);
    const enc = device.createCommandEncoder({ label: 'map readback' });
    enc.copyTextureToBuffer({ texture }, { buffer, bytesPerRow: rowBytes }, [width, height]);
    device.queue.submit([enc.finish()]);
    await buffer.mapAsync(GPUMapMode.READ);
    const all = new Float32Array(buffer.getMappedRange());
    const rgb = new Float32Array(width * height * 3), values = new Float32Array(width * height);
    // The GPU's unorm-to-float conversion may be an ulp off v / 255: every 8- or 16-bit value is
    // k / 65535 (255 * 257 = 65535), so snap to that, as the C++ reader computes it.
    const snap = (x) => Math.fround(Math.round(Math.min(Math.max(x, 0), 1) * 65535) / 65535);
    for (let y = 0; y < height; y++) {
      for (let x = 0; x < width; x++) {
        const i = y * width + x, o = (y * rowBytes) / 4 + 4 * x;
        for (let k = 0; k < 3; k++) rgb[3 * i + k] = snap(all[o + k]);
        values[i] = rgb[3 * i];
      }
    }
    buffer.unmap();
    return { width, height, rgb, values };
  } finally {
    texture.destroy();
    buffer.destroy();
  }
}
