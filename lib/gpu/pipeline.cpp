#include "gpu/pipeline.h"

#include "base/error.h"
#include "gpu/context.h"
#include "gpu/render_target.h"

#include <array>
#include <utility>

namespace limn::gpu {

namespace {

[[noreturn]] void fail(const std::string& pipeline, const std::string& message) {
    throw Error(ErrorKind::BadInput, "GPU pass '" + pipeline + "': " + message);
}

} // namespace

std::array<uint32_t, 3> spirvLocalSize(std::span<const uint32_t> spirv) {
    constexpr uint32_t kMagic = 0x07230203, kOpExecutionMode = 16, kLocalSize = 17;
    if (spirv.size() < 5 || spirv[0] != kMagic)
        throw Error(ErrorKind::BadInput, "not a SPIR-V module");
    for (size_t i = 5; i < spirv.size();) {
        uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xFFFF;
        if (words == 0 || i + words > spirv.size())
            throw Error(ErrorKind::BadInput, "malformed SPIR-V module");
        if (op == kOpExecutionMode && words >= 6 && spirv[i + 2] == kLocalSize)
            return {spirv[i + 3], spirv[i + 4], spirv[i + 5]};
        i += words;
    }
    return {0, 0, 0};
}

// BindGroup ------------------------------------------------------------------------------------

BindGroup::~BindGroup() {
    release();
}

void BindGroup::release() {
    if (ctx_ && pool_) ctx_->vk().vkDestroyDescriptorPool(ctx_->device(), pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
    set_ = VK_NULL_HANDLE;
}

BindGroup::BindGroup(BindGroup&& other) noexcept {
    *this = std::move(other);
}

BindGroup& BindGroup::operator=(BindGroup&& other) noexcept {
    if (this != &other) {
        release();
        ctx_ = std::exchange(other.ctx_, nullptr);
        pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
        set_ = std::exchange(other.set_, VK_NULL_HANDLE);
    }
    return *this;
}

// Pipeline -------------------------------------------------------------------------------------

Pipeline::Pipeline(Context& ctx, std::string name, uint32_t storageBuffers, uint32_t pushBytes,
                   uint32_t headerBytes, VkShaderStageFlags stages)
    : ctx_(&ctx), name_(std::move(name)), storageBuffers_(storageBuffers), pushBytes_(pushBytes),
      headerBytes_(headerBytes), stages_(stages) {
    if (storageBuffers > kMaxStorageBuffersPerPass ||
        storageBuffers > ctx.limits().maxPerStageDescriptorStorageBuffers)
        fail(name_, std::to_string(storageBuffers) + " storage buffers; at most " +
                        std::to_string(kMaxStorageBuffersPerPass) + " per pass (WebGPU's limit)");
    if (pushBytes % 4 || headerBytes + pushBytes > ctx.limits().maxPushConstantsSize)
        fail(name_, std::to_string(pushBytes) + " bytes of push constants; the device allows " +
                        std::to_string(ctx.limits().maxPushConstantsSize - headerBytes) +
                        " (a multiple of 4)");
    const auto& vk = ctx.vk();
    std::vector<VkDescriptorSetLayoutBinding> bindings(storageBuffers);
    for (uint32_t i = 0; i < storageBuffers; ++i)
        bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr};
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = storageBuffers;
    setInfo.pBindings = bindings.data();
    check(vk.vkCreateDescriptorSetLayout(ctx.device(), &setInfo, nullptr, &setLayout_),
          "vkCreateDescriptorSetLayout");
    VkPushConstantRange push{stages, 0, headerBytes + pushBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout_;
    layoutInfo.pushConstantRangeCount = push.size ? 1 : 0;
    layoutInfo.pPushConstantRanges = &push;
    VkResult r = vk.vkCreatePipelineLayout(ctx.device(), &layoutInfo, nullptr, &layout_);
    if (r != VK_SUCCESS) {
        release();
        check(r, "vkCreatePipelineLayout");
    }
}

Pipeline::~Pipeline() {
    release();
}

VkPipeline Pipeline::handle() const {
    if (!pipeline_ && compile_) pipeline_ = compile_();
    return pipeline_;
}

void Pipeline::release() {
    const auto& vk = ctx_->vk();
    if (pipeline_) vk.vkDestroyPipeline(ctx_->device(), pipeline_, nullptr);
    if (layout_) vk.vkDestroyPipelineLayout(ctx_->device(), layout_, nullptr);
    if (setLayout_) vk.vkDestroyDescriptorSetLayout(ctx_->device(), setLayout_, nullptr);
    pipeline_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    setLayout_ = VK_NULL_HANDLE;
}

VkShaderModule Pipeline::createModule(std::span<const uint32_t> spirv, const char* stage) const {
    if (spirv.size() < 5 || spirv[0] != 0x07230203u)
        fail(name_, std::string("the ") + stage + " shader is not a SPIR-V module");
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(ctx_->vk().vkCreateShaderModule(ctx_->device(), &info, nullptr, &module),
          "creating the " + std::string(stage) + " shader of '" + name_ + "'");
    return module;
}

BindGroup Pipeline::bind(std::initializer_list<BufferBinding> buffers) const {
    return bind(std::span<const BufferBinding>(buffers.begin(), buffers.size()));
}

BindGroup Pipeline::bind(std::span<const BufferBinding> buffers) const {
    if (buffers.size() != storageBuffers_)
        fail(name_, "binds " + std::to_string(buffers.size()) + " buffers, its layout has " +
                        std::to_string(storageBuffers_));
    std::vector<VkDescriptorBufferInfo> infos;
    for (size_t i = 0; i < buffers.size(); ++i) {
        const BufferBinding& b = buffers[i];
        const Buffer& buf = *b.buffer;
        std::string which = "binding " + std::to_string(i) + " ('" + buf.name() + "')";
        if (!(buf.usage() & kStorage)) fail(name_, which + " is not a storage buffer");
        uint64_t size =
            b.size == VK_WHOLE_SIZE ? buf.size() - std::min(b.offset, buf.size()) : b.size;
        if (b.offset > buf.size() || size > buf.size() - b.offset)
            fail(name_, which + ": range " + std::to_string(b.offset) + "+" + std::to_string(size) +
                            " is outside the buffer (" + std::to_string(buf.size()) + " bytes)");
        if (b.offset % ctx_->limits().minStorageBufferOffsetAlignment)
            fail(name_, which + ": offset " + std::to_string(b.offset) + " is not a multiple of " +
                            std::to_string(ctx_->limits().minStorageBufferOffsetAlignment));
        if (size > maxStorageBufferBytes(*ctx_))
            fail(name_, which + ": binds " + std::to_string(size) + " bytes, more than " +
                            std::to_string(maxStorageBufferBytes(*ctx_)));
        // An empty range cannot be bound; bind the (padded) start, the shader reads nothing.
        infos.push_back({buf.handle(), size ? b.offset : 0, size ? size : VK_WHOLE_SIZE});
    }
    const auto& vk = ctx_->vk();
    BindGroup group;
    group.ctx_ = ctx_;
    // One small pool per group: groups live as long as the pass that owns them, and nothing has
    // to be sized for the whole renderer up front.
    VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, std::max(1u, storageBuffers_)};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &poolSize;
    check(vk.vkCreateDescriptorPool(ctx_->device(), &poolInfo, nullptr, &group.pool_),
          "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = group.pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &setLayout_;
    check(vk.vkAllocateDescriptorSets(ctx_->device(), &alloc, &group.set_),
          "vkAllocateDescriptorSets");
    std::vector<VkWriteDescriptorSet> writes(infos.size());
    for (uint32_t i = 0; i < infos.size(); ++i) {
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = group.set_;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vk.vkUpdateDescriptorSets(ctx_->device(), static_cast<uint32_t>(writes.size()), writes.data(),
                              0, nullptr);
    return group;
}

// ComputePipeline ------------------------------------------------------------------------------

ComputePipeline::ComputePipeline(Context& ctx, const ComputePipelineDesc& desc)
    : Pipeline(ctx, desc.name, desc.storageBuffers, desc.pushConstantBytes, kDispatchHeaderBytes,
               VK_SHADER_STAGE_COMPUTE_BIT) {
    try {
        auto size = spirvLocalSize(desc.spirv);
        if (size[0] == 0) fail(name_, "the shader declares no local_size_x");
        if (size[1] != 1 || size[2] != 1)
            fail(name_, "passes are one-dimensional: local size must be (X, 1, 1)");
        localSize_ = size[0];
        if (localSize_ > kMaxWorkgroupInvocations ||
            localSize_ > ctx.limits().maxComputeWorkGroupInvocations)
            fail(name_, "workgroup of " + std::to_string(localSize_) + " invocations; at most " +
                            std::to_string(kMaxWorkgroupInvocations) + " (WebGPU's limit)");
        VkShaderModule module = createModule(desc.spirv, "compute");
        VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        info.stage.module = module;
        info.stage.pName = "main";
        info.layout = layout_;
        VkResult r = ctx.vk().vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info,
                                                       nullptr, &pipeline_);
        ctx.vk().vkDestroyShaderModule(ctx.device(), module, nullptr);
        check(r, "creating compute pipeline '" + name_ + "'");
    } catch (...) {
        release();
        throw;
    }
}

// GraphicsPipeline -----------------------------------------------------------------------------

GraphicsPipeline::GraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc,
                                   TargetFormat target)
    : Pipeline(ctx, desc.name, desc.storageBuffers, desc.pushConstantBytes, 0,
               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT) {
    for (auto [spirv, stage] : {std::pair{desc.vertexSpirv, "vertex"}, std::pair{desc.fragmentSpirv, "fragment"}})
        if (spirv.size() < 5 || spirv[0] != 0x07230203u)
            fail(name_, std::string("the ") + stage + " shader is not a SPIR-V module");
    compile_ = [this, desc, target] { return create(desc, target); };
}

VkPipeline GraphicsPipeline::create(const GraphicsPipelineDesc& desc, TargetFormat target) const {
    VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
    const auto& vk = ctx_->vk();
    VkPipeline pipeline = VK_NULL_HANDLE;
    try {
        vs = createModule(desc.vertexSpirv, "vertex");
        fs = createModule(desc.fragmentSpirv, "fragment");
        VkPipelineShaderStageCreateInfo stages[2] = {
            {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
             VK_SHADER_STAGE_VERTEX_BIT, vs, "main", nullptr},
            {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
             VK_SHADER_STAGE_FRAGMENT_BIT, fs, "main", nullptr}};
        VkPipelineVertexInputStateCreateInfo vertexInput{
            VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        VkPipelineInputAssemblyStateCreateInfo assembly{
            VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = desc.primitive == Primitive::Lines
                                ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST
                                : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo viewport{
            VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo raster{
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = desc.cull == Cull::Back    ? VK_CULL_MODE_BACK_BIT
                          : desc.cull == Cull::Front ? VK_CULL_MODE_FRONT_BIT
                                                     : VK_CULL_MODE_NONE;
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f; // the only width WebGPU has
        VkPipelineMultisampleStateCreateInfo multisample{
            VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        multisample.rasterizationSamples = static_cast<VkSampleCountFlagBits>(target.samples);
        VkPipelineDepthStencilStateCreateInfo depth{
            VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
        depth.depthTestEnable = VK_TRUE;
        depth.depthWriteEnable = desc.depthWrite ? VK_TRUE : VK_FALSE;
        depth.depthCompareOp = desc.depthTest == DepthTest::Less ? VK_COMPARE_OP_LESS
                               : desc.depthTest == DepthTest::LessOrEqual
                                   ? VK_COMPARE_OP_LESS_OR_EQUAL
                                   : VK_COMPARE_OP_ALWAYS;
        VkPipelineColorBlendAttachmentState attachment{};
        attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                    VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        VkPipelineColorBlendStateCreateInfo blend{
            VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        blend.attachmentCount = 1;
        blend.pAttachments = &attachment;
        VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic{
            VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamicStates;
        VkFormat colorFormat = target.color;
        VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachmentFormats = &colorFormat;
        rendering.depthAttachmentFormat = RenderTarget::kDepthFormat;

        VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                          &rendering};
        info.stageCount = 2;
        info.pStages = stages;
        info.pVertexInputState = &vertexInput;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamic;
        info.layout = layout_;
        VkResult r = vk.vkCreateGraphicsPipelines(ctx_->device(), VK_NULL_HANDLE, 1, &info, nullptr,
                                                  &pipeline);
        check(r, "creating graphics pipeline '" + name_ + "'");
    } catch (...) {
        if (vs) vk.vkDestroyShaderModule(ctx_->device(), vs, nullptr);
        if (fs) vk.vkDestroyShaderModule(ctx_->device(), fs, nullptr);
        throw;
    }
    vk.vkDestroyShaderModule(ctx_->device(), vs, nullptr);
    vk.vkDestroyShaderModule(ctx_->device(), fs, nullptr);
    return pipeline;
}

} // namespace limn::gpu
