#include "gpu/validation.h"

namespace limn::gpu {

void ValidationLog::record(Severity severity, const std::string& message) {
    std::lock_guard lock(mutex_);
    (severity == Severity::Error ? errors_ : warnings_) += 1;
    if (messages_.size() < kKeptMessages)
        messages_.push_back((severity == Severity::Error ? "error: " : "warning: ") + message);
}

uint32_t ValidationLog::errors() const {
    std::lock_guard lock(mutex_);
    return errors_;
}

uint32_t ValidationLog::warnings() const {
    std::lock_guard lock(mutex_);
    return warnings_;
}

std::vector<std::string> ValidationLog::messages() const {
    std::lock_guard lock(mutex_);
    return messages_;
}

void ValidationLog::clear() {
    std::lock_guard lock(mutex_);
    errors_ = warnings_ = 0;
    messages_.clear();
}

} // namespace limn::gpu
