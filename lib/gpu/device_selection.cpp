#include "gpu/device_selection.h"

#include <algorithm>
#include <cctype>

namespace limn::gpu {

namespace {

int rank(DeviceType type) {
    switch (type) {
    case DeviceType::DiscreteGpu:
        return 0;
    case DeviceType::IntegratedGpu:
        return 1;
    case DeviceType::VirtualGpu:
        return 2;
    case DeviceType::Cpu:
        return 3;
    case DeviceType::Other:
        return 4;
    }
    return 5;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string describe(const DeviceCandidate& d, size_t i) {
    return "device " + std::to_string(i) + " '" + d.name + "' (" + deviceTypeName(d.type) +
           ", Vulkan " + d.apiVersion + ")";
}

std::string join(const std::vector<std::string>& parts, const char* separator) {
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : separator) + p;
    return out;
}

} // namespace

const char* deviceTypeName(DeviceType type) {
    switch (type) {
    case DeviceType::DiscreteGpu:
        return "discrete GPU";
    case DeviceType::IntegratedGpu:
        return "integrated GPU";
    case DeviceType::VirtualGpu:
        return "virtual GPU";
    case DeviceType::Cpu:
        return "CPU";
    case DeviceType::Other:
        return "other";
    }
    return "?";
}

DeviceChoice chooseDevice(const std::vector<DeviceCandidate>& devices, const std::string& wanted) {
    DeviceChoice choice;
    const std::string needle = lower(wanted);
    // The best usable device that matches: lowest rank, then enumeration order (stable, so the
    // same machine always picks the same device).
    for (size_t i = 0; i < devices.size(); ++i) {
        const auto& d = devices[i];
        if (!needle.empty() && lower(d.name).find(needle) == std::string::npos) continue;
        if (!d.unsuitable.empty()) continue;
        if (!choice.index || rank(d.type) < rank(devices[*choice.index].type)) choice.index = i;
    }
    for (size_t i = 0; i < devices.size(); ++i) {
        const auto& d = devices[i];
        std::string line = describe(d, i) + ": ";
        if (choice.index == i)
            line +=
                "selected" + std::string(needle.empty() ? "" : " (name matches '" + wanted + "')");
        else if (!needle.empty() && lower(d.name).find(needle) == std::string::npos)
            line += "skipped: name does not contain '" + wanted + "'";
        else if (!d.unsuitable.empty())
            line += "skipped: " + join(d.unsuitable, "; ");
        else
            line += "usable, but a " + std::string(deviceTypeName(devices[*choice.index].type)) +
                    " is preferred";
        choice.report.push_back(line);
    }
    if (choice.index) return choice;

    std::vector<std::string> found;
    for (size_t i = 0; i < devices.size(); ++i) {
        const auto& d = devices[i];
        std::string entry = "'" + d.name + "' (" + deviceTypeName(d.type) + ")";
        if (!d.unsuitable.empty()) entry += " [unusable: " + join(d.unsuitable, "; ") + "]";
        found.push_back(entry);
    }
    if (devices.empty())
        choice.error = "no Vulkan device found; install a Vulkan driver (mesa-vulkan-drivers "
                       "provides the lavapipe CPU device)";
    else if (!needle.empty())
        choice.error = "no usable Vulkan device matches --device '" + wanted +
                       "'; devices found: " + join(found, ", ");
    else
        choice.error = "no usable Vulkan device; devices found: " + join(found, ", ");
    return choice;
}

} // namespace limn::gpu
