// Shortest round-trip decimal text for doubles and floats (std::to_chars), independent of the
// locale, so text outputs are exact and deterministic.
#pragma once

#include <charconv>
#include <string>

namespace limn {

template <class T>
void appendNumber(std::string& out, T value) {
    char buf[32];
    auto [p, ec] = std::to_chars(buf, buf + sizeof buf, value);
    (void)ec;
    if (value == 0) { // print -0 as 0 so equal surfaces give equal text
        out += '0';
        return;
    }
    out.append(buf, p);
}

} // namespace limn
