// fuzz_png: arbitrary bytes through limn's own PNG decoder (lib/image/png_decode.cpp), which reads
// every displacement and texture map that is a common PNG. Anything but Error(BadInput) is a bug.
#include "base/error.h"
#include "image/png_decode.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace limn;
    try {
        auto img = decodePngCommon({data, size});
        if (img && img->values.size() != size_t(img->width) * img->height * img->channels) std::abort();
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::BadInput) std::abort();
    }
    return 0;
}
