// The hostile containers of hostile_containers.h, each payload written field by field as
// formats/limn.md section 5 lays it out.
#include "hostile_containers.h"

#include "base/bytes.h"
#include "container/container.h"
#include "mesh/examples.h"
#include "mesh/mesh_chunks.h"
#include "topology/classification.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <tuple>

namespace limn::test::hostile {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Payloads written field by field as section 5 lays them out.
std::vector<uint8_t> meshPayload(uint32_t V, uint32_t F, uint64_t C, std::vector<double> xyz,
                                 std::vector<uint32_t> sizes, std::vector<uint32_t> corners) {
    ByteWriter w;
    w.write(V);
    w.write(F);
    w.write(C);
    w.writeArray(xyz);
    w.writeArray(sizes);
    w.writeArray(corners);
    return w.take();
}
const std::vector<double> kTriangleXYZ = {0, 0, 0, 1, 0, 0, 0, 1, 0};

std::vector<uint8_t> uvPayload(uint32_t N, uint32_t reserved, uint64_t C, std::vector<double> uv,
                               std::vector<uint32_t> indices) {
    ByteWriter w;
    w.write(N);
    w.write(reserved);
    w.write(C);
    w.writeArray(uv);
    w.writeArray(indices);
    return w.take();
}

struct TagsSpec {
    uint8_t boundary = 0xFF, fvar = 0xFF, crease = 0xFF, triangles = 0xFF;
    std::vector<std::tuple<uint32_t, uint32_t, float>> creases;
    std::vector<std::pair<uint32_t, float>> corners;
    std::vector<uint32_t> holes;
    std::optional<uint32_t> creaseCount; // a false count, else the real one
};
std::vector<uint8_t> tagsPayload(const TagsSpec& t) {
    ByteWriter w;
    for (uint8_t b : {t.boundary, t.fvar, t.crease, t.triangles}) w.write(b);
    w.write(t.creaseCount.value_or(uint32_t(t.creases.size())));
    w.write(uint32_t(t.corners.size()));
    w.write(uint32_t(t.holes.size()));
    for (auto [a, b, s] : t.creases) {
        w.write(a);
        w.write(b);
        w.write(s);
    }
    for (auto [v, s] : t.corners) {
        w.write(v);
        w.write(s);
    }
    w.writeArray(t.holes);
    return w.take();
}

// The triangle's CLSF payload from the worked example (section 6), to be damaged.
std::vector<uint8_t> triangleClassification() {
    ByteWriter w;
    for (uint8_t b : {uint8_t(1), uint8_t(0), uint8_t(0), uint8_t(5)}) w.write(b);
    for (uint32_t v : {3u, 1u, 3u, 3u, 0u, 0u, 0u}) w.write(v);
    for (uint32_t v : {2u, 2u, 2u, 0x249u, 0x249u, 0x249u, 0x18u}) w.write(v);
    return w.take();
}

template <class T>
void poke(std::vector<uint8_t>& bytes, size_t offset, T value) {
    std::memcpy(bytes.data() + offset, &value, sizeof value);
}

} // namespace

std::vector<uint8_t> triangleMesh(std::vector<uint32_t> corners) {
    return meshPayload(3, 1, corners.size(), kTriangleXYZ, {uint32_t(corners.size())}, corners);
}

std::vector<uint8_t> frame(std::vector<std::pair<const char*, std::vector<uint8_t>>> chunks,
                           uint32_t version) {
    Container c;
    for (auto& [type, payload] : chunks) {
        Chunk chunk;
        std::memcpy(&chunk.type.value, type, 4);
        chunk.version = version;
        chunk.payload = std::move(payload);
        c.chunks.push_back(std::move(chunk));
    }
    return serializeContainer(c);
}

