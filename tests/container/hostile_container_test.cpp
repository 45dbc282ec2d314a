// Hostile .limn input (formats/limn.md section 4): every truncation, bad framing, out-of-range
// counts, indices and values, NaN and Inf. Each must be refused with a clear message and exit
// code 1, in process and through the tools, without a crash or a partial output file.
#include "base/bytes.h"
#include "base/error.h"
#include "container/container.h"
#include "mesh/examples.h"
#include "mesh/mesh_chunks.h"
#include "test_support.h"
#include "topology/classification.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <optional>

using namespace limn;

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
std::vector<uint8_t> triangleMesh(std::vector<uint32_t> corners = {0, 1, 2}) {
    return meshPayload(3, 1, corners.size(), kTriangleXYZ, {uint32_t(corners.size())}, corners);
}

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

std::vector<uint8_t> frame(std::vector<std::pair<const char*, std::vector<uint8_t>>> chunks,
                           uint32_t version = 1) {
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

template <class T>
void poke(std::vector<uint8_t>& bytes, size_t offset, T value) {
    std::memcpy(bytes.data() + offset, &value, sizeof value);
}

// What every reader does with a file: frame, mesh chunks, classification.
void readEverything(std::span<const uint8_t> bytes) {
    Container c = parseContainer(bytes);
    Mesh m = loadMesh(c);
    if (const Chunk* clsf = c.find(kClassificationChunk)) decodeClassificationChunk(*clsf, m);
}

struct Case {
    std::string name;
    std::vector<uint8_t> bytes;
    std::string message;       // a substring of the error
    bool classifyReads = true; // false where only CLSF is bad: limn-classify replaces CLSF
};

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

std::string errorText(const Error& e) {
    return e.where() + ": " + e.what();
}

TEST(HostileContainer, RejectedInProcess) {
    for (const auto& c : cases()) {
        SCOPED_TRACE(c.name);
        try {
            readEverything(c.bytes);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_NE(errorText(e).find(c.message), std::string::npos) << errorText(e);
        }
    }
}

// Lists the directory's entries other than `keep`: no output, no temporary file left behind.
std::vector<std::string> leftovers(const std::filesystem::path& dir, const std::string& keep) {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().filename() != keep) out.push_back(e.path().filename().string());
    return out;
}

TEST(HostileContainer, RejectedByTheTools) {
    for (const auto& c : cases()) {
        SCOPED_TRACE(c.name);
        test::ScratchDir dir;
        std::string input = (dir / "in.limn").string();
        test::writeFile(input, std::string(c.bytes.begin(), c.bytes.end()));

        auto info = test::run({test::tool("limn-info").string(), "--json", input});
        EXPECT_EQ(info.exitCode, 1);
        EXPECT_EQ(info.out, "");
        EXPECT_EQ(info.err.rfind("limn-info: error: " + input + ": ", 0), 0u) << info.err;
        EXPECT_NE(info.err.find(c.message), std::string::npos) << info.err;
        EXPECT_EQ(std::count(info.err.begin(), info.err.end(), '\n'), 1) << info.err;

        if (!c.classifyReads) continue;
        std::string output = (dir / "out.limn").string();
        auto classify = test::run({test::tool("limn-classify").string(), input, "-o", output});
        EXPECT_EQ(classify.exitCode, 1);
        EXPECT_EQ(classify.err.rfind("limn-classify: error: " + input + ": ", 0), 0u)
            << classify.err;
        EXPECT_EQ(leftovers(dir.path(), "in.limn"), std::vector<std::string>{});
    }
}

// Valid containers to cut: the worked triangle, and a creased cube with UVs, every tag kind and
// an unknown chunk.
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

TEST(HostileContainer, EveryTruncatedPrefixIsRejected) {
    for (const auto& bytes : validContainers()) {
        ASSERT_NO_THROW(readEverything(bytes));
        for (size_t n = 0; n < bytes.size(); ++n) {
            try {
                readEverything(std::span(bytes.data(), n));
                ADD_FAILURE() << "prefix of " << n << " bytes accepted";
            } catch (const Error& e) {
                EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            }
        }
    }
}

// A chunk cut short inside a well-framed file: the chunk codecs, not the framing, must notice.
TEST(HostileContainer, EveryTruncatedPayloadIsRejected) {
    for (const auto& bytes : validContainers()) {
        Container whole = parseContainer(bytes);
        for (size_t k = 0; k < whole.chunks.size(); ++k) {
            if (whole.chunks[k].type == FourCC("XTRA")) continue; // opaque: any length is valid
            SCOPED_TRACE(whole.chunks[k].type.str());
            for (size_t n = 0; n < whole.chunks[k].payload.size(); ++n) {
                Container cut = whole;
                cut.chunks[k].payload.resize(n);
                EXPECT_THROW(readEverything(serializeContainer(cut)), Error) << n << " bytes";
            }
        }
    }
}

TEST(HostileContainer, TruncatedFilesThroughLimnInfo) {
    auto bytes = validContainers()[1];
    test::ScratchDir dir;
    std::string path = (dir / "cut.limn").string();
    for (size_t n = 0; n < bytes.size(); n += n < 64 ? 13 : 397) {
        SCOPED_TRACE(n);
        test::writeFile(path, std::string(bytes.begin(), bytes.begin() + n));
        auto r = test::run({test::tool("limn-info").string(), path});
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err.rfind("limn-info: error: " + path + ": ", 0), 0u) << r.err;
        // The same bytes on standard input are refused too (sniffed as .limn or as OBJ).
        auto piped = test::run({test::tool("limn-info").string()},
                               std::string(bytes.begin(), bytes.begin() + n));
        EXPECT_EQ(piped.exitCode, 1) << piped.err;
        EXPECT_EQ(piped.out, "");
    }
}

