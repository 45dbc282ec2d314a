// Shortest round-trip decimal text for doubles and floats (std::to_chars), independent of the
// locale, so text outputs are exact and deterministic.
#pragma once

#include <charconv>
#include <string>

namespace limn {

// The exact shortest text, -0 kept (what a reader must get back bit for bit).
template <class T>
void appendShortest(std::string& out, T value) {
    char buf[32];
    auto [p, ec] = std::to_chars(buf, buf + sizeof buf, value);
    (void)ec;
    out.append(buf, p);
}

template <class T>
void appendNumber(std::string& out, T value) {
    if (value == 0) { // print -0 as 0 so equal surfaces give equal text
        out += '0';
        return;
    }
    appendShortest(out, value);
}

} // namespace limn
