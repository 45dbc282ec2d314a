// GPU time per frame from timestamp queries ('timestamp-query'), for the viewer's status line and
// limn-web-render --bench. GPUBufferUsage and GPUMapMode are the page's (in Node, the globals
// requestNodeDevice installs).

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
