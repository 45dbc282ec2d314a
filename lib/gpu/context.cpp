#include "gpu/context.h"

#include "base/error.h"

#include <algorithm>
#include <cstring>

namespace limn::gpu {

namespace {

constexpr uint32_t kNoFamily = ~0u;
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    auto* log = static_cast<ValidationLog*>(user);
    std::string text = data && data->pMessage ? data->pMessage : "(no message)";
    log->record(severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT
                    ? ValidationLog::Severity::Error
                    : ValidationLog::Severity::Warning,
                text);
    return VK_FALSE; // never abort the call: the layer reports, limn decides
}

DeviceType toDeviceType(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return DeviceType::DiscreteGpu;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return DeviceType::IntegratedGpu;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return DeviceType::VirtualGpu;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return DeviceType::Cpu;
    default:
        return DeviceType::Other;
    }
}

bool hasExtension(const std::vector<VkExtensionProperties>& list, const char* name) {
    return std::any_of(list.begin(), list.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

std::vector<VkExtensionProperties> deviceExtensions(const VulkanFunctions& vk,
                                                    VkPhysicalDevice pd) {
    uint32_t n = 0;
    vk.vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> list(n);
    vk.vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, list.data());
    list.resize(n);
    return list;
}

uint32_t graphicsComputeFamily(const VulkanFunctions& vk, VkPhysicalDevice pd,
                               uint32_t* validBits) {
    uint32_t n = 0;
    vk.vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vk.vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < n; ++i)
        if ((families[i].queueFlags & need) == need) {
            if (validBits) *validBits = families[i].timestampValidBits;
            return i;
        }
    return kNoFamily;
}

