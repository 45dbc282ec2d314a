// Recording and running a frame: one reusable command buffer with its fence and timestamp
// queries. A frame is recorded from scratch each time (begin ... submitAndWait), the way an
// animated mesh would re-run its passes:
//
//   cmd.begin();
//   cmd.copy(staging, controlPoints);                        // per-frame upload
//   cmd.barrier(Access::TransferWrite, Access::ComputeRead);
//   cmd.beginTimed("face points L1");
//   cmd.dispatch(facePoints, facePointsBindings, faceCount, push);  // sized to the work
//   cmd.endTimed();
//   cmd.barrier(Access::ComputeWrite, Access::ComputeRead | Access::VertexRead);
//   cmd.beginRendering(target, clear); cmd.drawIndexed(...); cmd.endRendering();
//   cmd.copyToReadback(target);
//   cmd.submitAndWait();
//   for (auto& t : cmd.passTimes()) ...                     // GPU milliseconds per timed pass
#pragma once

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "gpu/render_target.h"
#include "gpu/vulkan.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace limn::gpu {

class Context;

// Where memory is written before a barrier and read after it. Combine with |.
enum class Access : uint32_t {
    TransferWrite = 1u << 0,
    TransferRead = 1u << 1,
    ComputeWrite = 1u << 2,
    ComputeRead = 1u << 3,
    VertexRead = 1u << 4,   // storage buffers read by vertex shaders
    FragmentRead = 1u << 5, // storage buffers read by fragment shaders
    IndexRead = 1u << 6,
    IndirectRead = 1u << 7,
    HostRead = 1u << 8,
    HostWrite = 1u << 9,
};
constexpr Access operator|(Access a, Access b) {
    return static_cast<Access>(static_cast<uint32_t>(a) | static_cast<uint32_t>(b));
}

struct PassTime {
    std::string name;
    double ms = 0; // NaN when the device has no timestamps
};

class CommandBuffer {
  public:
    explicit CommandBuffer(Context& ctx, uint32_t maxTimedPasses = 64);
    ~CommandBuffer();
    CommandBuffer(const CommandBuffer&) = delete;
    CommandBuffer& operator=(const CommandBuffer&) = delete;

    // Starts recording (the previous recording and its timings are discarded).
    void begin();
    // Ends recording, submits, and waits for the GPU to finish.
    void submitAndWait();

    // Transfers. `bytes` defaults to the whole source; ranges are bounds-checked.
    void copy(const Buffer& src, const Buffer& dst, uint64_t bytes = ~uint64_t(0),
              uint64_t srcOffset = 0, uint64_t dstOffset = 0);
    void fill(const Buffer& dst, uint32_t value);

    // A memory barrier: everything `before` wrote is visible to what `after` reads (and
    // write-after-read hazards are ordered too).
    void barrier(Access before, Access after);

    // Runs `pipeline` over `count` invocations: ceil(count / workgroup) groups, laid out as a 2D
    // grid when that exceeds 65535 (WebGPU's per-dimension limit). The count reaches the shader
    // in the dispatch header for its bounds check (limn_compute.glsl). `push` must be exactly
    // the pipeline's pushConstantBytes. A count of 0 records nothing.
    void dispatch(const ComputePipeline& pipeline, const BindGroup& bindings, uint32_t count,
                  std::span<const uint8_t> push = {});
    template <class Push>
    void dispatch(const ComputePipeline& pipeline, const BindGroup& bindings, uint32_t count,
                  const Push& push) {
        dispatch(pipeline, bindings, count, asBytes(push));
    }

    // Runs `pipeline` over the workgroups (x, y, z) that a pass wrote into `args` at `offset`
    // (WebGPU's dispatchWorkgroupsIndirect). The header's count is `maxCount` (the shader's bound
    // against its buffers) and its row width `rowGroups` * workgroup size: the pass that writes
    // the arguments lays large counts out as rows of `rowGroups` groups.
    void dispatchIndirect(const ComputePipeline& pipeline, const BindGroup& bindings,
                          const Buffer& args, uint64_t offset, uint32_t maxCount, uint32_t rowGroups,
                          std::span<const uint8_t> push = {});
    template <class Push>
    void dispatchIndirect(const ComputePipeline& pipeline, const BindGroup& bindings,
                          const Buffer& args, uint64_t offset, uint32_t maxCount, uint32_t rowGroups,
                          const Push& push) {
        dispatchIndirect(pipeline, bindings, args, offset, maxCount, rowGroups, asBytes(push));
    }

