#include "gpu/buffer.h"

#include "base/error.h"
#include "gpu/context.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace limn::gpu {

namespace {

std::string mib(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    return text;
}

} // namespace

uint64_t maxStorageBufferBytes(const Context& ctx) {
    return std::min<uint64_t>(kMaxStorageBufferBytes, ctx.limits().maxStorageBufferRange);
}

uint64_t maxElementsPerStorageBuffer(const Context& ctx, uint64_t elementBytes) {
    return elementBytes ? maxStorageBufferBytes(ctx) / elementBytes : 0;
}

Buffer::Buffer(Context& ctx, BufferDesc desc) : ctx_(&ctx), desc_(std::move(desc)) {
    if ((desc_.usage & kStorage) && desc_.size > maxStorageBufferBytes(ctx)) {
        throw Error(ErrorKind::BadInput,
                    "GPU buffer '" + desc_.name + "' needs " + std::to_string(desc_.size) +
                        " bytes (" + mib(desc_.size) +
                        "), more than one storage buffer may hold (" +
                        mib(maxStorageBufferBytes(ctx)) +
                        ": WebGPU's limit or the device's); split the data over several buffers "
                        "or lower the subdivision depth");
    }
    const auto& vk = ctx.vk();
    // Vulkan has no empty buffers, and fills and copies work in 4-byte words: round up.
    allocated_ = std::max<uint64_t>(16, (desc_.size + 15) & ~uint64_t(15));
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = allocated_;
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (desc_.usage & kStorage) info.usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (desc_.usage & kIndex) info.usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    if (desc_.usage & kIndirect) info.usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    try {
        check(vk.vkCreateBuffer(ctx.device(), &info, nullptr, &buffer_),
              "creating GPU buffer '" + desc_.name + "'");
        VkMemoryRequirements req{};
        vk.vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
        VkMemoryPropertyFlags required = 0, preferred = 0, chosen = 0;
        switch (desc_.memory) {
        case MemoryKind::Device:
            preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryKind::Upload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryKind::Readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
        }
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, required, preferred, &chosen);
        check(vk.vkAllocateMemory(ctx.device(), &alloc, nullptr, &memory_),
              "allocating " + mib(req.size) + " for GPU buffer '" + desc_.name + "'");
        check(vk.vkBindBufferMemory(ctx.device(), buffer_, memory_, 0), "vkBindBufferMemory");
        if (desc_.memory != MemoryKind::Device) {
            void* p = nullptr;
            check(vk.vkMapMemory(ctx.device(), memory_, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory");
            mapped_ = static_cast<uint8_t*>(p);
            coherent_ = chosen & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        }
        ctx.noteAllocation(static_cast<int64_t>(req.size));
        allocated_ = req.size;
    } catch (...) {
        allocated_ = 0;
        release();
        throw;
    }
}

Buffer::~Buffer() {
    release();
}

void Buffer::release() {
    if (!ctx_) return;
    const auto& vk = ctx_->vk();
    if (buffer_) vk.vkDestroyBuffer(ctx_->device(), buffer_, nullptr);
    if (memory_) vk.vkFreeMemory(ctx_->device(), memory_, nullptr); // unmaps implicitly
    if (memory_ && allocated_) ctx_->noteAllocation(-static_cast<int64_t>(allocated_));
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    allocated_ = 0;
}

Buffer::Buffer(Buffer&& other) noexcept {
    *this = std::move(other);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        release();
        ctx_ = std::exchange(other.ctx_, nullptr);
        desc_ = std::move(other.desc_);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        allocated_ = std::exchange(other.allocated_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
        coherent_ = other.coherent_;
    }
    return *this;
}

void Buffer::requireMapped(const char* what, uint64_t offset, uint64_t bytes) const {
    if (!mapped_)
        throw Error(ErrorKind::BadInput, std::string(what) + " on GPU buffer '" + desc_.name +
                                             "', which the CPU cannot see");
    if (offset > desc_.size || bytes > desc_.size - offset)
        throw Error(ErrorKind::BadInput, std::string(what) + " of " + std::to_string(bytes) +
                                             " bytes at offset " + std::to_string(offset) +
                                             " is outside GPU buffer '" + desc_.name + "' (" +
                                             std::to_string(desc_.size) + " bytes)");
}

void Buffer::write(std::span<const uint8_t> bytes, uint64_t offset) {
    requireMapped("write", offset, bytes.size());
    if (!bytes.empty()) std::memcpy(mapped_ + offset, bytes.data(), bytes.size());
    if (!coherent_) {
        VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
        range.memory = memory_;
        range.size = VK_WHOLE_SIZE;
        check(ctx_->vk().vkFlushMappedMemoryRanges(ctx_->device(), 1, &range),
              "flushing a mapping");
    }
}

void Buffer::read(std::span<uint8_t> out, uint64_t offset) const {
    requireMapped("read", offset, out.size());
    if (!coherent_) {
        VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
        range.memory = memory_;
        range.size = VK_WHOLE_SIZE;
        check(ctx_->vk().vkInvalidateMappedMemoryRanges(ctx_->device(), 1, &range),
              "invalidating a mapping");
    }
    if (!out.empty()) std::memcpy(out.data(), mapped_ + offset, out.size());
}

} // namespace limn::gpu
