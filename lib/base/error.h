// The one error type limn's libraries throw. Libraries never print or exit; tools catch Error,
// print `limn-<tool>: error: <file>[:<where>]: <message>` and map the kind to an exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace limn {

// Exit codes every tool documents (brief, "Conventions every tool follows").
enum class ErrorKind : int {
    BadInput = 1,   // bad input or failed processing
    Usage = 2,      // bad command line
    Capability = 3, // missing capability, e.g. no Vulkan device
};

class Error : public std::runtime_error {
public:
    Error(ErrorKind kind, std::string message, std::string where = {})
        : std::runtime_error(message), kind_(kind), where_(std::move(where)) {}

    ErrorKind kind() const { return kind_; }
    // Location inside the input ("line 12", "chunk MESH", "offset 0x40"); may be empty.
    const std::string& where() const { return where_; }
    // The input file the error is about; set by the layer that knows it.
    const std::string& file() const { return file_; }
    Error& setFile(std::string file) {
        if (file_.empty()) file_ = std::move(file);
        return *this;
    }

private:
    ErrorKind kind_;
    std::string where_;
    std::string file_;
};

// Shorthands for the common case.
[[noreturn]] inline void throwBadInput(std::string message, std::string where = {}) {
    throw Error(ErrorKind::BadInput, std::move(message), std::move(where));
}
[[noreturn]] inline void throwUsage(std::string message) {
    throw Error(ErrorKind::Usage, std::move(message));
}

} // namespace limn
