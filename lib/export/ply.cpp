#include "export/ply.h"

#include "base/bytes.h"
#include "mesh/text_format.h"

#include <algorithm>
#include <charconv>
#include <cstring>

namespace limn::exporting {

std::vector<uint8_t> encodePly(const DrawnMesh& mesh, bool ascii) {
    const size_t triangles = mesh.triangles.size() / 3;
    std::string header = "ply\n";
    header += ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n";
    header += "comment limn-render: the triangles as drawn\n";
    header += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
    for (const char* p : {"x", "y", "z", "nx", "ny", "nz"})
        header += std::string("property float ") + p + "\n";
    header += "property int ptex\nproperty float u\nproperty float v\n";
    if (mesh.hasTexCoords) header += "property float s\nproperty float t\n";
    const bool flags = std::any_of(mesh.vertices.begin(), mesh.vertices.end(),
                                   [](const DrawnVertex& v) { return v.approximate != 0; });
    if (flags) header += "property uchar approximate\n";
    header += "element face " + std::to_string(triangles) + "\n";
    header += "property list uchar int vertex_indices\nend_header\n";

    std::vector<uint8_t> out(header.begin(), header.end());
    if (ascii) {
        std::string body;
        for (const auto& v : mesh.vertices) {
            for (float f : {v.x, v.y, v.z, v.nx, v.ny, v.nz}) {
                appendShortest(body, f);
                body += ' ';
            }
            body += std::to_string(v.ptex) + ' ';
            appendShortest(body, v.u);
            body += ' ';
            appendShortest(body, v.v);
            if (mesh.hasTexCoords) {
                body += ' ';
                appendShortest(body, v.s);
                body += ' ';
                appendShortest(body, v.t);
            }
            if (flags) body += v.approximate ? " 1" : " 0";
            body += '\n';
        }
        for (size_t t = 0; t < triangles; ++t)
            body += "3 " + std::to_string(mesh.triangles[3 * t]) + ' ' +
                    std::to_string(mesh.triangles[3 * t + 1]) + ' ' +
                    std::to_string(mesh.triangles[3 * t + 2]) + '\n';
        out.insert(out.end(), body.begin(), body.end());
        return out;
    }
    out.reserve(out.size() + mesh.vertices.size() * (mesh.hasTexCoords ? 44 : 36) + triangles * 13);
    for (const auto& v : mesh.vertices) {
        for (float f : {v.x, v.y, v.z, v.nx, v.ny, v.nz}) appendRaw(out, f);
        appendRaw(out, v.ptex);
        appendRaw(out, v.u);
        appendRaw(out, v.v);
        if (mesh.hasTexCoords) {
            appendRaw(out, v.s);
            appendRaw(out, v.t);
        }
        if (flags) out.push_back(v.approximate ? 1 : 0);
    }
    for (size_t t = 0; t < triangles; ++t) {
        out.push_back(3);
        for (int k = 0; k < 3; ++k) appendRaw(out, static_cast<int32_t>(mesh.triangles[3 * t + k]));
    }
    return out;
}

} // namespace limn::exporting
