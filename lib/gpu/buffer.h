// GPU buffers. Every storage buffer is checked against the device's maxStorageBufferRange and
// against WebGPU's 128 MiB binding limit (the brief keeps every pass portable to a browser): a
// larger one is refused with a message that says to split it; maxElementsPerStorageBuffer() tells
// a caller where to split.
#pragma once

#include "gpu/vulkan.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn::gpu {

class Context;

// WebGPU's default maxStorageBufferBindingSize.
inline constexpr uint64_t kMaxStorageBufferBytes = uint64_t(128) << 20;

enum class MemoryKind {
    Device,   // device-local; filled by copies and passes
    Upload,   // host-visible, written by the CPU, source of copies (staging, per-frame data)
    Readback, // host-visible (cached where possible), destination of copies read by the CPU
};

enum BufferUsage : uint32_t {
    kStorage = 1u << 0,  // bound to compute or draw passes
    kIndex = 1u << 1,    // index buffer of a draw
    kIndirect = 1u << 2, // indirect dispatch/draw arguments
};

struct BufferDesc {
    std::string name; // for messages
    uint64_t size = 0;
    uint32_t usage = kStorage; // BufferUsage bits; transfers are always allowed
    MemoryKind memory = MemoryKind::Device;
};

// The most elements of `elementBytes` bytes one storage buffer may hold on this device.
uint64_t maxStorageBufferBytes(const Context& ctx);
uint64_t maxElementsPerStorageBuffer(const Context& ctx, uint64_t elementBytes);

class Buffer {
  public:
    // Throws Error(BadInput) naming the buffer when a storage buffer is too large.
    Buffer(Context& ctx, BufferDesc desc);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    uint64_t size() const { return desc_.size; }
    const std::string& name() const { return desc_.name; }
    MemoryKind memory() const { return desc_.memory; }
    uint32_t usage() const { return desc_.usage; }

    // Host-visible buffers only (Upload, Readback): copy bytes in or out of the mapping, flushing
    // or invalidating non-coherent memory. Bounds-checked against size().
    void write(std::span<const uint8_t> bytes, uint64_t offset = 0);
    void read(std::span<uint8_t> out, uint64_t offset = 0) const;
    template <class T>
    void writeArray(std::span<const T> values, uint64_t offset = 0) {
        write({reinterpret_cast<const uint8_t*>(values.data()), values.size_bytes()}, offset);
    }
    template <class T>
    std::vector<T> readArray(uint64_t count, uint64_t offset = 0) const {
        std::vector<T> out(count);
        read({reinterpret_cast<uint8_t*>(out.data()), count * sizeof(T)}, offset);
        return out;
    }

  private:
    void release();
    void requireMapped(const char* what, uint64_t offset, uint64_t bytes) const;

    Context* ctx_ = nullptr;
    BufferDesc desc_;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    uint64_t allocated_ = 0;
    uint8_t* mapped_ = nullptr;
    bool coherent_ = true;
};

} // namespace limn::gpu
