#include "mesh/import.h"

#include "base/error.h"
#include "base/io.h"
#include "container/container.h"
#include "mesh/gltf.h"
#include "mesh/mesh_chunks.h"
#include "mesh/obj.h"
#include "mesh/openmesh_io.h"

#include <cstring>
#include <filesystem>

namespace limn {

MeshFormat formatFromExtension(const std::string& ext) {
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".gltf") return MeshFormat::Gltf;
    if (ext == ".glb") return MeshFormat::Glb;
    if (ext == ".ply") return MeshFormat::Ply;
    if (ext == ".off") return MeshFormat::Off;
    if (ext == ".limn") return MeshFormat::Container;
    return MeshFormat::Unknown;
}

MeshFormat formatFromContent(std::span<const uint8_t> bytes) {
    auto startsWith = [&](const char* s) {
        size_t n = std::strlen(s);
        return bytes.size() >= n && std::memcmp(bytes.data(), s, n) == 0;
    };
    if (looksLikeContainer(bytes)) return MeshFormat::Container;
    if (startsWith("glTF")) return MeshFormat::Glb;
    if (startsWith("ply")) return MeshFormat::Ply;
    for (const char* off : {"OFF", "COFF", "NOFF", "STOFF", "CNOFF", "STCOFF", "4OFF", "nOFF"})
        if (startsWith(off)) return MeshFormat::Off;
    size_t i = 0;
    while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' ||
                                bytes[i] == '\n' || bytes[i] == 0xEF || bytes[i] == 0xBB ||
                                bytes[i] == 0xBF))
        ++i;
    if (i < bytes.size() && bytes[i] == '{') return MeshFormat::Gltf;
    return MeshFormat::Obj;
}

const char* formatName(MeshFormat f) {
    switch (f) {
    case MeshFormat::Obj: return "OBJ";
    case MeshFormat::Gltf: return "glTF";
    case MeshFormat::Glb: return "GLB";
    case MeshFormat::Ply: return "PLY";
    case MeshFormat::Off: return "OFF";
    case MeshFormat::Container: return ".limn";
    case MeshFormat::Unknown: break;
    }
    return "unknown";
}

MeshFormat importFormat(const std::string& path, std::span<const uint8_t> bytes) {
    return isStdio(path) ? formatFromContent(bytes) : formatFromExtension(extensionOf(path));
}

Mesh importMesh(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings,
                std::vector<std::string>* filesRead, std::optional<MeshMaterial>* material,
                GltfPolygons* polygons) {
    MeshFormat format = importFormat(path, bytes);
    if (format == MeshFormat::Unknown) {
        Error e(ErrorKind::BadInput, "unknown mesh format '" + extensionOf(path) +
                                         "'; limn reads .obj, .gltf, .glb, .ply, .off and .limn");
        e.setFile(path);
        throw e;
    }
    try {
        switch (format) {
        case MeshFormat::Obj: return readObj(bytes, warnings);
        case MeshFormat::Gltf:
            return readGltf(bytes, false, directoryOf(path), warnings, filesRead, material, polygons);
        case MeshFormat::Glb:
            return readGltf(bytes, true, directoryOf(path), warnings, filesRead, material, polygons);
        case MeshFormat::Ply: return readWithOpenMesh(bytes, ".ply", warnings);
        case MeshFormat::Off: return readWithOpenMesh(bytes, ".off", warnings);
        case MeshFormat::Container: {
            const Container c = parseContainer(bytes);
            if (material)
                if (auto m = loadMaterial(c)) *material = std::move(m);
            return loadMesh(c);
        }
        case MeshFormat::Unknown: break;
        }
    } catch (Error& e) {
        e.setFile(path);
        throw;
    }
    return {};
}

Mesh loadOrImportMesh(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings,
                      std::vector<std::string>* filesRead) {
    if (looksLikeContainer(bytes)) return loadMesh(parseContainer(bytes));
    return importMesh(path, bytes, warnings, filesRead);
}

GltfMorphFrames importGltfMorphFrames(const std::string& path, std::span<const uint8_t> bytes, Warnings& warnings,
                                      const GltfMorphRequest& request) {
    try {
        const MeshFormat format = importFormat(path, bytes);
        if (format != MeshFormat::Gltf && format != MeshFormat::Glb)
            throwBadInput("a morph-target animation is read from a .gltf or .glb file");
        return readGltfMorphFrames(bytes, format == MeshFormat::Glb, directoryOf(path), warnings, request);
    } catch (Error& e) {
        e.setFile(path);
        throw;
    }
}

Mesh importMeshFile(const std::string& path, Warnings& warnings,
                    std::vector<std::string>* filesRead) {
    auto bytes = readInput(path);
    return importMesh(path, bytes, warnings, filesRead);
}

void checkExportPath(const std::string& path) {
    const std::string ext = extensionOf(path);
    if (isStdio(path) || ext == ".obj" || ext == ".ply" || ext == ".off") return;
    // A device or pipe (/dev/null, a FIFO) gets OBJ, like standard output.
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
        !std::filesystem::is_directory(status))
        return;
    throw Error(ErrorKind::Usage, "cannot write '" + path + "': the output format is chosen by " +
                                      "the extension, one of .obj, .ply, .off (standard output " +
                                      "gets OBJ)");
}

std::string exportMesh(const Mesh& mesh, const std::string& path) {
    checkExportPath(path);
    std::string ext = extensionOf(path);
    if (ext == ".ply") return writePly(mesh);
    if (ext == ".off") return writeOff(mesh);
    return writeObj(mesh);
}

} // namespace limn