std::vector<Case> cases() {
    std::vector<Case> out;
    auto good = frame({{"MESH", triangleMesh()}, {"CLSF", triangleClassification()}});
    auto with = [&](std::string name, auto change, std::string message) {
        auto bytes = good;
        change(bytes);
        out.push_back({std::move(name), bytes, std::move(message)});
    };
    // Header (section 2 and checklist item 1).
    out.push_back({"empty", {}, "not a .limn container (bad magic)"});
    with(
        "bad_magic", [](auto& b) { b[1] = 'X'; }, "not a .limn container (bad magic)");
    with(
        "text_mode_magic", [](auto& b) { b[4] = '\n'; }, "damaged container magic");
    with(
        "version_2", [](auto& b) { poke<uint32_t>(b, 8, 2); },
        "container version 2 is not supported");
    with(
        "flags", [](auto& b) { poke<uint32_t>(b, 12, 1); }, "reserved header flags are not zero");
    with(
        "length_too_small", [](auto& b) { poke<uint64_t>(b, 16, 24); }, "header says 24 bytes");
    with(
        "trailing_data", [](auto& b) { b.insert(b.end(), 8, 0); }, "truncated or trailing data");
    // Chunk framing (checklist item 2). The MESH chunk header is at offset 24.
    with(
        "chunk_past_end", [](auto& b) { poke<uint64_t>(b, 32, 1u << 30); }, "runs past the end");
    with(
        "chunk_length_huge", [](auto& b) { poke<uint64_t>(b, 32, ~uint64_t(0)); },
        "runs past the end");
    with(
        "chunk_type", [](auto& b) { b[26] = ' '; }, "chunk type is not four characters");
    with(
        "chunk_version_0", [](auto& b) { poke<uint32_t>(b, 28, 0); }, "chunk version 0 is invalid");
    with(
        "half_chunk_header",
        [](auto& b) {
            b.insert(b.end(), {'X', 'T', 'R', 'A', 1, 0, 0, 0});
            poke<uint64_t>(b, 16, b.size());
        },
        "truncated chunk header");
    with(
        "nonzero_padding", [](auto& b) { b.back() = 1; }, "padding bytes are not zero");
    with(
        "mesh_version_2", [](auto& b) { poke<uint32_t>(b, 28, 2); },
        "chunk MESH version 2 is newer");
    out.push_back({"duplicate_chunk", frame({{"MESH", triangleMesh()}, {"MESH", triangleMesh()}}),
                   "chunk type appears twice"});
    out.push_back({"no_mesh", frame({{"XTRA", {1, 2, 3}}}), "no MESH chunk"});
    {
        std::vector<uint8_t> odd(kContainerMagic, kContainerMagic + 8);
        odd.resize(28, 0);
        poke<uint32_t>(odd, 8, 1);
        poke<uint64_t>(odd, 16, 28);
        out.push_back({"length_not_multiple_of_8", odd, "not a multiple of 8"});
    }
    // MESH (checklist items 3 and 4).
    auto mesh = [&](std::string name, std::vector<uint8_t> payload, std::string message) {
        out.push_back({std::move(name), frame({{"MESH", std::move(payload)}}), std::move(message)});
    };
    mesh("face_index_out_of_range", triangleMesh({0, 1, 7}), "face 0 refers to vertex 7");
    mesh("face_index_huge", triangleMesh({0, 1, 0xFFFFFFFFu}), "refers to vertex 4294967295");
    mesh("degenerate_face", triangleMesh({0, 1, 1}), "uses vertex 1 twice");
    mesh("nan_position", meshPayload(3, 1, 3, {0, 0, 0, kNaN, 0, 0, 0, 1, 0}, {3}, {0, 1, 2}),
         "vertex 1 has a non-finite position");
    mesh("inf_position", meshPayload(3, 1, 3, {0, 0, 0, 1, 0, 0, 0, -kInf, 0}, {3}, {0, 1, 2}),
         "vertex 2 has a non-finite position");
    mesh("empty_mesh", meshPayload(0, 0, 0, {}, {}, {}), "the mesh has no vertices");
    mesh("faceless_mesh", meshPayload(3, 0, 0, kTriangleXYZ, {}, {}), "the mesh has no faces");
    mesh("two_gon", meshPayload(3, 1, 2, kTriangleXYZ, {2}, {0, 1}), "a face needs at least 3");
    mesh("sizes_exceed_corners", meshPayload(3, 2, 3, kTriangleXYZ, {3, 3}, {0, 1, 2}),
         "face sizes add up to more than the 3 corners");
    mesh("sizes_short_of_corners", meshPayload(3, 1, 4, kTriangleXYZ, {3}, {0, 1, 2, 0}),
         "face sizes add up to 3, not the 4");
    mesh("vertex_count_huge", meshPayload(0xFFFFFFFFu, 1, 3, kTriangleXYZ, {3}, {0, 1, 2}),
         "positions: 12884901885 entries do not fit");
    mesh("corner_count_huge", meshPayload(3, 1, ~uint64_t(0) / 2, kTriangleXYZ, {3}, {0, 1, 2}),
         "face vertices: 9223372036854775807 entries do not fit");
    mesh(
        "mesh_trailing_bytes",
        [] {
            auto p = triangleMesh();
            p.resize(p.size() + 4);
            return p;
        }(),
        "4 unexpected bytes after the last field");
    mesh("mesh_truncated_field", std::vector<uint8_t>{3, 0, 0, 0, 1, 0}, "truncated");
    // FVUV.
    auto uv = [&](std::string name, std::vector<uint8_t> payload, std::string message) {
        out.push_back({std::move(name),
                       frame({{"MESH", triangleMesh()}, {"FVUV", std::move(payload)}}),
                       std::move(message)});
    };
    uv("uv_index_out_of_range", uvPayload(1, 0, 3, {0, 0}, {0, 5, 0}), "corner 1 refers to UV 5");
    uv("uv_nan", uvPayload(1, 0, 3, {kNaN, 0}, {0, 0, 0}), "UV 0 is not finite");
    uv("uv_inf", uvPayload(1, 0, 3, {0, kInf}, {0, 0, 0}), "UV 0 is not finite");
    uv("uv_beyond_float", uvPayload(1, 0, 3, {1e39, 0}, {0, 0, 0}), "UV 0 is 1e+39 from the origin");
    uv("uv_corner_count", uvPayload(1, 0, 4, {0, 0}, {0, 0, 0, 0}), "UV corner count 4 differs");
    uv("uv_reserved", uvPayload(1, 7, 3, {0, 0}, {0, 0, 0}), "reserved field is not zero");
    uv("uv_count_huge", uvPayload(0x80000000u, 0, 3, {0, 0}, {0, 0, 0}),
       "UV values: 4294967296 entries");
    // TAGS.
    auto tags = [&](std::string name, auto change, std::string message) {
        TagsSpec t;
        change(t);
        out.push_back({std::move(name), frame({{"MESH", triangleMesh()}, {"TAGS", tagsPayload(t)}}),
                       std::move(message)});
    };
    tags(
        "crease_vertex_out_of_range",
        [](TagsSpec& t) {
            t.creases = {{0, 9, 1.0f}};
        },
        "crease tag 0 (0,9) refers to a vertex out of range");
    tags(
        "crease_self",
        [](TagsSpec& t) {
            t.creases = {{1, 1, 1.0f}};
        },
        "joins a vertex to itself");
    tags(
        "crease_nan",
        [](TagsSpec& t) {
            t.creases = {{0, 1, float(kNaN)}};
        },
        "it must be finite and >= 0");
    tags(
        "crease_negative",
        [](TagsSpec& t) {
            t.creases = {{0, 1, -1.0f}};
        },
        "it must be finite and >= 0");
    tags(
        "corner_out_of_range",
        [](TagsSpec& t) {
            t.corners = {{3, 1.0f}};
        },
        "corner tag 0 (vertex 3) refers to a vertex out of range");
    tags(
        "corner_inf",
        [](TagsSpec& t) {
            t.corners = {{0, float(kInf)}};
        },
        "it must be finite and >= 0");
    tags(
        "hole_out_of_range", [](TagsSpec& t) { t.holes = {1}; }, "hole tag 0 refers to face 1");
    tags(
        "boundary_enum", [](TagsSpec& t) { t.boundary = 3; },
        "boundary rule value 3 is out of range");
    tags(
        "fvar_enum", [](TagsSpec& t) { t.fvar = 6; }, "face-varying rule value 6 is out of range");
    tags(
        "crease_count_huge", [](TagsSpec& t) { t.creaseCount = 0xFFFFFFFFu; },
        "crease count 4294967295 too large");
    // CLSF (only readers of CLSF see these; limn-classify recomputes it).
    auto clsf = [&](std::string name, auto change, std::string message) {
        auto payload = triangleClassification();
        change(payload);
        out.push_back({std::move(name), frame({{"MESH", triangleMesh()}, {"CLSF", payload}}),
                       std::move(message), false});
    };
    clsf(
        "clsf_vertex_count", [](auto& p) { poke<uint32_t>(p, 4, 4); },
        "classification is for 4 vertices");
    clsf(
        "clsf_option", [](auto& p) { p[0] = 9; }, "scheme option out of range");
    clsf(
        "clsf_reserved", [](auto& p) { poke<uint32_t>(p, 28, 1); }, "reserved field is not zero");
    clsf(
        "clsf_truncated", [](auto& p) { p.resize(p.size() - 4); },
        "face flags: 1 entries do not fit");
    clsf(
        "clsf_trailing", [](auto& p) { p.resize(p.size() + 4); }, "4 unexpected bytes");
    return out;
}

std::vector<std::vector<uint8_t>> validContainers() {
    Container cube;
    Mesh m = makeCreasedCube();
    m.tags.holes = {3};
    m.tags.boundary = BoundaryRule::EdgeAndCorner;
    storeMesh(cube, m);
    Topology topo(uint32_t(m.vertexCount()), m.faceOffsets, m.faceVertices);
    Warnings w;
    cube.set(encodeClassificationChunk(classifyMesh(m, topo, resolveSchemeOptions(m.tags, {}), w)));
    cube.set({FourCC("XTRA"), 2, {1, 2, 3, 4, 5}});
    return {frame({{"MESH", triangleMesh()},
                   {"TAGS", tagsPayload({})},
                   {"CLSF", triangleClassification()}}),
            serializeContainer(cube)};
}

} // namespace limn::test::hostile
