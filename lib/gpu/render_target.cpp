#include "gpu/render_target.h"

#include "base/error.h"
#include "gpu/context.h"

#include <algorithm>
#include <cstring>

namespace limn::gpu {

namespace {

uint32_t alignedRow(uint32_t width, uint32_t bytesPerPixel) {
    return (width * bytesPerPixel + RenderTarget::kRowAlignment - 1) /
           RenderTarget::kRowAlignment * RenderTarget::kRowAlignment;
}

void checkTarget(const Context& ctx, uint32_t width, uint32_t height, TargetFormat format) {
    uint32_t max = ctx.limits().maxImageDimension2D;
    if (width == 0 || height == 0 || width > max || height > max)
        throw Error(ErrorKind::BadInput, "image size " + std::to_string(width) + "x" +
                                             std::to_string(height) + " is outside 1.." +
                                             std::to_string(max) + " for this device");
    if (format.samples != 1 && format.samples != 4)
        throw Error(ErrorKind::Usage, "samples per pixel must be 1 or 4, not " +
                                          std::to_string(format.samples));
    if (format.color != RenderTarget::kColorFormat && format.color != RenderTarget::kLinearFormat)
        throw Error(ErrorKind::BadInput, "internal: unsupported render target format");
    if (!(ctx.limits().colorSampleCounts & format.samples) ||
        !(ctx.limits().depthSampleCounts & format.samples))
        throw Error(ErrorKind::Capability, "the device " + ctx.deviceName() + " cannot draw with " +
                                               std::to_string(format.samples) +
                                               " samples per pixel; use --samples 1");
    if (format.color == RenderTarget::kLinearFormat) {
        VkFormatProperties props{};
        ctx.vk().vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), format.color, &props);
        const VkFormatFeatureFlags need =
            VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
        if ((props.optimalTilingFeatures & need) != need)
            throw Error(ErrorKind::Capability, "the device " + ctx.deviceName() +
                                                   " cannot render to RGBA16F images (needed "
                                                   "for 16-bit PNG, EXR and --supersample)");
    }
}

} // namespace

uint64_t RenderTarget::estimateBytes(uint32_t width, uint32_t height, TargetFormat format,
                                     bool readDepth) {
    const uint64_t pixels = uint64_t(width) * height;
    const uint64_t bpp = bytesPerPixel(format.color);
    uint64_t bytes = pixels * format.samples * (bpp + 4); // drawn colour + depth
    if (format.samples > 1) bytes += pixels * bpp + (readDepth ? pixels * 4 : 0); // resolves
    bytes += uint64_t(alignedRow(width, uint32_t(bpp))) * height;                 // readback
    if (readDepth) bytes += uint64_t(alignedRow(width, 4)) * height;
    return bytes;
}

RenderTarget::RenderTarget(Context& ctx, uint32_t width, uint32_t height, TargetFormat format,
                           bool readDepth)
    : ctx_((checkTarget(ctx, width, height, format), &ctx)), width_(width),
      height_(height), format_(format), readDepth_(readDepth),
      rowPitch_(alignedRow(width, bytesPerPixel(format.color))),
      depthRowPitch_(alignedRow(width, 4)),
      readback_(ctx, {"image readback", uint64_t(rowPitch_) * height, 0, MemoryKind::Readback}) {
    const auto& vk = ctx.vk();
    auto makeImage = [&](VkFormat fmt, uint32_t samples, VkImageUsageFlags usage,
                         VkImageAspectFlags aspect, VkImage& image, VkImageView& view) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = fmt;
        info.extent = {width, height, 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = static_cast<VkSampleCountFlagBits>(samples);
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = usage;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        check(vk.vkCreateImage(ctx.device(), &info, nullptr, &image), "vkCreateImage");
        VkMemoryRequirements req{};
        vk.vkGetImageMemoryRequirements(ctx.device(), image, &req);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex =
            ctx.memoryType(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, nullptr);
        VkDeviceMemory memory = VK_NULL_HANDLE;
        check(vk.vkAllocateMemory(ctx.device(), &alloc, nullptr, &memory),
              "allocating a " + std::to_string(width) + "x" + std::to_string(height) + " image");
        memory_.push_back(memory);
        allocated_ += req.size;
        ctx.noteAllocation(static_cast<int64_t>(req.size));
        check(vk.vkBindImageMemory(ctx.device(), image, memory, 0), "vkBindImageMemory");
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = fmt;
        viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
        check(vk.vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view), "vkCreateImageView");
    };
    try {
        const bool msaa = format.samples > 1;
        const VkImageUsageFlags colourUse = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        const VkImageUsageFlags depthUse = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        makeImage(format.color, format.samples,
                  colourUse | (msaa ? 0 : VK_IMAGE_USAGE_TRANSFER_SRC_BIT),
                  VK_IMAGE_ASPECT_COLOR_BIT, color_, colorView_);
        makeImage(kDepthFormat, format.samples,
                  depthUse | (!msaa && readDepth ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0),
                  VK_IMAGE_ASPECT_DEPTH_BIT, depth_, depthView_);
        if (msaa)
            makeImage(format.color, 1, colourUse | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT, colorResolve_, colorResolveView_);
        if (msaa && readDepth)
            makeImage(kDepthFormat, 1, depthUse | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_DEPTH_BIT, depthResolve_, depthResolveView_);
        if (readDepth)
            depthReadback_.emplace(ctx, BufferDesc{"depth readback",
                                                   uint64_t(depthRowPitch_) * height, 0,
                                                   MemoryKind::Readback});
    } catch (...) {
        release();
        throw;
    }
}

RenderTarget::~RenderTarget() {
    release();
}

void RenderTarget::release() {
    const auto& vk = ctx_->vk();
    VkDevice d = ctx_->device();
    for (VkImageView v : {colorView_, depthView_, colorResolveView_, depthResolveView_})
        if (v) vk.vkDestroyImageView(d, v, nullptr);
    for (VkImage i : {color_, depth_, colorResolve_, depthResolve_})
        if (i) vk.vkDestroyImage(d, i, nullptr);
    for (VkDeviceMemory m : memory_) vk.vkFreeMemory(d, m, nullptr);
    memory_.clear();
    ctx_->noteAllocation(-static_cast<int64_t>(allocated_));
    allocated_ = 0;
    colorView_ = depthView_ = colorResolveView_ = depthResolveView_ = VK_NULL_HANDLE;
    color_ = depth_ = colorResolve_ = depthResolve_ = VK_NULL_HANDLE;
}

std::vector<uint8_t> RenderTarget::pixels() const {
    std::vector<uint8_t> padded(uint64_t(rowPitch_) * height_);
    readback_.read(padded);
    const size_t row = size_t(width_) * bytesPerPixel(format_.color);
    std::vector<uint8_t> out(row * height_);
    for (uint32_t y = 0; y < height_; ++y)
        std::copy_n(padded.data() + size_t(y) * rowPitch_, row, out.data() + y * row);
    return out;
}

std::vector<float> RenderTarget::depth() const {
    if (!depthReadback_) throw Error(ErrorKind::BadInput, "internal: the target keeps no depth");
    std::vector<uint8_t> padded(uint64_t(depthRowPitch_) * height_);
    depthReadback_->read(padded);
    std::vector<float> out(size_t(width_) * height_);
    for (uint32_t y = 0; y < height_; ++y)
        std::memcpy(out.data() + size_t(y) * width_, padded.data() + size_t(y) * depthRowPitch_,
                    size_t(width_) * 4);
    return out;
}

} // namespace limn::gpu
