// KHR_draco_mesh_compression: the primitive's bitstream decoded by Google's Draco library
// (Debian's libdraco), which also undoes its quantization. Draco's points are the primitive's
// vertices and its faces its triangles, in the decoder's order.
#include "mesh/gltf_parts.h"

#include "base/error.h"

#include <draco/compression/decode.h>

namespace limn::gltf {

void decodeDraco(const tinygltf::Model& model, const DracoPrimitive& draco, const std::string& what,
                 PrimitiveData& out) {
    const std::string where = what + " (KHR_draco_mesh_compression)";
    if (draco.bufferView < 0 || draco.bufferView >= static_cast<int>(model.bufferViews.size()))
        throwBadInput(where + ": buffer view " + std::to_string(draco.bufferView) + " does not exist");
    const auto& view = model.bufferViews[draco.bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
        throwBadInput(where + ": the buffer view refers to a missing buffer");
    const auto& buffer = model.buffers[view.buffer].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        throwBadInput(where + ": the buffer view runs past its buffer");

    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok() || !decoded.value())
        throwBadInput(where + ": the Draco data does not decode (" + decoded.status().error_msg_string() + ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();

    auto attribute = [&](const std::string& name, int components) -> const draco::PointAttribute* {
        auto it = draco.attributes.find(name);
        if (it == draco.attributes.end()) return nullptr;
        const draco::PointAttribute* a = mesh->GetAttributeByUniqueId(uint32_t(it->second));
        if (!a) throwBadInput(where + ": " + name + " is Draco attribute " + std::to_string(it->second) + ", which the data lacks");
        if (a->num_components() < components)
            throwBadInput(where + ": " + name + " has " + std::to_string(a->num_components()) + " components");
        return a;
    };
    const draco::PointAttribute* position = attribute("POSITION", 3);
    if (!position) throwBadInput(where + ": no POSITION among the compressed attributes");
    const draco::PointAttribute* texcoord = attribute("TEXCOORD_0", 2);

    const size_t points = mesh->num_points();
    out.positions.resize(points);
    if (texcoord) out.texcoords.resize(points);
    for (draco::PointIndex p(0); p < uint32_t(points); ++p) {
        float xyz[3] = {0, 0, 0}, uv[2] = {0, 0};
        if (!position->ConvertValue<float, 3>(position->mapped_index(p), xyz))
            throwBadInput(where + ": POSITION of point " + std::to_string(p.value()) + " does not convert");
        out.positions[p.value()] = {xyz[0], xyz[1], xyz[2]};
        if (texcoord) {
            if (!texcoord->ConvertValue<float, 2>(texcoord->mapped_index(p), uv))
                throwBadInput(where + ": TEXCOORD_0 of point " + std::to_string(p.value()) + " does not convert");
            out.texcoords[p.value()] = {uv[0], uv[1]};
        }
    }
    out.indices.resize(size_t(mesh->num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        const auto& face = mesh->face(f);
        for (int k = 0; k < 3; ++k) {
            const uint32_t i = face[k].value();
            if (i >= points) throwBadInput(where + ": a face refers to point " + std::to_string(i) + " of " + std::to_string(points));
            out.indices[size_t(f.value()) * 3 + size_t(k)] = i;
        }
    }
    out.hasIndices = true;
}

} // namespace limn::gltf
