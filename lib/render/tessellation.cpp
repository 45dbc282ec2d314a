// What the two tessellations (tessellation.h) share on the host.
#include "render/tessellation.h"

#include <cstring>

namespace limn::render {

std::vector<uint32_t> displacementMapWords(const FloatImage& img) {
    std::vector<uint32_t> w{img.width, img.height};
    w.reserve(2 + size_t(img.width) * img.height);
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
        uint32_t bits;
        std::memcpy(&bits, &img.values[i * img.channels], 4);
        w.push_back(bits);
    }
    return w;
}

} // namespace limn::render
