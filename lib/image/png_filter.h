// The five PNG row filters' predictors (ISO/IEC 15948, section 9.2), shared by the encoder and the
// decoder: a is the byte to the left, b the one above, c the one above-left (0 outside the image).
#pragma once

#include <cstdint>
#include <cstdlib>

namespace limn::png {

inline int predict(unsigned filter, int a, int b, int c) {
    switch (filter) {
    case 1:
        return a; // Sub
    case 2:
        return b; // Up
    case 3:
        return (a + b) / 2; // Average
    case 4: {               // Paeth
        const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
        return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
    }
    default:
        return 0; // None
    }
}

} // namespace limn::png
