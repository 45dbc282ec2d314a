// Vulkan, loaded at run time. limn does not link libvulkan: it dlopen()s the loader, so a machine
// without one still runs the tools and gets a clear "missing capability" error (exit code 3)
// instead of a dynamic-linker failure. Every entry point limn uses is listed once below and lives
// in a per-context table (VulkanFunctions), so two contexts never share function pointers.
#pragma once

#ifndef VK_NO_PROTOTYPES
#define VK_NO_PROTOTYPES
#endif
#include <vulkan/vulkan.h>

#include <string>

namespace limn::gpu {

// X-macros: (name). Global ones are loaded with a null instance.
#define LIMN_VK_GLOBAL_FUNCTIONS(X)                                                                \
    X(vkCreateInstance)                                                                            \
    X(vkEnumerateInstanceVersion)                                                                  \
    X(vkEnumerateInstanceLayerProperties)                                                          \
    X(vkEnumerateInstanceExtensionProperties)

#define LIMN_VK_INSTANCE_FUNCTIONS(X)                                                              \
    X(vkDestroyInstance)                                                                           \
    X(vkEnumeratePhysicalDevices)                                                                  \
    X(vkGetPhysicalDeviceProperties)                                                               \
    X(vkGetPhysicalDeviceProperties2)                                                              \
    X(vkGetPhysicalDeviceFeatures2)                                                                \
    X(vkGetPhysicalDeviceQueueFamilyProperties)                                                    \
    X(vkGetPhysicalDeviceMemoryProperties)                                                         \
    X(vkGetPhysicalDeviceFormatProperties)                                                         \
    X(vkEnumerateDeviceExtensionProperties)                                                        \
    X(vkCreateDevice)                                                                              \
    X(vkGetDeviceProcAddr)                                                                         \
    X(vkCreateDebugUtilsMessengerEXT)                                                              \
    X(vkDestroyDebugUtilsMessengerEXT)                                                             \
    X(vkSubmitDebugUtilsMessageEXT)

// Device functions; the *2 commands of synchronization2 and dynamic rendering are loaded under
// their core names on Vulkan 1.3 and their KHR names on 1.2 (see Context).
#define LIMN_VK_DEVICE_FUNCTIONS(X)                                                                \
    X(vkDestroyDevice)                                                                             \
    X(vkGetDeviceQueue)                                                                            \
    X(vkDeviceWaitIdle)                                                                            \
    X(vkQueueSubmit)                                                                               \
    X(vkCreateBuffer)                                                                              \
    X(vkDestroyBuffer)                                                                             \
    X(vkGetBufferMemoryRequirements)                                                               \
    X(vkAllocateMemory)                                                                            \
    X(vkFreeMemory)                                                                                \
    X(vkBindBufferMemory)                                                                          \
    X(vkBindImageMemory)                                                                           \
    X(vkMapMemory)                                                                                 \
    X(vkUnmapMemory)                                                                               \
    X(vkInvalidateMappedMemoryRanges)                                                              \
    X(vkFlushMappedMemoryRanges)                                                                   \
    X(vkCreateImage)                                                                               \
    X(vkDestroyImage)                                                                              \
    X(vkGetImageMemoryRequirements)                                                                \
    X(vkCreateImageView)                                                                           \
    X(vkDestroyImageView)                                                                          \
    X(vkCreateShaderModule)                                                                        \
    X(vkDestroyShaderModule)                                                                       \
    X(vkCreateDescriptorSetLayout)                                                                 \
    X(vkDestroyDescriptorSetLayout)                                                                \
    X(vkCreateDescriptorPool)                                                                      \
    X(vkDestroyDescriptorPool)                                                                     \
    X(vkAllocateDescriptorSets)                                                                    \
    X(vkUpdateDescriptorSets)                                                                      \
    X(vkCreatePipelineLayout)                                                                      \
    X(vkDestroyPipelineLayout)                                                                     \
    X(vkCreateComputePipelines)                                                                    \
    X(vkCreateGraphicsPipelines)                                                                   \
    X(vkDestroyPipeline)                                                                           \
    X(vkCreateCommandPool)                                                                         \
    X(vkDestroyCommandPool)                                                                        \
    X(vkResetCommandPool)                                                                          \
    X(vkAllocateCommandBuffers)                                                                    \
    X(vkBeginCommandBuffer)                                                                        \
    X(vkEndCommandBuffer)                                                                          \
    X(vkCreateFence)                                                                               \
    X(vkDestroyFence)                                                                              \
    X(vkResetFences)                                                                               \
    X(vkWaitForFences)                                                                             \
    X(vkCreateQueryPool)                                                                           \
    X(vkDestroyQueryPool)                                                                          \
    X(vkGetQueryPoolResults)                                                                       \
    X(vkCmdResetQueryPool)                                                                         \
    X(vkCmdBindPipeline)                                                                           \
    X(vkCmdBindDescriptorSets)                                                                     \
    X(vkCmdPushConstants)                                                                          \
    X(vkCmdDispatch)                                                                               \
    X(vkCmdDispatchIndirect)                                                                       \
    X(vkCmdCopyBuffer)                                                                             \
    X(vkCmdFillBuffer)                                                                             \
    X(vkCmdCopyImageToBuffer)                                                                      \
    X(vkCmdBindIndexBuffer)                                                                        \
    X(vkCmdDraw)                                                                                   \
    X(vkCmdDrawIndexed)                                                                            \
    X(vkCmdDrawIndirect)                                                                           \
    X(vkCmdDrawIndexedIndirect)                                                                    \
    X(vkCmdSetViewport)                                                                            \
    X(vkCmdSetScissor)

#define LIMN_VK_DEVICE_FUNCTIONS_13(X)                                                             \
    X(vkCmdPipelineBarrier2)                                                                       \
    X(vkCmdWriteTimestamp2)                                                                        \
    X(vkCmdBeginRendering)                                                                         \
    X(vkCmdEndRendering)

struct VulkanFunctions {
#define LIMN_VK_DECLARE(name) PFN_##name name = nullptr;
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
    LIMN_VK_GLOBAL_FUNCTIONS(LIMN_VK_DECLARE)
    LIMN_VK_INSTANCE_FUNCTIONS(LIMN_VK_DECLARE)
    LIMN_VK_DEVICE_FUNCTIONS(LIMN_VK_DECLARE)
    LIMN_VK_DEVICE_FUNCTIONS_13(LIMN_VK_DECLARE)
#undef LIMN_VK_DECLARE
};

// Opens the Vulkan loader (libvulkan.so.1) once per process and fills the global entry points.
// Throws Error(Capability) when there is no loader.
void loadGlobalFunctions(VulkanFunctions& vk);
// Fills the instance-level entry points (extension ones may stay null when not enabled).
void loadInstanceFunctions(VulkanFunctions& vk, VkInstance instance);
// Fills the device-level entry points; `core13` picks core or KHR names for the 1.3 commands.
void loadDeviceFunctions(VulkanFunctions& vk, VkDevice device, bool core13);

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" etc.
const char* resultName(VkResult result);

// Throws Error(BadInput) "<what> failed: <result>" unless result is VK_SUCCESS. Out-of-memory
// results say so, since that is what a user can act on.
void check(VkResult result, const std::string& what);

// "1.3.230"
std::string versionString(uint32_t apiVersion);

} // namespace limn::gpu
