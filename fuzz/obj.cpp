// fuzz_obj: arbitrary bytes through the OBJ reader (with OpenSubdiv tags), then classification of
// whatever it accepts. Anything but limn::Error(BadInput) is a bug.
#include "mesh/obj.h"
#include "base/error.h"
#include "topology/classification.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace limn;
    try {
        Warnings w;
        Mesh m = readObj({data, size}, w);
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        classifyMesh(m, topo, resolveSchemeOptions(m.tags, {}), w);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::BadInput) std::abort();
    }
    return 0;
}
