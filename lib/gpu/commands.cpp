#include "gpu/commands.h"

#include "base/error.h"
#include "gpu/context.h"

#include <cmath>
#include <limits>

namespace limn::gpu {

namespace {

// WebGPU's maxComputeWorkgroupsPerDimension; Vulkan guarantees it too.
constexpr uint32_t kMaxGroupsPerDimension = 65535;

struct StageAccess {
    VkPipelineStageFlags2 stage = 0;
    VkAccessFlags2 access = 0;
};

// Each kind of access: the pipeline stage it happens in and the access flag it needs.
struct AccessMapping {
    Access bit;
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
};
constexpr AccessMapping kAccessMappings[] = {
    {Access::TransferWrite, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT},
    {Access::TransferRead, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT},
    {Access::ComputeWrite, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT},
    {Access::ComputeRead, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
     VK_ACCESS_2_SHADER_STORAGE_READ_BIT},
    {Access::VertexRead, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
     VK_ACCESS_2_SHADER_STORAGE_READ_BIT},
    {Access::FragmentRead, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
     VK_ACCESS_2_SHADER_STORAGE_READ_BIT},
    {Access::IndexRead, VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT},
    {Access::IndirectRead, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
     VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT},
    {Access::HostRead, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT},
    {Access::HostWrite, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT},
};

StageAccess toStageAccess(Access a) {
    StageAccess r;
    for (const auto& m : kAccessMappings)
        if (static_cast<uint32_t>(a) & static_cast<uint32_t>(m.bit)) {
            r.stage |= m.stage;
            r.access |= m.access;
        }
    return r;
}

void imageBarrier(const VulkanFunctions& vk, VkCommandBuffer cmd, VkImage image,
                  VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to, StageAccess src,
                  StageAccess dst) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = src.stage;
    b.srcAccessMask = src.access;
    b.dstStageMask = dst.stage;
    b.dstAccessMask = dst.access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vk.vkCmdPipelineBarrier2(cmd, &dep);
}

} // namespace

