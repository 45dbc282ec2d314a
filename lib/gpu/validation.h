// What the Vulkan validation layer said. The context's debug messenger counts errors and
// warnings and keeps the first messages, so a tool can report "N validation errors" and a test
// can assert zero; nothing is printed by the library.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace limn::gpu {

enum class Validation {
    Off,
    On,              // VK_LAYER_KHRONOS_validation, core checks
    Synchronization, // plus synchronization validation (hazards between passes)
};

class ValidationLog {
  public:
    static constexpr size_t kKeptMessages = 64;

    enum class Severity { Warning, Error };
    void record(Severity severity, const std::string& message);

    uint32_t errors() const;
    uint32_t warnings() const;
    // The first kKeptMessages messages, each prefixed "error: " or "warning: ".
    std::vector<std::string> messages() const;
    void clear();

  private:
    mutable std::mutex mutex_; // the layer may call back from any thread that calls Vulkan
    uint32_t errors_ = 0, warnings_ = 0;
    std::vector<std::string> messages_;
};

} // namespace limn::gpu
