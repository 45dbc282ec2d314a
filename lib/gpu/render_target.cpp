#include "gpu/render_target.h"

#include "base/error.h"
#include "gpu/context.h"

#include <algorithm>

namespace limn::gpu {

namespace {

uint32_t checkedSize(const Context& ctx, uint32_t width, uint32_t height) {
    uint32_t max = ctx.limits().maxImageDimension2D;
    if (width == 0 || height == 0 || width > max || height > max)
        throw Error(ErrorKind::BadInput, "image size " + std::to_string(width) + "x" +
                                             std::to_string(height) + " is outside 1.." +
                                             std::to_string(max) + " for this device");
    return (width * 4 + RenderTarget::kRowAlignment - 1) / RenderTarget::kRowAlignment *
           RenderTarget::kRowAlignment;
}

} // namespace

RenderTarget::RenderTarget(Context& ctx, uint32_t width, uint32_t height)
    : ctx_(&ctx), width_(width), height_(height), rowPitch_(checkedSize(ctx, width, height)),
      readback_(ctx, {"image readback", uint64_t(rowPitch_) * height, 0, MemoryKind::Readback}) {
    const auto& vk = ctx.vk();
    auto makeImage = [&](VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                         VkImage& image, VkDeviceMemory& memory, VkImageView& view) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {width, height, 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
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
        check(vk.vkAllocateMemory(ctx.device(), &alloc, nullptr, &memory),
              "allocating a " + std::to_string(width) + "x" + std::to_string(height) + " image");
        allocated_ += req.size;
        ctx.noteAllocation(static_cast<int64_t>(req.size));
        check(vk.vkBindImageMemory(ctx.device(), image, memory, 0), "vkBindImageMemory");
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format;
        viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
        check(vk.vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view), "vkCreateImageView");
    };
    try {
        makeImage(kColorFormat,
                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT, color_, colorMemory_, colorView_);
        makeImage(kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                  VK_IMAGE_ASPECT_DEPTH_BIT, depth_, depthMemory_, depthView_);
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
    if (colorView_) vk.vkDestroyImageView(d, colorView_, nullptr);
    if (depthView_) vk.vkDestroyImageView(d, depthView_, nullptr);
    if (color_) vk.vkDestroyImage(d, color_, nullptr);
    if (depth_) vk.vkDestroyImage(d, depth_, nullptr);
    if (colorMemory_) vk.vkFreeMemory(d, colorMemory_, nullptr);
    if (depthMemory_) vk.vkFreeMemory(d, depthMemory_, nullptr);
    ctx_->noteAllocation(-static_cast<int64_t>(allocated_));
    allocated_ = 0;
    colorView_ = depthView_ = VK_NULL_HANDLE;
    color_ = depth_ = VK_NULL_HANDLE;
    colorMemory_ = depthMemory_ = VK_NULL_HANDLE;
}

std::vector<uint8_t> RenderTarget::pixels() const {
    std::vector<uint8_t> padded(uint64_t(rowPitch_) * height_);
    readback_.read(padded);
    const size_t row = size_t(width_) * 4;
    std::vector<uint8_t> out(row * height_);
    for (uint32_t y = 0; y < height_; ++y)
        std::copy_n(padded.data() + size_t(y) * rowPitch_, row, out.data() + y * row);
    return out;
}

} // namespace limn::gpu
