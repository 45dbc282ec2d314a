// fuzz_container: arbitrary bytes through everything a .limn reader does: framing, the mesh
// chunks, and the classification. Anything but limn::Error(BadInput) is a bug.
#include "container/container.h"
#include "base/error.h"
#include "mesh/mesh_chunks.h"
#include "topology/classification.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace limn;
    try {
        Container c = parseContainer({data, size});
        loadMaterial(c); // MATL is optional and independent of the mesh
        Mesh m = loadMesh(c);
        if (const Chunk* clsf = c.find(kClassificationChunk)) decodeClassificationChunk(*clsf, m);
        // A mesh that loads must also classify (what limn-classify and limn-info do next).
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        Warnings w;
        classifyMesh(m, topo, resolveSchemeOptions(m.tags, {}), w);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::BadInput) std::abort();
    }
    return 0;
}