CommandBuffer::CommandBuffer(Context& ctx, uint32_t maxTimedPasses)
    : ctx_(&ctx), maxTimed_(maxTimedPasses) {
    const auto& vk = ctx.vk();
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    poolInfo.queueFamilyIndex = ctx.queueFamily();
    check(vk.vkCreateCommandPool(ctx.device(), &poolInfo, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkResult r = vk.vkAllocateCommandBuffers(ctx.device(), &alloc, &cmd_);
    if (r == VK_SUCCESS) r = vk.vkCreateFence(ctx.device(), &fenceInfo, nullptr, &fence_);
    if (r == VK_SUCCESS && ctx.limits().timestamps && maxTimed_) {
        VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        q.queryType = VK_QUERY_TYPE_TIMESTAMP;
        q.queryCount = 2 * maxTimed_;
        r = vk.vkCreateQueryPool(ctx.device(), &q, nullptr, &queries_);
    }
    if (r != VK_SUCCESS) {
        release();
        check(r, "creating a command buffer");
    }
}

CommandBuffer::~CommandBuffer() {
    release();
}

void CommandBuffer::release() {
    const auto& vk = ctx_->vk();
    if (queries_) vk.vkDestroyQueryPool(ctx_->device(), queries_, nullptr);
    if (fence_) vk.vkDestroyFence(ctx_->device(), fence_, nullptr);
    if (pool_) vk.vkDestroyCommandPool(ctx_->device(), pool_, nullptr);
    queries_ = VK_NULL_HANDLE;
    fence_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
}

void CommandBuffer::requireRecording(const char* what) const {
    if (!recording_)
        throw Error(ErrorKind::BadInput,
                    std::string("internal: ") + what + " outside begin()/submit");
}

void CommandBuffer::begin() {
    const auto& vk = ctx_->vk();
    check(vk.vkResetCommandPool(ctx_->device(), pool_, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vk.vkBeginCommandBuffer(cmd_, &info), "vkBeginCommandBuffer");
    if (queries_) vk.vkCmdResetQueryPool(cmd_, queries_, 0, 2 * maxTimed_);
    timedNames_.clear();
    timedMs_.clear();
    recording_ = true;
    inTimed_ = inRendering_ = false;
}

void CommandBuffer::submitAndWait() {
    requireRecording("submit");
    if (inTimed_ || inRendering_)
        throw Error(ErrorKind::BadInput, "internal: submit inside a timed pass or rendering");
    const auto& vk = ctx_->vk();
    recording_ = false;
    check(vk.vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    check(vk.vkQueueSubmit(ctx_->queue(), 1, &submit, fence_), "vkQueueSubmit");
    check(vk.vkWaitForFences(ctx_->device(), 1, &fence_, VK_TRUE, UINT64_MAX),
          "waiting for the GPU");
    check(vk.vkResetFences(ctx_->device(), 1, &fence_), "vkResetFences");

    timedMs_.assign(timedNames_.size(), std::numeric_limits<double>::quiet_NaN());
    if (queries_ && !timedNames_.empty()) {
        std::vector<uint64_t> stamps(2 * timedNames_.size());
        check(vk.vkGetQueryPoolResults(
                  ctx_->device(), queries_, 0, static_cast<uint32_t>(stamps.size()),
                  stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "reading GPU timestamps");
        for (size_t i = 0; i < timedNames_.size(); ++i)
            timedMs_[i] =
                double(stamps[2 * i + 1] - stamps[2 * i]) * ctx_->limits().timestampPeriodNs * 1e-6;
    }
}

void CommandBuffer::copy(const Buffer& src, const Buffer& dst, uint64_t bytes, uint64_t srcOffset,
                         uint64_t dstOffset) {
    requireRecording("copy");
    if (bytes == ~uint64_t(0)) bytes = src.size() - std::min(srcOffset, src.size());
    if (srcOffset > src.size() || bytes > src.size() - srcOffset || dstOffset > dst.size() ||
        bytes > dst.size() - dstOffset)
        throw Error(ErrorKind::BadInput, "copy of " + std::to_string(bytes) + " bytes from '" +
                                             src.name() + "' to '" + dst.name() +
                                             "' is out of bounds");
    if (bytes == 0) return;
    VkBufferCopy region{srcOffset, dstOffset, bytes};
    ctx_->vk().vkCmdCopyBuffer(cmd_, src.handle(), dst.handle(), 1, &region);
}

void CommandBuffer::fill(const Buffer& dst, uint32_t value) {
    requireRecording("fill");
    ctx_->vk().vkCmdFillBuffer(cmd_, dst.handle(), 0, VK_WHOLE_SIZE, value);
}

void CommandBuffer::barrier(Access before, Access after) {
    requireRecording("barrier");
    StageAccess src = toStageAccess(before), dst = toStageAccess(after);
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = src.stage;
    b.srcAccessMask = src.access;
    b.dstStageMask = dst.stage;
    b.dstAccessMask = dst.access;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    ctx_->vk().vkCmdPipelineBarrier2(cmd_, &dep);
}

void CommandBuffer::bindAndPush(const Pipeline& pipeline, VkPipelineBindPoint point,
                                const BindGroup& bindings, std::span<const uint8_t> header,
                                std::span<const uint8_t> push) {
    if (push.size() != pipeline.pushConstantBytes())
        throw Error(ErrorKind::BadInput, "internal: pass '" + pipeline.name() + "' takes " +
                                             std::to_string(pipeline.pushConstantBytes()) +
                                             " bytes of push constants, got " +
                                             std::to_string(push.size()));
    const auto& vk = ctx_->vk();
    vk.vkCmdBindPipeline(cmd_, point, pipeline.handle());
    VkDescriptorSet set = bindings.handle();
    if (pipeline.storageBuffers())
        vk.vkCmdBindDescriptorSets(cmd_, point, pipeline.layout(), 0, 1, &set, 0, nullptr);
    std::vector<uint8_t> bytes(header.begin(), header.end());
    bytes.insert(bytes.end(), push.begin(), push.end());
    if (!bytes.empty())
        vk.vkCmdPushConstants(cmd_, pipeline.layout(), pipeline.stages(), 0,
                              static_cast<uint32_t>(bytes.size()), bytes.data());
}

void CommandBuffer::dispatch(const ComputePipeline& pipeline, const BindGroup& bindings,
                             uint32_t count, std::span<const uint8_t> push) {
    requireRecording("dispatch");
    if (inRendering_) throw Error(ErrorKind::BadInput, "internal: dispatch inside rendering");
    if (count == 0) return;
    const uint64_t groups =
        (uint64_t(count) + pipeline.workgroupSize() - 1) / pipeline.workgroupSize();
    // A 2D grid whose x * y covers `groups` with as little waste as possible; the shader turns
    // it back into a linear index and drops the excess invocations.
    const uint64_t y = (groups + kMaxGroupsPerDimension - 1) / kMaxGroupsPerDimension;
    const uint64_t x = (groups + y - 1) / y;
    if (y > kMaxGroupsPerDimension || x * pipeline.workgroupSize() > UINT32_MAX ||
        y > ctx_->limits().maxComputeWorkGroupCount[1] ||
        x > ctx_->limits().maxComputeWorkGroupCount[0])
        throw Error(ErrorKind::BadInput, "pass '" + pipeline.name() +
                                             "': " + std::to_string(count) +
                                             " invocations exceed the dispatch limits");
    uint32_t header[4] = {count, static_cast<uint32_t>(x) * pipeline.workgroupSize(), 0, 0};
    bindAndPush(pipeline, VK_PIPELINE_BIND_POINT_COMPUTE, bindings,
                {reinterpret_cast<const uint8_t*>(header), sizeof header}, push);
    ctx_->vk().vkCmdDispatch(cmd_, static_cast<uint32_t>(x), static_cast<uint32_t>(y), 1);
}

void CommandBuffer::dispatchIndirect(const ComputePipeline& pipeline, const BindGroup& bindings,
                                     const Buffer& args, uint64_t offset, uint32_t maxCount,
                                     uint32_t rowGroups, std::span<const uint8_t> push) {
    requireRecording("dispatchIndirect");
    if (inRendering_) throw Error(ErrorKind::BadInput, "internal: dispatch inside rendering");
    if (!(args.usage() & kIndirect) || offset % 4 != 0 || offset + 12 > args.size())
        throw Error(ErrorKind::BadInput, "internal: '" + args.name() + "' holds no dispatch arguments at " +
                                             std::to_string(offset));
    uint32_t header[4] = {maxCount, rowGroups * pipeline.workgroupSize(), 0, 0};
    bindAndPush(pipeline, VK_PIPELINE_BIND_POINT_COMPUTE, bindings,
                {reinterpret_cast<const uint8_t*>(header), sizeof header}, push);
    ctx_->vk().vkCmdDispatchIndirect(cmd_, args.handle(), offset);
}

void CommandBuffer::beginRendering(const RenderTarget& target, std::array<float, 4> clearColor) {
    requireRecording("beginRendering");
    const auto& vk = ctx_->vk();
    // UNDEFINED discards last frame's contents; the source stages order this frame's writes after
    // the previous copy-out and depth use (write-after-read across submissions). Resolves write
    // in the colour-attachment-output stage, depth resolves included.
    const StageAccess colourWrite{
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT};
    imageBarrier(vk, cmd_, target.colorImage(), VK_IMAGE_ASPECT_COLOR_BIT,
                 VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0}, colourWrite);
    if (target.colorResolveImage())
        imageBarrier(vk, cmd_, target.colorResolveImage(), VK_IMAGE_ASPECT_COLOR_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0}, colourWrite);
    const VkPipelineStageFlags2 depthStages =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    imageBarrier(vk, cmd_, target.depthImage(), VK_IMAGE_ASPECT_DEPTH_BIT,
                 VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 {depthStages | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0},
                 {depthStages | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT});
    if (target.depthResolveImage())
        imageBarrier(vk, cmd_, target.depthResolveImage(), VK_IMAGE_ASPECT_DEPTH_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0},
                     {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | depthStages,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT});
    const bool msaa = target.format().samples > 1;
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target.colorView();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    // The samples are needed only until they are resolved (WebGPU: storeOp "discard").
    color.storeOp = msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    if (msaa) {
        color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        color.resolveImageView = target.colorResolveView();
        color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    for (int i = 0; i < 4; ++i) color.clearValue.color.float32[i] = clearColor[i];
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = target.depthView();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = target.readsDepth() && !msaa ? VK_ATTACHMENT_STORE_OP_STORE
                                                 : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    if (target.depthResolveImage()) {
        depth.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
        depth.resolveImageView = target.depthResolveView();
        depth.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    }
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {target.width(), target.height()}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    info.pDepthAttachment = &depth;
    vk.vkCmdBeginRendering(cmd_, &info);
    VkViewport viewport{
        0, float(target.height()), float(target.width()), -float(target.height()), 0, 1};
    VkRect2D scissor{{0, 0}, {target.width(), target.height()}};
    vk.vkCmdSetViewport(cmd_, 0, 1, &viewport);
    vk.vkCmdSetScissor(cmd_, 0, 1, &scissor);
    inRendering_ = true;
}

void CommandBuffer::endRendering() {
    requireRecording("endRendering");
    ctx_->vk().vkCmdEndRendering(cmd_);
    inRendering_ = false;
}

void CommandBuffer::draw(const GraphicsPipeline& pipeline, const BindGroup& bindings,
                         uint32_t vertexCount, uint32_t instanceCount,
                         std::span<const uint8_t> push) {
    requireRecording("draw");
    if (!inRendering_) throw Error(ErrorKind::BadInput, "internal: draw outside rendering");
    if (!vertexCount || !instanceCount) return;
    bindAndPush(pipeline, VK_PIPELINE_BIND_POINT_GRAPHICS, bindings, {}, push);
    ctx_->vk().vkCmdDraw(cmd_, vertexCount, instanceCount, 0, 0);
}

void CommandBuffer::drawIndexed(const GraphicsPipeline& pipeline, const BindGroup& bindings,
                                const Buffer& indices, uint32_t indexCount, uint32_t instanceCount,
                                std::span<const uint8_t> push) {
    requireRecording("drawIndexed");
    if (!inRendering_) throw Error(ErrorKind::BadInput, "internal: draw outside rendering");
    if (!(indices.usage() & kIndex))
        throw Error(ErrorKind::BadInput,
                    "internal: '" + indices.name() + "' is not an index buffer");
    if (uint64_t(indexCount) * 4 > indices.size())
        throw Error(ErrorKind::BadInput, "internal: " + std::to_string(indexCount) +
                                             " indices overrun '" + indices.name() + "'");
    if (!indexCount || !instanceCount) return;
    bindAndPush(pipeline, VK_PIPELINE_BIND_POINT_GRAPHICS, bindings, {}, push);
    ctx_->vk().vkCmdBindIndexBuffer(cmd_, indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    ctx_->vk().vkCmdDrawIndexed(cmd_, indexCount, instanceCount, 0, 0, 0);
}

void CommandBuffer::drawIndirect(const GraphicsPipeline& pipeline, const BindGroup& bindings,
                                 const Buffer& args, uint64_t offset, std::span<const uint8_t> push) {
    requireRecording("drawIndirect");
    if (!inRendering_) throw Error(ErrorKind::BadInput, "internal: draw outside rendering");
    if (!(args.usage() & kIndirect) || offset % 4 != 0 || offset + 16 > args.size())
        throw Error(ErrorKind::BadInput, "internal: '" + args.name() + "' holds no draw arguments");
    bindAndPush(pipeline, VK_PIPELINE_BIND_POINT_GRAPHICS, bindings, {}, push);
    ctx_->vk().vkCmdDrawIndirect(cmd_, args.handle(), offset, 1, 16);
}

void CommandBuffer::drawIndexedIndirect(const GraphicsPipeline& pipeline, const BindGroup& bindings,
                                        const Buffer& indices, const Buffer& args, uint64_t offset,
                                        std::span<const uint8_t> push) {
    requireRecording("drawIndexedIndirect");
    if (!inRendering_) throw Error(ErrorKind::BadInput, "internal: draw outside rendering");
    if (!(indices.usage() & kIndex))
        throw Error(ErrorKind::BadInput, "internal: '" + indices.name() + "' is not an index buffer");
    if (!(args.usage() & kIndirect) || offset % 4 != 0 || offset + 20 > args.size())
        throw Error(ErrorKind::BadInput, "internal: '" + args.name() + "' holds no draw arguments");
    bindAndPush(pipeline, VK_PIPELINE_BIND_POINT_GRAPHICS, bindings, {}, push);
    ctx_->vk().vkCmdBindIndexBuffer(cmd_, indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    ctx_->vk().vkCmdDrawIndexedIndirect(cmd_, args.handle(), offset, 1, 20);
}

void CommandBuffer::copyToReadback(const RenderTarget& target) {
    requireRecording("copyToReadback");
    const auto& vk = ctx_->vk();
    imageBarrier(
        vk, cmd_, target.colorReadImage(), VK_IMAGE_ASPECT_COLOR_BIT,
        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
        {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
        {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT});
    VkBufferImageCopy region{};
    region.bufferRowLength = target.rowPitch() / RenderTarget::bytesPerPixel(target.format().color);
    region.bufferImageHeight = target.height();
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {target.width(), target.height(), 1};
    vk.vkCmdCopyImageToBuffer(cmd_, target.colorReadImage(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              target.readback().handle(), 1, &region);
    if (const Buffer* depth = target.depthReadback()) {
        // Written by the depth tests (1 sample) or by the resolve (colour-output stage).
        imageBarrier(vk, cmd_, target.depthReadImage(), VK_IMAGE_ASPECT_DEPTH_BIT,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
                     {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT});
        VkBufferImageCopy d{};
        d.bufferRowLength = target.depthRowPitch() / 4;
        d.bufferImageHeight = target.height();
        d.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
        d.imageExtent = {target.width(), target.height(), 1};
        vk.vkCmdCopyImageToBuffer(cmd_, target.depthReadImage(),
                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depth->handle(), 1, &d);
    }
    barrier(Access::TransferWrite, Access::HostRead);
}

void CommandBuffer::beginTimed(const std::string& name) {
    requireRecording("beginTimed");
    if (inTimed_) throw Error(ErrorKind::BadInput, "internal: timed passes do not nest");
    if (timedNames_.size() >= maxTimed_)
        throw Error(ErrorKind::BadInput,
                    "internal: more than " + std::to_string(maxTimed_) + " timed passes");
    uint32_t index = static_cast<uint32_t>(timedNames_.size());
    timedNames_.push_back(name);
    inTimed_ = true;
    if (queries_)
        ctx_->vk().vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_,
                                        2 * index);
}

void CommandBuffer::endTimed() {
    requireRecording("endTimed");
    if (!inTimed_) throw Error(ErrorKind::BadInput, "internal: endTimed without beginTimed");
    inTimed_ = false;
    uint32_t index = static_cast<uint32_t>(timedNames_.size() - 1);
    if (queries_)
        ctx_->vk().vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_,
                                        2 * index + 1);
}

std::vector<PassTime> CommandBuffer::passTimes() const {
    std::vector<PassTime> out;
    for (size_t i = 0; i < timedNames_.size() && i < timedMs_.size(); ++i)
        out.push_back({timedNames_[i], timedMs_[i]});
    return out;
}

void uploadNow(Context& ctx, const Buffer& dst, std::span<const uint8_t> bytes,
               uint64_t dstOffset) {
    if (bytes.empty()) return;
    Buffer staging(ctx, {"staging for '" + dst.name() + "'", bytes.size(), 0, MemoryKind::Upload});
    staging.write(bytes);
    CommandBuffer cmd(ctx, 0);
    cmd.begin();
    cmd.copy(staging, dst, bytes.size(), 0, dstOffset);
    cmd.submitAndWait();
}

std::vector<uint8_t> readbackNow(Context& ctx, const Buffer& src) {
    Buffer staging(ctx, {"readback of '" + src.name() + "'", src.size(), 0, MemoryKind::Readback});
    CommandBuffer cmd(ctx, 0);
    cmd.begin();
    cmd.copy(src, staging);
    cmd.barrier(Access::TransferWrite, Access::HostRead);
    cmd.submitAndWait();
    std::vector<uint8_t> out(src.size());
    staging.read(out);
    return out;
}

} // namespace limn::gpu
