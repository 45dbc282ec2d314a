#include "gpu/vulkan.h"

#include "base/error.h"

#include <dlfcn.h>
#include <mutex>

namespace limn::gpu {

namespace {

// The loader stays open for the life of the process: function pointers taken from it may be held
// by any context, and unloading Mesa's drivers at exit is a known source of crashes.
PFN_vkGetInstanceProcAddr openLoader() {
    static std::once_flag once;
    static PFN_vkGetInstanceProcAddr getProc = nullptr;
    std::call_once(once, [] {
        void* lib = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!lib) lib = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
        if (lib)
            getProc =
                reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(lib, "vkGetInstanceProcAddr"));
    });
    return getProc;
}

} // namespace

void loadGlobalFunctions(VulkanFunctions& vk) {
    vk.vkGetInstanceProcAddr = openLoader();
    if (!vk.vkGetInstanceProcAddr)
        throw Error(ErrorKind::Capability,
                    "no Vulkan loader (libvulkan.so.1) found; install libvulkan1 and a Vulkan "
                    "driver, e.g. mesa-vulkan-drivers for the lavapipe CPU device");
#define LIMN_VK_LOAD(name)                                                                         \
    vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(nullptr, #name));
    LIMN_VK_GLOBAL_FUNCTIONS(LIMN_VK_LOAD)
#undef LIMN_VK_LOAD
    if (!vk.vkCreateInstance)
        throw Error(ErrorKind::Capability, "the Vulkan loader lacks vkCreateInstance");
}

void loadInstanceFunctions(VulkanFunctions& vk, VkInstance instance) {
#define LIMN_VK_LOAD(name)                                                                         \
    vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(instance, #name));
    LIMN_VK_INSTANCE_FUNCTIONS(LIMN_VK_LOAD)
#undef LIMN_VK_LOAD
}

void loadDeviceFunctions(VulkanFunctions& vk, VkDevice device, bool core13) {
    auto get = [&](const char* name) {
        PFN_vkVoidFunction f = vk.vkGetDeviceProcAddr(device, name);
        if (!f)
            throw Error(ErrorKind::Capability,
                        std::string("the Vulkan device lacks the entry point ") + name);
        return f;
    };
#define LIMN_VK_LOAD(name) vk.name = reinterpret_cast<PFN_##name>(get(#name));
    LIMN_VK_DEVICE_FUNCTIONS(LIMN_VK_LOAD)
#undef LIMN_VK_LOAD
    std::string suffix = core13 ? "" : "KHR";
#define LIMN_VK_LOAD(name) vk.name = reinterpret_cast<PFN_##name>(get((#name + suffix).c_str()));
    LIMN_VK_DEVICE_FUNCTIONS_13(LIMN_VK_LOAD)
#undef LIMN_VK_LOAD
}

const char* resultName(VkResult result) {
    switch (result) {
#define LIMN_CASE(r)                                                                               \
    case r:                                                                                        \
        return #r;
        LIMN_CASE(VK_SUCCESS)
        LIMN_CASE(VK_NOT_READY)
        LIMN_CASE(VK_TIMEOUT)
        LIMN_CASE(VK_INCOMPLETE)
        LIMN_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        LIMN_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        LIMN_CASE(VK_ERROR_INITIALIZATION_FAILED)
        LIMN_CASE(VK_ERROR_DEVICE_LOST)
        LIMN_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        LIMN_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        LIMN_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        LIMN_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        LIMN_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        LIMN_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        LIMN_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        LIMN_CASE(VK_ERROR_UNKNOWN)
#undef LIMN_CASE
    default:
        return "VkResult error";
    }
}

void check(VkResult result, const std::string& what) {
    if (result == VK_SUCCESS) return;
    std::string message = what + " failed: " + resultName(result);
    if (result == VK_ERROR_OUT_OF_HOST_MEMORY || result == VK_ERROR_OUT_OF_DEVICE_MEMORY)
        message += " (the scene needs more memory than the device has; lower --size or the depth)";
    throw Error(ErrorKind::BadInput, message);
}

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

} // namespace limn::gpu
