// EXT_meshopt_compression and KHR_meshopt_compression: each compressed buffer view is decoded by
// meshoptimizer's own decoders into the bytes of the view it stands for (its fallback buffer),
// before any accessor is read; the filters are meshoptimizer's too.
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <meshoptimizer.h>

namespace limn::gltf {

namespace {

// The most bytes the decoded views may hold in all: the cap limn puts on an input file.
constexpr uint64_t kMaxDecodedBytes = uint64_t(4) << 30;

} // namespace

void decodeMeshopt(tinygltf::Model& model, const Prepass& prepass) {
    uint64_t placeholders = 0;
    for (const auto& [b, length] : prepass.placeholderBuffers) {
        if (b < 0 || b >= static_cast<int>(model.buffers.size())) continue;
        placeholders += length;
        if (length > kMaxDecodedBytes || placeholders > kMaxDecodedBytes)
            throwBadInput("glTF: fallback buffer " + std::to_string(b) + " declares " + std::to_string(length) +
                          " bytes, more than limn reads (4 GiB in all)");
        model.buffers[b].data.assign(size_t(length), 0);
    }
    uint64_t decoded = 0;
    for (const auto& [v, m] : prepass.meshopt) {
        const std::string what = "glTF: buffer view " + std::to_string(v) + " (" + m.extension + ")";
        if (v >= static_cast<int>(model.bufferViews.size())) throwBadInput(what + " does not exist");
        const auto& view = model.bufferViews[v];
        if (m.buffer < 0 || m.buffer >= static_cast<int>(model.buffers.size()))
            throwBadInput(what + ": compressed data in buffer " + std::to_string(m.buffer) + ", which does not exist");
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
            throwBadInput(what + ": refers to a missing buffer");
        const auto& source = model.buffers[m.buffer].data;
        if (m.byteOffset > source.size() || m.byteLength > source.size() - m.byteOffset)
            throwBadInput(what + ": compressed data runs past the end of buffer " + std::to_string(m.buffer));
        if (m.byteStride == 0 || m.byteStride > 256 || m.count > kMaxDecodedBytes / m.byteStride)
            throwBadInput(what + ": byteStride " + std::to_string(m.byteStride) + " or count " +
                          std::to_string(m.count) + " is out of range");
        const uint64_t size = m.byteStride * m.count;
        decoded += size;
        if (decoded > kMaxDecodedBytes) throwBadInput(what + ": the decoded views hold more than 4 GiB");
        auto& target = model.buffers[view.buffer].data;
        if (view.byteLength != size)
            throwBadInput(what + ": the view's byteLength " + std::to_string(view.byteLength) +
                          " is not byteStride times count (" + std::to_string(size) + ")");
        if (view.byteOffset > target.size() || size > target.size() - view.byteOffset)
            throwBadInput(what + ": the decoded data runs past the end of buffer " + std::to_string(view.buffer));
        if (m.buffer == view.buffer)
            throwBadInput(what + ": the compressed data and the view are in the same buffer");
        uint8_t* out = target.data() + view.byteOffset;
        const uint8_t* in = source.data() + m.byteOffset;
        int rc = -1;
        if (m.mode == "ATTRIBUTES") {
            if (m.byteStride % 4) throwBadInput(what + ": byteStride of ATTRIBUTES must be a multiple of 4");
            // Version 1 of the attribute codec (KHR only) is newer than Debian 12's meshoptimizer.
            if (m.byteLength > 0 && in[0] == 0xA1)
                throwBadInput(what + ": the data uses version 1 of the attribute codec, which the "
                                     "meshoptimizer " + std::to_string(MESHOPTIMIZER_VERSION / 100) + "." +
                              std::to_string(MESHOPTIMIZER_VERSION % 100) +
                              " limn is built with does not decode; re-encode with version 0 (EXT_meshopt_compression)");
            rc = meshopt_decodeVertexBuffer(out, size_t(m.count), size_t(m.byteStride), in, size_t(m.byteLength));
        } else if (m.mode == "TRIANGLES" || m.mode == "INDICES") {
            if (m.byteStride != 2 && m.byteStride != 4)
                throwBadInput(what + ": byteStride of " + m.mode + " must be 2 or 4");
            if (m.mode == "TRIANGLES" && m.count % 3) throwBadInput(what + ": TRIANGLES count is not a multiple of 3");
            rc = m.mode == "TRIANGLES"
                     ? meshopt_decodeIndexBuffer(out, size_t(m.count), size_t(m.byteStride), in, size_t(m.byteLength))
                     : meshopt_decodeIndexSequence(out, size_t(m.count), size_t(m.byteStride), in, size_t(m.byteLength));
        } else {
            throwBadInput(what + ": unknown mode '" + m.mode + "' (ATTRIBUTES, TRIANGLES or INDICES)");
        }
        if (rc != 0) throwBadInput(what + ": the compressed data does not decode (meshoptimizer error " + std::to_string(rc) + ")");
        if (m.filter == "NONE") continue;
        if (m.mode != "ATTRIBUTES") throwBadInput(what + ": a filter on " + m.mode + " data");
        if (m.filter == "OCTAHEDRAL" && (m.byteStride == 4 || m.byteStride == 8))
            meshopt_decodeFilterOct(out, size_t(m.count), size_t(m.byteStride));
        else if (m.filter == "QUATERNION" && m.byteStride == 8)
            meshopt_decodeFilterQuat(out, size_t(m.count), size_t(m.byteStride));
        else if (m.filter == "EXPONENTIAL")
            meshopt_decodeFilterExp(out, size_t(m.count), size_t(m.byteStride));
        else if (m.filter == "COLOR")
            throwBadInput(what + ": the COLOR filter is newer than the meshoptimizer " +
                          std::to_string(MESHOPTIMIZER_VERSION / 100) + "." + std::to_string(MESHOPTIMIZER_VERSION % 100) +
                          " limn is built with");
        else
            throwBadInput(what + ": filter '" + m.filter + "' with byteStride " + std::to_string(m.byteStride) +
                          " is not one glTF defines");
    }
}

} // namespace limn::gltf
