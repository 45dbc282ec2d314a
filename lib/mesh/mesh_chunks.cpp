#include "mesh/mesh_chunks.h"

#include "base/bytes.h"
#include "base/error.h"

#include <cctype>

namespace limn {

namespace {

constexpr uint8_t kUnset = 0xFF;

template <class E>
uint8_t encodeOptional(const std::optional<E>& v) {
    return v ? static_cast<uint8_t>(*v) : kUnset;
}

template <class E>
std::optional<E> decodeOptional(uint8_t v, uint8_t max, const char* what, ByteReader& r) {
    if (v == kUnset) return std::nullopt;
    if (v > max) r.fail(std::string(what) + " value " + std::to_string(v) + " is out of range");
    return static_cast<E>(v);
}

void requireVersion(const Chunk& c, uint32_t supported) {
    if (c.version > supported)
        throwBadInput("chunk " + c.type.str() + " version " + std::to_string(c.version) +
                      " is newer than this limn reads (" + std::to_string(supported) +
                      "); upgrade limn");
}

void requireConsumed(const ByteReader& r) {
    if (!r.atEnd())
        r.fail(std::to_string(r.remaining()) + " unexpected bytes after the last field");
}

} // namespace

Chunk encodeMeshChunk(const Mesh& m) {
    ByteWriter w;
    w.write<uint32_t>(static_cast<uint32_t>(m.vertexCount()));
    w.write<uint32_t>(static_cast<uint32_t>(m.faceCount()));
    w.write<uint64_t>(m.cornerCount());
    for (const auto& p : m.positions) {
        w.write<double>(p.x);
        w.write<double>(p.y);
        w.write<double>(p.z);
    }
    for (size_t f = 0; f < m.faceCount(); ++f) w.write<uint32_t>(m.faceSize(f));
    w.writeArray(m.faceVertices);
    return {kMeshChunk, 1, w.take()};
}

Chunk encodeUVChunk(const Mesh& m) {
    ByteWriter w;
    w.write<uint32_t>(static_cast<uint32_t>(m.uvs.size()));
    w.write<uint32_t>(0);
    w.write<uint64_t>(m.uvIndices.size());
    for (const auto& uv : m.uvs) {
        w.write<double>(uv.x);
        w.write<double>(uv.y);
    }
    w.writeArray(m.uvIndices);
    return {kUVChunk, 1, w.take()};
}

Chunk encodeTagsChunk(const Tags& t) {
    ByteWriter w;
    w.write<uint8_t>(encodeOptional(t.boundary));
    w.write<uint8_t>(encodeOptional(t.fvar));
    w.write<uint8_t>(encodeOptional(t.creaseMethod));
    w.write<uint8_t>(encodeOptional(t.triangles));
    w.write<uint32_t>(static_cast<uint32_t>(t.creases.size()));
    w.write<uint32_t>(static_cast<uint32_t>(t.corners.size()));
    w.write<uint32_t>(static_cast<uint32_t>(t.holes.size()));
    for (const auto& c : t.creases) {
        w.write<uint32_t>(c.v0);
        w.write<uint32_t>(c.v1);
        w.write<float>(c.sharpness);
    }
    for (const auto& c : t.corners) {
        w.write<uint32_t>(c.vertex);
        w.write<float>(c.sharpness);
    }
    w.writeArray(t.holes);
    return {kTagsChunk, 1, w.take()};
}

constexpr uint32_t kMaxTextureFormatName = 255;

Chunk encodeMaterialChunk(const MeshMaterial& m) {
    ByteWriter w;
    for (int c = 0; c < 4; ++c) w.write<float>(static_cast<float>(m.baseColorFactor[c]));
    const std::string format = m.hasTexture() ? m.textureFormat : std::string();
    w.write<uint32_t>(static_cast<uint32_t>(format.size()));
    w.write<uint32_t>(0);
    w.write<uint64_t>(m.textureBytes.size());
    w.writeArray(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(format.data()), format.size()));
    w.writeArray(m.textureBytes);
    return {kMaterialChunk, 1, w.take()};
}

std::optional<MeshMaterial> loadMaterial(const Container& container) {
    const Chunk* chunk = container.find(kMaterialChunk);
    if (!chunk) return std::nullopt;
    requireVersion(*chunk, 1);
    ByteReader r(chunk->payload, "chunk MATL");
    MeshMaterial m;
    for (int c = 0; c < 4; ++c) {
        const float v = r.read<float>();
        if (!(v >= 0.0f && v <= 1.0f))
            r.fail("base colour factor component " + std::to_string(c) + " is not within 0 to 1");
        m.baseColorFactor[c] = v;
    }
    const uint32_t formatLength = r.read<uint32_t>();
    if (r.read<uint32_t>() != 0) r.fail("reserved field is not 0");
    const uint64_t textureLength = r.read<uint64_t>();
    if (formatLength > kMaxTextureFormatName)
        r.fail("texture format name of " + std::to_string(formatLength) + " bytes (at most " +
               std::to_string(kMaxTextureFormatName) + ")");
    if ((formatLength == 0) != (textureLength == 0))
        r.fail("a texture needs a format name, and a format name a texture");
    auto name = r.readBytes(formatLength, "texture format name");
    for (uint8_t ch : name)
        if (!(std::isalnum(ch) || ch == '.' || ch == '_' || ch == '-'))
            r.fail("texture format name holds a character other than A-Z a-z 0-9 . _ -");
    m.textureFormat.assign(name.begin(), name.end());
    m.textureBytes = r.readArray<uint8_t>(textureLength, "texture bytes");
    requireConsumed(r);
    return m;
}

