// Device selection rules on made-up device lists (no Vulkan needed).
#include "gpu/device_selection.h"

#include <gtest/gtest.h>

using namespace limn::gpu;

namespace {

DeviceCandidate device(std::string name, DeviceType type,
                       std::vector<std::string> unsuitable = {}) {
    return {std::move(name), type, "1.3.0", std::move(unsuitable)};
}

TEST(DeviceSelection, PrefersDiscreteThenIntegratedThenCpu) {
    std::vector<DeviceCandidate> devices = {device("llvmpipe", DeviceType::Cpu),
                                            device("Intel UHD", DeviceType::IntegratedGpu),
                                            device("NVIDIA H100", DeviceType::DiscreteGpu)};
    EXPECT_EQ(chooseDevice(devices, "").index, 2u);
    devices.pop_back();
    EXPECT_EQ(chooseDevice(devices, "").index, 1u);
    devices.pop_back();
    auto c = chooseDevice(devices, "");
    EXPECT_EQ(c.index, 0u);
    ASSERT_EQ(c.report.size(), 1u);
    EXPECT_NE(c.report[0].find("selected"), std::string::npos) << c.report[0];
}

TEST(DeviceSelection, ExplainsEveryRejection) {
    std::vector<DeviceCandidate> devices = {
        device("Old GPU", DeviceType::DiscreteGpu, {"Vulkan 1.1.0 is older than 1.2"}),
        device("llvmpipe (LLVM 15)", DeviceType::Cpu)};
    auto c = chooseDevice(devices, "");
    ASSERT_EQ(c.index, 1u);
    EXPECT_NE(c.report[0].find("skipped: Vulkan 1.1.0 is older than 1.2"), std::string::npos)
        << c.report[0];
    EXPECT_NE(c.report[1].find("selected"), std::string::npos);
}

TEST(DeviceSelection, NameIsCaseInsensitiveSubstring) {
    std::vector<DeviceCandidate> devices = {device("NVIDIA H100", DeviceType::DiscreteGpu),
                                            device("llvmpipe (LLVM 15)", DeviceType::Cpu)};
    auto c = chooseDevice(devices, "LLVMPIPE");
    EXPECT_EQ(c.index, 1u);
    EXPECT_NE(c.report[0].find("name does not contain 'LLVMPIPE'"), std::string::npos)
        << c.report[0];
}

TEST(DeviceSelection, NoMatchListsTheDevicesFound) {
    std::vector<DeviceCandidate> devices = {
        device("llvmpipe (LLVM 15)", DeviceType::Cpu),
        device("Broken", DeviceType::DiscreteGpu, {"no D32 depth attachments"})};
    auto c = chooseDevice(devices, "no-such-device");
    EXPECT_FALSE(c.index);
    EXPECT_NE(c.error.find("no-such-device"), std::string::npos) << c.error;
    EXPECT_NE(c.error.find("'llvmpipe (LLVM 15)' (CPU)"), std::string::npos) << c.error;
    EXPECT_NE(c.error.find("no D32 depth attachments"), std::string::npos) << c.error;
    // A match that is unusable is no match either.
    EXPECT_FALSE(chooseDevice(devices, "broken").index);
}

TEST(DeviceSelection, NoDevicesAtAll) {
    auto c = chooseDevice({}, "");
    EXPECT_FALSE(c.index);
    EXPECT_NE(c.error.find("no Vulkan device found"), std::string::npos) << c.error;
}

TEST(DeviceSelection, TiesKeepEnumerationOrder) {
    std::vector<DeviceCandidate> devices = {device("GPU A", DeviceType::DiscreteGpu),
                                            device("GPU B", DeviceType::DiscreteGpu)};
    EXPECT_EQ(chooseDevice(devices, "").index, 0u);
    EXPECT_EQ(chooseDevice(devices, "gpu b").index, 1u);
}

} // namespace
