// Libraries report non-fatal problems by appending to a Warnings list; tools print them on stderr
// unless -q. Keeping them as data lets tests assert on them.
#pragma once

#include <string>
#include <vector>

namespace limn {

struct Warnings {
    std::vector<std::string> messages;
    void add(std::string message) { messages.push_back(std::move(message)); }
    bool empty() const { return messages.empty(); }
};

} // namespace limn