// Why limn cannot run on this device (empty: it can). Only devices of Vulkan 1.2+ are queried
// further, since the feature structs below are not defined for older ones.
std::vector<std::string> unsuitableReasons(const VulkanFunctions& vk, VkPhysicalDevice pd,
                                           const VkPhysicalDeviceProperties& props) {
    std::vector<std::string> why;
    if (props.apiVersion < VK_API_VERSION_1_2) {
        why.push_back("Vulkan " + versionString(props.apiVersion) + " is older than 1.2");
        return why;
    }
    const bool core13 = props.apiVersion >= VK_API_VERSION_1_3;
    auto extensions = deviceExtensions(vk, pd);
    VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    VkPhysicalDeviceSynchronization2Features sync2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES, &dynamicRendering};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &sync2};
    bool dynExt = core13 || hasExtension(extensions, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
    bool syncExt = core13 || hasExtension(extensions, VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME);
    vk.vkGetPhysicalDeviceFeatures2(pd, &features);
    if (!dynExt || !dynamicRendering.dynamicRendering) why.push_back("no dynamic rendering");
    if (!syncExt || !sync2.synchronization2) why.push_back("no synchronization2");
    if (graphicsComputeFamily(vk, pd, nullptr) == kNoFamily)
        why.push_back("no queue family with graphics and compute");
    VkFormatProperties color{}, depth{};
    vk.vkGetPhysicalDeviceFormatProperties(pd, kColorFormat, &color);
    vk.vkGetPhysicalDeviceFormatProperties(pd, kDepthFormat, &depth);
    const VkFormatFeatureFlags colorNeed =
        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if ((color.optimalTilingFeatures & colorNeed) != colorNeed)
        why.push_back("cannot render to and copy from RGBA8 sRGB images");
    if (!(depth.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
        why.push_back("no D32 depth attachments");
    return why;
}

} // namespace

Context::Context(const ContextOptions& options) {
    try {
        createInstance(options);
        uint32_t count = 0;
        check(vk_.vkEnumeratePhysicalDevices(instance_, &count, nullptr),
              "vkEnumeratePhysicalDevices");
        std::vector<VkPhysicalDevice> physical(count);
        if (count)
            check(vk_.vkEnumeratePhysicalDevices(instance_, &count, physical.data()),
                  "vkEnumeratePhysicalDevices");
        physical.resize(count);

        std::vector<DeviceCandidate> candidates;
        std::vector<VkPhysicalDeviceProperties> props(physical.size());
        for (size_t i = 0; i < physical.size(); ++i) {
            vk_.vkGetPhysicalDeviceProperties(physical[i], &props[i]);
            DeviceCandidate c;
            c.name = props[i].deviceName;
            c.type = toDeviceType(props[i].deviceType);
            c.apiVersion = versionString(props[i].apiVersion);
            c.unsuitable = unsuitableReasons(vk_, physical[i], props[i]);
            candidates.push_back(std::move(c));
        }
        DeviceChoice choice = chooseDevice(candidates, options.device);
        report_ = choice.report;
        if (!choice.index) throw Error(ErrorKind::Capability, choice.error);

        const auto& p = props[*choice.index];
        physical_ = physical[*choice.index];
        deviceName_ = p.deviceName;
        deviceType_ = candidates[*choice.index].type;
        apiVersion_ = p.apiVersion;
        uint32_t validBits = 0;
        queueFamily_ = graphicsComputeFamily(vk_, physical_, &validBits);
        const auto& l = p.limits;
        limits_.maxStorageBufferRange = l.maxStorageBufferRange;
        std::copy(l.maxComputeWorkGroupCount, l.maxComputeWorkGroupCount + 3,
                  limits_.maxComputeWorkGroupCount);
        limits_.maxComputeWorkGroupInvocations = l.maxComputeWorkGroupInvocations;
        limits_.maxPushConstantsSize = l.maxPushConstantsSize;
        limits_.maxPerStageDescriptorStorageBuffers = l.maxPerStageDescriptorStorageBuffers;
        limits_.minStorageBufferOffsetAlignment = l.minStorageBufferOffsetAlignment;
        limits_.nonCoherentAtomSize = l.nonCoherentAtomSize;
        limits_.maxImageDimension2D = l.maxImageDimension2D;
        limits_.colorSampleCounts = l.framebufferColorSampleCounts;
        limits_.depthSampleCounts = l.framebufferDepthSampleCounts;
        limits_.standardSampleLocations = l.standardSampleLocations == VK_TRUE;
        VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        vk_.vkGetPhysicalDeviceFeatures2(physical_, &supported);
        limits_.sampleRateShading = supported.features.sampleRateShading == VK_TRUE;
        limits_.timestamps = l.timestampComputeAndGraphics && validBits > 0;
        limits_.timestampPeriodNs = l.timestampPeriod;
        vk_.vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
        for (uint32_t i = 0; i < memory_.memoryHeapCount; ++i)
            if (memory_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
                limits_.deviceLocalHeapBytes =
                    std::max<uint64_t>(limits_.deviceLocalHeapBytes, memory_.memoryHeaps[i].size);
        createDevice(physical_, p.apiVersion >= VK_API_VERSION_1_3);
    } catch (...) {
        release(); // a constructor that throws gets no destructor call
        throw;
    }
}

void Context::createInstance(const ContextOptions& options) {
    loadGlobalFunctions(vk_);
    uint32_t instanceVersion = VK_API_VERSION_1_0;
    if (vk_.vkEnumerateInstanceVersion) vk_.vkEnumerateInstanceVersion(&instanceVersion);
    if (instanceVersion < VK_API_VERSION_1_2)
        throw Error(ErrorKind::Capability, "the Vulkan loader supports only Vulkan " +
                                               versionString(instanceVersion) + "; limn needs 1.2");

    std::vector<const char*> layers, extensions;
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    VkValidationFeatureEnableEXT syncFeature =
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT validationFeatures{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    const void* next = nullptr;
    if (options.validation != Validation::Off) {
        uint32_t n = 0;
        vk_.vkEnumerateInstanceLayerProperties(&n, nullptr);
        std::vector<VkLayerProperties> available(n);
        vk_.vkEnumerateInstanceLayerProperties(&n, available.data());
        bool found =
            std::any_of(available.begin(), available.begin() + n, [](const VkLayerProperties& l) {
                return std::strcmp(l.layerName, kValidationLayer) == 0;
            });
        if (!found)
            throw Error(ErrorKind::Capability,
                        std::string("validation was asked for, but the layer ") + kValidationLayer +
                            " is not installed (Debian: vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        validationLog_ = std::make_shared<ValidationLog>();
        messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
        messengerInfo.pfnUserCallback = onDebugMessage;
        messengerInfo.pUserData = validationLog_.get();
        // Chained into the instance create info, the messenger also sees messages from
        // vkCreateInstance and vkDestroyInstance themselves.
        next = &messengerInfo;
        if (options.validation == Validation::Synchronization) {
            extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
            validationFeatures.enabledValidationFeatureCount = 1;
            validationFeatures.pEnabledValidationFeatures = &syncFeature;
            validationFeatures.pNext = &messengerInfo;
            next = &validationFeatures;
        }
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "limn";
    app.pEngineName = "limn";
    app.apiVersion = VK_API_VERSION_1_3; // the newest limn uses; 1.2 devices are handled
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, next};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkResult r = vk_.vkCreateInstance(&info, nullptr, &instance_);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
        throw Error(ErrorKind::Capability, std::string("cannot create a Vulkan instance (") +
                                               resultName(r) + "); is a Vulkan driver installed?");
    if (r == VK_ERROR_LAYER_NOT_PRESENT || r == VK_ERROR_EXTENSION_NOT_PRESENT)
        throw Error(ErrorKind::Capability,
                    std::string("cannot enable Vulkan validation (") + resultName(r) + ")");
    check(r, "vkCreateInstance");
    loadInstanceFunctions(vk_, instance_);
    if (validationLog_)
        check(vk_.vkCreateDebugUtilsMessengerEXT(instance_, &messengerInfo, nullptr, &messenger_),
              "vkCreateDebugUtilsMessengerEXT");
}

void Context::createDevice(VkPhysicalDevice physical, bool core13) {
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily_;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    // The same feature structs serve 1.3 (core) and 1.2 (extensions): they are aliases.
    VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    dynamicRendering.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceSynchronization2Features sync2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES, &dynamicRendering};
    sync2.synchronization2 = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &sync2};
    features.features.sampleRateShading = limits_.sampleRateShading ? VK_TRUE : VK_FALSE;

    std::vector<const char*> extensions;
    if (!core13) {
        extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
        extensions.push_back(VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME);
    }
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    check(vk_.vkCreateDevice(physical, &info, nullptr, &device_), "vkCreateDevice");
    loadDeviceFunctions(vk_, device_, core13);
    vk_.vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
}

Context::~Context() {
    release();
}

void Context::release() {
    if (device_) {
        vk_.vkDeviceWaitIdle(device_);
        vk_.vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        vk_.vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vk_.vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                             VkMemoryPropertyFlags preferred,
                             VkMemoryPropertyFlags* chosenFlags) const {
    uint32_t best = kNoFamily;
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
        VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
        if (!(typeBits & (1u << i)) || (flags & required) != required) continue;
        if ((flags & preferred) == preferred) {
            best = i;
            break;
        }
        if (best == kNoFamily) best = i;
    }
    if (best == kNoFamily)
        throw Error(ErrorKind::Capability, "the Vulkan device has no suitable memory type");
    if (chosenFlags) *chosenFlags = memory_.memoryTypes[best].propertyFlags;
    return best;
}

void Context::waitIdle() const {
    check(vk_.vkDeviceWaitIdle(device_), "vkDeviceWaitIdle");
}

} // namespace limn::gpu
