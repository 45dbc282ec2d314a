// The image a frame is drawn into: an optimal-tiled RGBA8 sRGB colour image and a D32 depth image,
// plus a host-visible buffer the colour image is copied into for readback. The copy's rows are
// padded to 256 bytes, as WebGPU's copyTextureToBuffer requires; pixels() strips the padding.
#pragma once

#include "gpu/buffer.h"
#include "gpu/vulkan.h"

#include <cstdint>
#include <vector>

namespace limn::gpu {

class Context;

class RenderTarget {
  public:
    static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    static constexpr uint32_t kRowAlignment = 256;

    // Throws Error(BadInput) when the size is 0 or beyond the device's maxImageDimension2D.
    RenderTarget(Context& ctx, uint32_t width, uint32_t height);
    ~RenderTarget();
    RenderTarget(const RenderTarget&) = delete;
    RenderTarget& operator=(const RenderTarget&) = delete;

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t rowPitch() const { return rowPitch_; } // bytes per row in the readback buffer

    VkImage colorImage() const { return color_; }
    VkImageView colorView() const { return colorView_; }
    VkImage depthImage() const { return depth_; }
    VkImageView depthView() const { return depthView_; }
    const Buffer& readback() const { return readback_; }

    // The pixels of the last frame copied with CommandBuffer::copyToReadback, top row first,
    // 4 bytes per pixel (sRGB-encoded RGBA), rows tightly packed.
    std::vector<uint8_t> pixels() const;

  private:
    void release();
    Context* ctx_;
    uint32_t width_, height_, rowPitch_;
    VkImage color_ = VK_NULL_HANDLE, depth_ = VK_NULL_HANDLE;
    VkDeviceMemory colorMemory_ = VK_NULL_HANDLE, depthMemory_ = VK_NULL_HANDLE;
    VkImageView colorView_ = VK_NULL_HANDLE, depthView_ = VK_NULL_HANDLE;
    uint64_t allocated_ = 0;
    Buffer readback_;
};

} // namespace limn::gpu