void storeMesh(Container& container, const Mesh& mesh) {
    container.set(encodeMeshChunk(mesh));
    if (mesh.hasUVs())
        container.set(encodeUVChunk(mesh));
    else
        container.remove(kUVChunk);
    container.set(encodeTagsChunk(mesh.tags));
}

Mesh loadMesh(const Container& container) {
    const Chunk* meshChunk = container.find(kMeshChunk);
    if (!meshChunk) throwBadInput("the container has no MESH chunk (was it made by limn-classify?)");
    requireVersion(*meshChunk, 1);
    Mesh m;
    {
        ByteReader r(meshChunk->payload, "chunk MESH");
        uint32_t V = r.read<uint32_t>();
        uint32_t F = r.read<uint32_t>();
        uint64_t C = r.read<uint64_t>();
        auto coords = r.readArray<double>(uint64_t(V) * 3, "positions");
        auto sizes = r.readArray<uint32_t>(F, "face sizes");
        m.faceVertices = r.readArray<uint32_t>(C, "face vertices");
        requireConsumed(r);
        m.positions.resize(V);
        for (size_t i = 0; i < V; ++i)
            m.positions[i] = {coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]};
        m.faceOffsets.assign(1, 0);
        m.faceOffsets.reserve(F + 1);
        uint64_t sum = 0;
        for (uint32_t f = 0; f < F; ++f) {
            sum += sizes[f];
            if (sum > C)
                throwBadInput("face sizes add up to more than the " + std::to_string(C) +
                                  " corners (at face " + std::to_string(f) + ")",
                              "chunk MESH");
            m.faceOffsets.push_back(static_cast<uint32_t>(sum));
        }
        if (sum != C)
            throwBadInput("face sizes add up to " + std::to_string(sum) + ", not the " +
                              std::to_string(C) + " corners stored",
                          "chunk MESH");
    }
    if (const Chunk* uvChunk = container.find(kUVChunk)) {
        requireVersion(*uvChunk, 1);
        ByteReader r(uvChunk->payload, "chunk FVUV");
        uint32_t N = r.read<uint32_t>();
        if (r.read<uint32_t>() != 0) r.fail("reserved field is not zero");
        uint64_t C = r.read<uint64_t>();
        if (C != m.cornerCount())
            r.fail("UV corner count " + std::to_string(C) + " differs from the mesh's " +
                   std::to_string(m.cornerCount()));
        auto values = r.readArray<double>(uint64_t(N) * 2, "UV values");
        m.uvIndices = r.readArray<uint32_t>(C, "UV indices");
        requireConsumed(r);
        m.uvs.resize(N);
        for (size_t i = 0; i < N; ++i) m.uvs[i] = {values[2 * i], values[2 * i + 1]};
    }
    if (const Chunk* tagsChunk = container.find(kTagsChunk)) {
        requireVersion(*tagsChunk, 1);
        ByteReader r(tagsChunk->payload, "chunk TAGS");
        m.tags.boundary = decodeOptional<BoundaryRule>(r.read<uint8_t>(), 2, "boundary rule", r);
        m.tags.fvar = decodeOptional<FVarRule>(r.read<uint8_t>(), 5, "face-varying rule", r);
        m.tags.creaseMethod =
            decodeOptional<CreaseMethod>(r.read<uint8_t>(), 1, "crease method", r);
        m.tags.triangles =
            decodeOptional<TriangleSubdivision>(r.read<uint8_t>(), 1, "triangle rule", r);
        uint32_t nc = r.read<uint32_t>(), nk = r.read<uint32_t>(), nh = r.read<uint32_t>();
        if (nc > r.remaining() / 12) r.fail("crease count " + std::to_string(nc) + " too large");
        m.tags.creases.resize(nc);
        for (auto& c : m.tags.creases) {
            c.v0 = r.read<uint32_t>();
            c.v1 = r.read<uint32_t>();
            c.sharpness = r.read<float>();
        }
        if (nk > r.remaining() / 8) r.fail("corner count " + std::to_string(nk) + " too large");
        m.tags.corners.resize(nk);
        for (auto& c : m.tags.corners) {
            c.vertex = r.read<uint32_t>();
            c.sharpness = r.read<float>();
        }
        m.tags.holes = r.readArray<uint32_t>(nh, "holes");
        requireConsumed(r);
    }
    try {
        validateMesh(m);
    } catch (Error& e) {
        throw Error(e.kind(), e.what(), e.where().empty() ? "mesh chunks" : e.where());
    }
    return m;
}

} // namespace limn
