// fuzz_ply: arbitrary bytes through OpenMesh's PLY reader (input starting with "ply") or OFF
// reader (anything else), behind limn's guards (mesh/openmesh_io.cpp). Anything but
// limn::Error(BadInput) is a bug.
#include "base/error.h"
#include "mesh/openmesh_io.h"
#include "topology/classification.h"

#include <cstdlib>
#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace limn;
    bool ply = size >= 3 && std::memcmp(data, "ply", 3) == 0;
    try {
        Warnings w;
        Mesh m = readWithOpenMesh({data, size}, ply ? ".ply" : ".off", w);
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        classifyMesh(m, topo, resolveSchemeOptions(m.tags, {}), w);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::BadInput) std::abort();
    }
    return 0;
}
