// Which Vulkan device limn runs on, decided from plain data so the rules are testable without a
// GPU (after vk-bootstrap's selector): every device is listed with the reasons it cannot be used,
// and the choice comes with a report that says why each device was taken or skipped (-v prints
// it). `--device NAME` is a case-insensitive substring of the device name; by default a discrete
// GPU beats an integrated one, which beats a virtual GPU, which beats the CPU device (lavapipe).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace limn::gpu {

enum class DeviceType { DiscreteGpu, IntegratedGpu, VirtualGpu, Cpu, Other };

const char* deviceTypeName(DeviceType type); // "discrete GPU", ..., "CPU"

struct DeviceCandidate {
    std::string name;
    DeviceType type = DeviceType::Other;
    std::string apiVersion;              // "1.3.230"
    std::vector<std::string> unsuitable; // why limn cannot run on it; empty when usable
};

struct DeviceChoice {
    std::optional<size_t> index;     // into the candidate list; empty when none fits
    std::vector<std::string> report; // one line per device
    std::string error;               // when no device fits: what went wrong, listing the devices
};

// `wanted` is the --device substring, empty for the default order.
DeviceChoice chooseDevice(const std::vector<DeviceCandidate>& devices, const std::string& wanted);

} // namespace limn::gpu
