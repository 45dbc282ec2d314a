// The Vulkan instance, the chosen device and its one queue. Everything else in lib/gpu is created
// from a Context and must be destroyed before it.
//
// Requirements (a device missing any is skipped, and -v says why): Vulkan 1.2 or newer; dynamic
// rendering and synchronization2 (core in 1.3, extensions on 1.2); a queue family with graphics
// and compute; RGBA8 sRGB colour targets that can be copied out; D32 depth. limn stays inside what
// WebGPU can express, so nothing else is asked for.
#pragma once

#include "gpu/device_selection.h"
#include "gpu/validation.h"
#include "gpu/vulkan.h"

#include <atomic>
#include <memory>
#include <string>
#include <vector>

namespace limn::gpu {

struct ContextOptions {
    std::string device; // case-insensitive substring of the name; empty: default
    Validation validation = Validation::Off;
};

// The limits limn checks against, read once from the device.
struct DeviceLimits {
    uint64_t maxStorageBufferRange = 0;
    uint32_t maxComputeWorkGroupCount[3] = {};
    uint32_t maxComputeWorkGroupInvocations = 0;
    uint32_t maxPushConstantsSize = 0;
    uint32_t maxPerStageDescriptorStorageBuffers = 0;
    uint64_t minStorageBufferOffsetAlignment = 1;
    uint64_t nonCoherentAtomSize = 1;
    uint32_t maxImageDimension2D = 0;
    // Sample counts (VkSampleCountFlags) colour and depth attachments support (MSAA).
    uint32_t colorSampleCounts = 1, depthSampleCounts = 1;
    // Whether multisampling puts its samples at Vulkan's standard locations (WebGPU's 4-sample
    // pattern is the same one): the view-adaptive cull drops elements that cover none of them.
    bool standardSampleLocations = false;
    // Whether fragment shaders may shade each sample on its own (sampleRateShading, enabled when
    // there): the smooth-shaded surfaces then shade every sample they cover, so 4x multisampling
    // also anti-aliases their highlights (WebGPU: @interpolate(perspective, sample)).
    bool sampleRateShading = false;
    // The largest device-local memory heap, in bytes (what a render target must fit into).
    uint64_t deviceLocalHeapBytes = 0;
    bool timestamps = false; // timestamps on the graphics+compute queue
    double timestampPeriodNs = 0;
};

class Context {
  public:
    // Throws Error(Capability) when there is no loader, no device, no device matching
    // options.device, or validation was asked for and the layer is not installed.
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const VulkanFunctions& vk() const { return vk_; }
    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }

    const std::string& deviceName() const { return deviceName_; }
    DeviceType deviceType() const { return deviceType_; }
    uint32_t apiVersion() const { return apiVersion_; }
    const DeviceLimits& limits() const { return limits_; }
    // One line per device: why it was selected or skipped.
    const std::vector<std::string>& selectionReport() const { return report_; }

    // Null when validation is off. Shared so that a caller can read it after the context is
    // gone: destroying the device is when the layer reports objects that were never freed.
    ValidationLog* validationLog() const { return validationLog_.get(); }
    std::shared_ptr<ValidationLog> sharedValidationLog() const { return validationLog_; }

    // A memory type allowed by `typeBits` with all `required` flags, preferring one that also has
    // `preferred`. Throws when none exists.
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                        VkMemoryPropertyFlags preferred, VkMemoryPropertyFlags* chosenFlags) const;

    void waitIdle() const;

    // Bytes of device memory held by this context's buffers and images (for --bench).
    uint64_t allocatedBytes() const { return allocatedBytes_; }
    void noteAllocation(int64_t delta) { allocatedBytes_ += static_cast<uint64_t>(delta); }

  private:
    void createInstance(const ContextOptions& options);
    void createDevice(VkPhysicalDevice physical, bool core13);
    void release();

    VulkanFunctions vk_;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    std::string deviceName_;
    DeviceType deviceType_ = DeviceType::Other;
    uint32_t apiVersion_ = 0;
    DeviceLimits limits_;
    VkPhysicalDeviceMemoryProperties memory_{};
    std::vector<std::string> report_;
    std::shared_ptr<ValidationLog> validationLog_;
    std::atomic<uint64_t> allocatedBytes_{0};
};

} // namespace limn::gpu
