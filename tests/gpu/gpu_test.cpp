// lib/gpu on the machine's Vulkan device (lavapipe here), with the validation layer on: every
// test ends by asserting that the layer reported nothing.
#include "base/error.h"
#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/render_target.h"
#include "gpu_test_shaders.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace limn;
using namespace limn::gpu;

namespace {

class Gpu : public ::testing::Test {
  protected:
    void SetUp() override {
        ContextOptions options;
        options.validation = Validation::Synchronization;
        ctx = std::make_unique<Context>(options);
        ASSERT_NE(ctx->validationLog(), nullptr);
    }
    void TearDown() override {
        if (!ctx) return;
        auto* log = ctx->validationLog();
        EXPECT_EQ(log->errors(), expectedErrors) << join(log->messages());
        EXPECT_EQ(log->warnings(), 0u) << join(log->messages());
    }
    static std::string join(const std::vector<std::string>& lines) {
        std::string s;
        for (const auto& l : lines) s += l + "\n";
        return s;
    }
    std::unique_ptr<Context> ctx;
    uint32_t expectedErrors = 0;
};

TEST_F(Gpu, ContextReportsTheChosenDevice) {
    EXPECT_FALSE(ctx->deviceName().empty());
    EXPECT_GE(ctx->apiVersion(), VK_API_VERSION_1_2);
    ASSERT_FALSE(ctx->selectionReport().empty());
    bool selected = false;
    for (const auto& line : ctx->selectionReport())
        selected |= line.find("selected") != std::string::npos;
    EXPECT_TRUE(selected);
}

TEST(GpuContext, UnknownDeviceIsAMissingCapability) {
    ContextOptions options;
    options.device = "no-such-device";
    try {
        Context ctx(options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Capability);
        EXPECT_NE(std::string(e.what()).find("no-such-device"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("devices found"), std::string::npos) << e.what();
    }
}

// The messenger counts what it is sent: one message injected through debug utils, then one real
// mistake (a buffer with no usage flags) that only the layer can catch.
TEST_F(Gpu, ValidationMessagesAreCounted) {
    auto* log = ctx->validationLog();
    VkDebugUtilsMessengerCallbackDataEXT data{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CALLBACK_DATA_EXT};
    data.pMessage = "limn test message";
    ctx->vk().vkSubmitDebugUtilsMessageEXT(ctx->instance(),
                                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                           VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT, &data);
    EXPECT_EQ(log->errors(), 1u);
    ASSERT_EQ(log->messages().size(), 1u);
    EXPECT_EQ(log->messages()[0], "error: limn test message");

    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 64;
    info.usage = 0; // invalid: VUID-VkBufferCreateInfo-usage-requiredbitmask
    VkBuffer buffer = VK_NULL_HANDLE;
    ctx->vk().vkCreateBuffer(ctx->device(), &info, nullptr, &buffer);
    if (buffer) ctx->vk().vkDestroyBuffer(ctx->device(), buffer, nullptr);
    EXPECT_GE(log->errors(), 2u);
    EXPECT_NE(join(log->messages()).find("VUID-VkBufferCreateInfo-usage"), std::string::npos)
        << join(log->messages());
    log->clear();
}

TEST_F(Gpu, StorageBuffersOverTheWebGpuLimitAreRefused) {
    EXPECT_LE(maxStorageBufferBytes(*ctx), kMaxStorageBufferBytes);
    EXPECT_EQ(maxElementsPerStorageBuffer(*ctx, 16), maxStorageBufferBytes(*ctx) / 16);
    try {
        Buffer big(*ctx, {"vertices L7", kMaxStorageBufferBytes + 16});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        std::string m = e.what();
        EXPECT_NE(m.find("vertices L7"), std::string::npos) << m;
        EXPECT_NE(m.find("split"), std::string::npos) << m;
    }
    // Exactly at the limit is fine (nothing is allocated until now).
    Buffer edge(*ctx, {"edge", maxStorageBufferBytes(*ctx)});
    EXPECT_EQ(edge.size(), maxStorageBufferBytes(*ctx));
}

TEST_F(Gpu, UploadAndReadback) {
    std::vector<uint32_t> values(1001);
    std::iota(values.begin(), values.end(), 7u);
    Buffer b(*ctx, {"values", values.size() * 4});
    uploadArrayNow<uint32_t>(*ctx, b, values);
    EXPECT_EQ(readbackArrayNow<uint32_t>(*ctx, b, values.size()), values);
    // Host buffers bounds-check their mapping.
    Buffer host(*ctx, {"host", 8, 0, MemoryKind::Upload});
    uint8_t bytes[12] = {};
    EXPECT_THROW(host.write(bytes), Error);
    EXPECT_THROW(b.write({bytes, 4}), Error); // device memory is not mapped
}

TEST_F(Gpu, DispatchIsSizedToTheWorkAndBoundsChecked) {
    ComputePipeline scale(*ctx, {"scale", scale_comp_spv, 2, 8});
    EXPECT_EQ(scale.workgroupSize(), 64u);
    const uint32_t count = 1000; // not a multiple of 64: the last group is partly idle
    std::vector<uint32_t> in(count);
    std::iota(in.begin(), in.end(), 0u);
    Buffer src(*ctx, {"in", count * 4}), dst(*ctx, {"out", (count + 64) * 4});
    uploadArrayNow<uint32_t>(*ctx, src, in);
    CommandBuffer cmd(*ctx);
    auto bindings = scale.bind({src, dst});
    struct {
        uint32_t scale, offset;
    } push{3, 5};
    cmd.begin();
    cmd.fill(dst, 0xDEADBEEF);
    cmd.barrier(Access::TransferWrite, Access::ComputeWrite);
    cmd.beginTimed("scale");
    cmd.dispatch(scale, bindings, count, push);
    cmd.endTimed();
    cmd.barrier(Access::ComputeWrite, Access::TransferRead);
    cmd.submitAndWait();
    auto out = readbackArrayNow<uint32_t>(*ctx, dst, count + 64);
    for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(out[i], i * 3 + 5) << i;
    for (uint32_t i = count; i < count + 64; ++i) ASSERT_EQ(out[i], 0xDEADBEEFu) << i;
    auto times = cmd.passTimes();
    ASSERT_EQ(times.size(), 1u);
    EXPECT_EQ(times[0].name, "scale");
    if (ctx->limits().timestamps) {
        EXPECT_GE(times[0].ms, 0.0);
    }
    // Push constants must match the pipeline's declared size.
    cmd.begin();
    EXPECT_THROW(cmd.dispatch(scale, bindings, count, uint32_t(1)), Error);
}

TEST_F(Gpu, LargeDispatchesUseATwoDimensionalGrid) {
    ComputePipeline iota(*ctx, {"iota", iota_comp_spv, 1, 0});
    const uint32_t count = 65535 * 2 + 10; // 131080 workgroups of 1
    Buffer dst(*ctx, {"out", count * 4});
    CommandBuffer cmd(*ctx);
    auto bindings = iota.bind({dst});
    cmd.begin();
    cmd.dispatch(iota, bindings, count);
    cmd.barrier(Access::ComputeWrite, Access::TransferRead);
    cmd.submitAndWait();
    auto out = readbackArrayNow<uint32_t>(*ctx, dst, count);
    for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(out[i], i) << i;
}

TEST_F(Gpu, PipelinesStayWithinWebGpuLimits) {
    EXPECT_THROW(ComputePipeline(*ctx, {"too many", scale_comp_spv, 9, 8}), Error);
    // The same module with its LocalSize literal patched to 512 invocations.
    std::vector<uint32_t> spirv(std::begin(scale_comp_spv), std::end(scale_comp_spv));
    auto size = spirvLocalSize(spirv);
    EXPECT_EQ(size[0], 64u);
    for (size_t i = 5; i + 5 < spirv.size(); i += spirv[i] >> 16) {
        if ((spirv[i] & 0xFFFF) == 16 && spirv[i + 2] == 17) spirv[i + 3] = 512;
    }
    EXPECT_EQ(spirvLocalSize(spirv)[0], 512u);
    try {
        ComputePipeline p(*ctx, {"wide", spirv, 2, 8});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("256"), std::string::npos) << e.what();
    }
    ComputePipeline scale(*ctx, {"scale", scale_comp_spv, 2, 8});
    Buffer a(*ctx, {"a", 64});
    EXPECT_THROW(scale.bind({a}), Error);              // wrong count
    EXPECT_THROW(scale.bind({a, {a, 8, 8}}), Error);   // misaligned offset (>= 16 everywhere)
    EXPECT_THROW(scale.bind({a, {a, 48, 32}}), Error); // past the end
}

// A clear of an odd-sized target, read back through the padded rows.
TEST_F(Gpu, RenderTargetReadbackHonoursRowPitch) {
    RenderTarget target(*ctx, 37, 5);
    EXPECT_EQ(target.rowPitch(), 256u);
    CommandBuffer cmd(*ctx);
    cmd.begin();
    // Linear 0.5 encodes to sRGB 188 (0.7354 * 255 = 187.5...; spec rounding allows 187 or 188).
    cmd.beginRendering(target, {0.5f, 0.0f, 1.0f, 1.0f});
    cmd.endRendering();
    cmd.copyToReadback(target);
    cmd.submitAndWait();
    auto px = target.pixels();
    ASSERT_EQ(px.size(), 37u * 5 * 4);
    for (size_t i = 0; i < px.size(); i += 4) {
        ASSERT_NEAR(px[i], 188, 1) << i;
        ASSERT_EQ(px[i + 1], 0) << i;
        ASSERT_EQ(px[i + 2], 255) << i;
        ASSERT_EQ(px[i + 3], 255) << i;
    }
    EXPECT_THROW(RenderTarget(*ctx, 0, 10), Error);
}

// A 4-sample RGBA16F target with depth kept: the clear is resolved into the single-sample images
// (colour averaged, depth sample 0), copied out through 8-byte and 4-byte padded rows.
TEST_F(Gpu, MultisampledFloatTargetResolvesColourAndDepth) {
    const TargetFormat format{RenderTarget::kLinearFormat, 4};
    RenderTarget target(*ctx, 37, 5, format, true);
    EXPECT_EQ(target.rowPitch(), 512u);  // 37 * 8 = 296 -> 512
    EXPECT_EQ(target.depthRowPitch(), 256u);
    EXPECT_NE(target.colorResolveImage(), VK_NULL_HANDLE);
    EXPECT_NE(target.depthResolveImage(), VK_NULL_HANDLE);
    // Samples x (colour 8 + depth 4), the two resolves, both readbacks.
    EXPECT_EQ(RenderTarget::estimateBytes(37, 5, format, true),
              37u * 5 * (4 * 12 + 8 + 4) + 512u * 5 + 256u * 5);
    CommandBuffer cmd(*ctx);
    cmd.begin();
    cmd.beginRendering(target, {0.25f, 0.5f, 2.0f, 0.0f}); // float: 2 is kept, not clamped
    cmd.endRendering();
    cmd.copyToReadback(target);
    cmd.submitAndWait();
    auto px = target.pixels();
    ASSERT_EQ(px.size(), 37u * 5 * 8);
    // binary16 bits of 0.25, 0.5, 2, 0.
    const uint16_t expected[4] = {0x3400, 0x3800, 0x4000, 0x0000};
    for (size_t i = 0; i < px.size(); i += 2)
        ASSERT_EQ(uint16_t(px[i] | (px[i + 1] << 8)), expected[(i / 2) % 4]) << i;
    auto depth = target.depth();
    ASSERT_EQ(depth.size(), 37u * 5);
    for (float d : depth) ASSERT_EQ(d, 1.0f);
    // WebGPU has 1 and 4 samples only.
    EXPECT_THROW(RenderTarget(*ctx, 8, 8, TargetFormat{RenderTarget::kColorFormat, 2}), Error);
}

} // namespace