// Single-bit damage anywhere in a valid file may be accepted (a changed coordinate is still a
// mesh) but must never crash or trip the sanitizers, and errors must be BadInput.
TEST(HostileContainer, EveryBitFlipIsHandled) {
    for (const auto& good : validContainers()) {
        for (size_t i = 0; i < good.size(); ++i)
            for (int bit = 0; bit < 8; ++bit) {
                auto bytes = good;
                bytes[i] ^= uint8_t(1u << bit);
                try {
                    readEverything(bytes);
                } catch (const Error& e) {
                    EXPECT_EQ(e.kind(), ErrorKind::BadInput) << i << ":" << bit;
                }
            }
    }
}

// Readers skip unknown chunks and tools pass them through unchanged (section 3).
TEST(HostileContainer, UnknownChunksPassThroughLimnClassify) {
    auto bytes = frame({{"XTRA", {9, 8, 7}}, {"MESH", triangleMesh()}, {"ZZ_9", {}}});
    auto r = test::run({test::tool("limn-classify").string(), "-"},
                       std::string(bytes.begin(), bytes.end()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    Container out =
        parseContainer(std::span(reinterpret_cast<const uint8_t*>(r.out.data()), r.out.size()));
    std::vector<std::string> order;
    for (const auto& c : out.chunks) order.push_back(c.type.str());
    EXPECT_EQ(order, (std::vector<std::string>{"XTRA", "MESH", "ZZ_9", "TAGS", "CLSF"}));
    EXPECT_EQ(out.find(FourCC("XTRA"))->payload, (std::vector<uint8_t>{9, 8, 7}));
    EXPECT_EQ(out.find(FourCC("XTRA"))->version, 1u);
    EXPECT_TRUE(out.find(FourCC("ZZ_9"))->payload.empty());
}

} // namespace

// MATL (formats/limn.md, 5): what is written reads back; every malformed field is refused with
// the chunk named; a newer version is refused; no MATL reads as none.
TEST(HostileContainer, MaterialChunk) {
    MeshMaterial m;
    m.baseColorFactor = {0.25, 0.5, 1.0, 0.75};
    m.textureBytes = {1, 2, 3, 4, 5};
    m.textureFormat = "texture.png";
    Container c;
    c.set(encodeMaterialChunk(m));
    auto back = loadMaterial(parseContainer(serializeContainer(c)));
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, m);
    EXPECT_EQ(c.chunks[0].payload.size(), 32u + 11u + 5u);
    EXPECT_FALSE(loadMaterial(Container{}));
    MeshMaterial plain; // a factor without a texture
    Container p;
    p.set(encodeMaterialChunk(plain));
    ASSERT_TRUE(loadMaterial(p));
    EXPECT_EQ(*loadMaterial(p), plain);

    auto payload = [](std::array<float, 4> factor, uint32_t n, uint32_t reserved, uint64_t T,
                      std::string name, std::vector<uint8_t> bytes) {
        ByteWriter w;
        for (float f : factor) w.write(f);
        w.write(n);
        w.write(reserved);
        w.write(T);
        w.writeArray(std::vector<uint8_t>(name.begin(), name.end()));
        w.writeArray(bytes);
        return w.take();
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<std::vector<uint8_t>> bad = {
        payload({nan, 1, 1, 1}, 0, 0, 0, "", {}),
        payload({1, 1.5f, 1, 1}, 0, 0, 0, "", {}),
        payload({1, 1, 1, -0.1f}, 0, 0, 0, "", {}),
        payload({1, 1, 1, 1}, 0, 1, 0, "", {}),                      // reserved
        payload({1, 1, 1, 1}, 5, 0, 0, "a.png", {}),                 // name without texture
        payload({1, 1, 1, 1}, 0, 0, 3, "", {1, 2, 3}),               // texture without name
        payload({1, 1, 1, 1}, 5, 0, 3, "a/png", {1, 2, 3}),          // character
        payload({1, 1, 1, 1}, 300, 0, 1, std::string(300, 'a'), {1}), // too long a name
        payload({1, 1, 1, 1}, 5, 0, 4, "a.png", {1, 2, 3}),          // truncated texture
        payload({1, 1, 1, 1}, 5, 0, uint64_t(1) << 62, "a.png", {1}), // huge count
        payload({1, 1, 1, 1}, 5, 0, 1, "a.png", {1, 2}),             // trailing byte
        std::vector<uint8_t>(31, 0),                                 // short header
    };
    for (size_t i = 0; i < bad.size(); ++i) {
        Container b;
        b.set({kMaterialChunk, 1, bad[i]});
        try {
            loadMaterial(b);
            ADD_FAILURE() << "case " << i << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput) << i;
            EXPECT_NE(e.where().find("MATL"), std::string::npos) << i << ": " << e.what();
        }
    }
    Container newer;
    newer.set({kMaterialChunk, 2, c.chunks[0].payload});
    EXPECT_THROW(loadMaterial(newer), Error);
}