    // Dynamic rendering into `target`, cleared to `clearColor` (linear RGBA; the sRGB target
    // encodes it) and depth 1. The viewport is Y-up (negative height), like WebGPU and OpenGL.
    void beginRendering(const RenderTarget& target, std::array<float, 4> clearColor);
    void endRendering();
    void draw(const GraphicsPipeline& pipeline, const BindGroup& bindings, uint32_t vertexCount,
              uint32_t instanceCount = 1, std::span<const uint8_t> push = {});
    void drawIndexed(const GraphicsPipeline& pipeline, const BindGroup& bindings,
                     const Buffer& indices, uint32_t indexCount, uint32_t instanceCount = 1,
                     std::span<const uint8_t> push = {});
    // Draws whose counts a compute pass wrote into `args` at `offset`: VkDrawIndirectCommand /
    // VkDrawIndexedIndirectCommand layouts (WebGPU's drawIndirect / drawIndexedIndirect; one
    // draw each, no multi-draw).
    void drawIndirect(const GraphicsPipeline& pipeline, const BindGroup& bindings, const Buffer& args,
                      uint64_t offset, std::span<const uint8_t> push = {});
    void drawIndexedIndirect(const GraphicsPipeline& pipeline, const BindGroup& bindings,
                             const Buffer& indices, const Buffer& args, uint64_t offset,
                             std::span<const uint8_t> push = {});
    // Copies the colour image into the target's readback buffer (after endRendering).
    void copyToReadback(const RenderTarget& target);

    // GPU timestamps around a pass. Not nested; at most maxTimedPasses per frame.
    void beginTimed(const std::string& name);
    void endTimed();
    // Valid after submitAndWait, in recording order.
    std::vector<PassTime> passTimes() const;

    VkCommandBuffer handle() const { return cmd_; }

    template <class T>
    static std::span<const uint8_t> asBytes(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        return {reinterpret_cast<const uint8_t*>(&value), sizeof(T)};
    }

  private:
    void release();
    void requireRecording(const char* what) const;
    void bindAndPush(const Pipeline& pipeline, VkPipelineBindPoint point, const BindGroup& bindings,
                     std::span<const uint8_t> header, std::span<const uint8_t> push);

    Context* ctx_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    uint32_t maxTimed_;
    std::vector<std::string> timedNames_;
    std::vector<double> timedMs_;
    bool recording_ = false, inTimed_ = false, inRendering_ = false;
};

// One-off transfers for setup and tests (each records and waits for its own submission).
void uploadNow(Context& ctx, const Buffer& dst, std::span<const uint8_t> bytes,
               uint64_t dstOffset = 0);
std::vector<uint8_t> readbackNow(Context& ctx, const Buffer& src);

template <class T>
void uploadArrayNow(Context& ctx, const Buffer& dst, std::span<const T> values) {
    uploadNow(ctx, dst, {reinterpret_cast<const uint8_t*>(values.data()), values.size_bytes()});
}
// A new buffer holding `values`. Vulkan buffers cannot be empty: no values give one zero T.
template <class T>
Buffer uploadBufferNow(Context& ctx, const std::string& name, const std::vector<T>& values,
                       uint32_t usage = kStorage) {
    const T zero{};
    std::span<const T> data = values.empty() ? std::span<const T>(&zero, 1) : std::span<const T>(values);
    Buffer b(ctx, {name, data.size_bytes(), usage});
    uploadArrayNow<T>(ctx, b, data);
    return b;
}
template <class T>
std::vector<T> readbackArrayNow(Context& ctx, const Buffer& src, size_t count) {
    auto bytes = readbackNow(ctx, src);
    std::vector<T> out(count);
    std::memcpy(out.data(), bytes.data(), std::min(bytes.size(), count * sizeof(T)));
    return out;
}

} // namespace limn::gpu
