// The one surface material limn keeps from an input mesh: glTF's metallic-roughness base colour
// (factor and texture). The texture stays encoded (PNG, JPEG, ... as stored in the asset): the
// mesh layer does not decode images (lib/image is a layer below it); limn-render decodes it.
#pragma once

#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace limn {

struct MeshMaterial {
    // glTF's baseColorFactor: linear RGBA, multiplies the texture. (1, 1, 1, 1) when the asset
    // gives none.
    glm::dvec4 baseColorFactor{1.0};
    // The baseColorTexture's image file bytes, or empty when there is none.
    std::vector<uint8_t> textureBytes;
    // A file name whose extension names the texture's format ("texture.png", "texture.jpg"), for
    // the image reader; empty without a texture.
    std::string textureFormat;
    bool hasTexture() const { return !textureBytes.empty(); }
    bool operator==(const MeshMaterial&) const = default;
};

} // namespace limn
