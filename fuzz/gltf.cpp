// fuzz_gltf: arbitrary bytes through the glTF reader (.glb when they start with its magic, else
// JSON): the pre-pass over extensions, tinygltf, Draco and meshopt decoding, sparse accessors,
// morph targets, the node graph and welding, then classification of whatever it accepts, and the
// morph-target animation reader. Only embedded data is read (readGltfEmbedded): a buffer or image
// URI naming a file is refused, so a mutated input never reads the machine's files. Anything but
// limn::Error(BadInput) is a bug.
#include "base/error.h"
#include "mesh/gltf.h"
#include "topology/classification.h"

#include <cstdlib>
#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace limn;
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    try {
        Warnings w;
        std::optional<MeshMaterial> material;
        Mesh m = readGltfEmbedded({data, size}, binary, w, &material);
        Topology topo(static_cast<uint32_t>(m.vertexCount()), m.faceOffsets, m.faceVertices);
        classifyMesh(m, topo, resolveSchemeOptions(m.tags, {}), w);
        // At the keyframes or 10 frames a second, within limits that keep each run short.
        readGltfMorphFrames({data, size}, binary, "", w,
                            {.fps = size % 2 ? 10.0 : 0.0, .maxFrames = 64, .maxPositionBytes = 16 << 20, .embeddedOnly = true});
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::BadInput) std::abort();
    }
    return 0;
}
