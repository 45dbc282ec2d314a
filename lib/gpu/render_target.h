// The image a frame is drawn into: an optimal-tiled colour image (RGBA8 sRGB, or RGBA16F linear
// for float output) and a D32 depth image, with 1 or 4 samples per pixel (the two counts WebGPU
// offers). With 4, the draw resolves into single-sample images at the end of rendering: colour by
// averaging the samples (in linear light: an sRGB image is decoded before averaging), depth by
// taking sample 0 (the only depth resolve every device has; WebGPU would do it with a
// textureLoad of sample 0). The single-sample images are copied into host-visible buffers for
// readback; the copy's rows are padded to 256 bytes, as WebGPU's copyTextureToBuffer requires,
// and pixels()/depth() strip the padding.
#pragma once

#include "gpu/buffer.h"
#include "gpu/vulkan.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace limn::gpu {

class Context;

// What a graphics pipeline draws into; a pipeline serves only targets of its format.
struct TargetFormat {
    VkFormat color = VK_FORMAT_R8G8B8A8_SRGB;
    uint32_t samples = 1; // 1 or 4
    // Each covered sample shaded on its own (the surfaces' *_per_sample.frag variants; needs
    // DeviceLimits::sampleRateShading); only meaningful with more than one sample.
    bool sampleShading = false;
};

class RenderTarget {
  public:
    static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
    static constexpr VkFormat kLinearFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    static constexpr uint32_t kRowAlignment = 256;

    // Throws Error(BadInput) when the size is 0 or beyond the device's maxImageDimension2D,
    // Error(Capability) when the device cannot draw that format with that many samples.
    // `readDepth`: keep the depth for depth().
    RenderTarget(Context& ctx, uint32_t width, uint32_t height, TargetFormat format = {},
                 bool readDepth = false);
    ~RenderTarget();
    RenderTarget(const RenderTarget&) = delete;
    RenderTarget& operator=(const RenderTarget&) = delete;

    // Device and readback bytes such a target takes (images, resolve images, readback buffers),
    // before creating it: callers refuse sizes that cannot fit.
    static uint64_t estimateBytes(uint32_t width, uint32_t height, TargetFormat format,
                                  bool readDepth);
    static uint32_t bytesPerPixel(VkFormat color) { return color == kLinearFormat ? 8 : 4; }

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    const TargetFormat& format() const { return format_; }
    bool readsDepth() const { return readDepth_; }
    uint32_t rowPitch() const { return rowPitch_; } // bytes per row in the colour readback buffer
    uint32_t depthRowPitch() const { return depthRowPitch_; }

    // Drawn into (multisampled when samples > 1).
    VkImage colorImage() const { return color_; }
    VkImageView colorView() const { return colorView_; }
    VkImage depthImage() const { return depth_; }
    VkImageView depthView() const { return depthView_; }
    // The single-sample images resolved into; null with 1 sample (or depth not read).
    VkImage colorResolveImage() const { return colorResolve_; }
    VkImageView colorResolveView() const { return colorResolveView_; }
    VkImage depthResolveImage() const { return depthResolve_; }
    VkImageView depthResolveView() const { return depthResolveView_; }
    // What is copied out: the resolve images, else the drawn ones.
    VkImage colorReadImage() const { return colorResolve_ ? colorResolve_ : color_; }
    VkImage depthReadImage() const { return depthResolve_ ? depthResolve_ : depth_; }
    const Buffer& readback() const { return readback_; }
    const Buffer* depthReadback() const { return depthReadback_ ? &*depthReadback_ : nullptr; }

    // The pixels of the last frame copied with CommandBuffer::copyToReadback, top row first,
    // bytesPerPixel() bytes per pixel (RGBA8 sRGB-encoded, or RGBA16F linear), rows tightly
    // packed.
    std::vector<uint8_t> pixels() const;
    // The depth buffer's values (0 near .. 1 far), top row first; only with readDepth.
    std::vector<float> depth() const;

  private:
    void release();
    Context* ctx_;
    uint32_t width_, height_;
    TargetFormat format_;
    bool readDepth_;
    uint32_t rowPitch_, depthRowPitch_;
    VkImage color_ = VK_NULL_HANDLE, depth_ = VK_NULL_HANDLE;
    VkImage colorResolve_ = VK_NULL_HANDLE, depthResolve_ = VK_NULL_HANDLE;
    VkImageView colorView_ = VK_NULL_HANDLE, depthView_ = VK_NULL_HANDLE;
    VkImageView colorResolveView_ = VK_NULL_HANDLE, depthResolveView_ = VK_NULL_HANDLE;
    std::vector<VkDeviceMemory> memory_;
    uint64_t allocated_ = 0;
    Buffer readback_;
    std::optional<Buffer> depthReadback_;
};

} // namespace limn::gpu
