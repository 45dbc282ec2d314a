// Compute and graphics pipelines built from embedded SPIR-V, each with one descriptor set of N
// storage buffers (bindings 0..N-1, WebGPU's "bind group") plus push constants. Draws pull their
// vertices from storage buffers by gl_VertexIndex / gl_InstanceIndex: there are no vertex
// buffers, so compute passes and draws share one kind of binding.
//
// Compute push constants start with a 16-byte dispatch header that CommandBuffer::dispatch fills
// (the invocation count for the shader's bounds check, see shaders/limn_compute.glsl); a
// pipeline's own push constants follow at offset 16.
#pragma once

#include "gpu/buffer.h"
#include "gpu/render_target.h"
#include "gpu/vulkan.h"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace limn::gpu {

class Context;

// WebGPU's default maxStorageBuffersPerShaderStage.
inline constexpr uint32_t kMaxStorageBuffersPerPass = 8;
// WebGPU's maxComputeInvocationsPerWorkgroup.
inline constexpr uint32_t kMaxWorkgroupInvocations = 256;
// The dispatch header at the start of every compute pipeline's push constants.
inline constexpr uint32_t kDispatchHeaderBytes = 16;

// A buffer, or part of one, bound to one binding of a pass.
struct BufferBinding {
    const Buffer* buffer = nullptr;
    uint64_t offset = 0;
    uint64_t size = VK_WHOLE_SIZE;                 // to the end of the buffer
    BufferBinding(const Buffer& b) : buffer(&b) {} // NOLINT: implicit on purpose
    BufferBinding(const Buffer& b, uint64_t off, uint64_t bytes)
        : buffer(&b), offset(off), size(bytes) {}
};

// The descriptor set binding buffers to a pipeline's bindings, in binding order.
class BindGroup {
  public:
    BindGroup() = default;
    ~BindGroup();
    BindGroup(BindGroup&& other) noexcept;
    BindGroup& operator=(BindGroup&& other) noexcept;
    BindGroup(const BindGroup&) = delete;
    BindGroup& operator=(const BindGroup&) = delete;
    VkDescriptorSet handle() const { return set_; }

  private:
    friend class Pipeline;
    void release();
    Context* ctx_ = nullptr;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

// What compute and graphics pipelines share: the layout and the bind groups made for it.
class Pipeline {
  public:
    ~Pipeline();
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    // Binds `buffers` to bindings 0..N-1. Checks the count, that each is a storage buffer, the
    // offset alignment and that each range fits the buffer and the 128 MiB limit.
    BindGroup bind(std::initializer_list<BufferBinding> buffers) const;
    BindGroup bind(std::span<const BufferBinding> buffers) const;

    const std::string& name() const { return name_; }
    // The compiled pipeline. A graphics pipeline is compiled here on first use: lavapipe compiles
    // its shaders when the pipeline is created (30-45 ms for the surface draw), and a renderer
    // holds variants that a run may never draw with (the draw without culling beside the one
    // that culls back faces, the draw of evaluated vertices, the wires).
    VkPipeline handle() const;
    VkPipelineLayout layout() const { return layout_; }
    uint32_t storageBuffers() const { return storageBuffers_; }
    uint32_t pushConstantBytes() const { return pushBytes_; } // the pipeline's own, header excluded
    VkShaderStageFlags stages() const { return stages_; }

  protected:
    Pipeline(Context& ctx, std::string name, uint32_t storageBuffers, uint32_t pushBytes,
             uint32_t headerBytes, VkShaderStageFlags stages);
    VkShaderModule createModule(std::span<const uint32_t> spirv, const char* stage) const;
    void release();

    Context* ctx_;
    std::string name_;
    uint32_t storageBuffers_, pushBytes_, headerBytes_;
    VkShaderStageFlags stages_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    mutable VkPipeline pipeline_ = VK_NULL_HANDLE;
    std::function<VkPipeline()> compile_; // a pipeline compiled on first use: creates it
};

struct ComputePipelineDesc {
    std::string name;
    std::span<const uint32_t> spirv; // entry point "main", local size (X, 1, 1)
    uint32_t storageBuffers = 0;
    uint32_t pushConstantBytes = 0; // after the dispatch header
};

class ComputePipeline : public Pipeline {
  public:
    ComputePipeline(Context& ctx, const ComputePipelineDesc& desc);
    uint32_t workgroupSize() const { return localSize_; }

  private:
    uint32_t localSize_ = 0;
};

enum class Primitive { Triangles, Lines };
enum class DepthTest { Less, LessOrEqual, Always };
// Which triangles the rasterizer drops, by their winding on screen (counter-clockwise is front);
// WebGPU's GPUCullMode has the same three.
enum class Cull { None, Back, Front };

struct GraphicsPipelineDesc {
    std::string name;
    std::span<const uint32_t> vertexSpirv, fragmentSpirv;
    uint32_t storageBuffers = 0; // visible to both stages
    uint32_t pushConstantBytes = 0;
    Primitive primitive = Primitive::Triangles;
    DepthTest depthTest = DepthTest::Less;
    bool depthWrite = true;
    Cull cull = Cull::None;
};

// Draws into a RenderTarget of `target`'s format (RGBA8 sRGB or RGBA16F, 1 or 4 samples, D32
// depth) with dynamic rendering. No culling by default: control meshes may be open or
// inconsistently oriented, and the shading is two-sided; a closed surface seen from outside may
// cull its back faces (desc.cull).
class GraphicsPipeline : public Pipeline {
  public:
    // Checks the layout now; compiles on first use (handle()), where a compile error throws.
    GraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc, TargetFormat target = {});

  private:
    VkPipeline create(const GraphicsPipelineDesc& desc, TargetFormat target) const;
};

// The LocalSize a SPIR-V compute module declares, {0,0,0} if none. Throws on a malformed module.
std::array<uint32_t, 3> spirvLocalSize(std::span<const uint32_t> spirv);

} // namespace limn::gpu
