// The BLND codec: byte layout as formats/limn.md specifies it (read here at the documented
// offsets), round trip, and hostile input (every truncation, out-of-range ids, NaN, bad counts).
#include "base/error.h"
#include "blend/blend_chunk.h"
#include "container/container.h"
#include "mesh/mesh_chunks.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

using namespace limn;
using namespace limn::blend;
using namespace limn::blendtest;

namespace {

template <class T>
T at(const std::vector<uint8_t>& b, size_t offset) {
    T v;
    std::memcpy(&v, b.data() + offset, sizeof v);
    return v;
}
template <class T>
void put(std::vector<uint8_t>& b, size_t offset, T v) {
    std::memcpy(b.data() + offset, &v, sizeof v);
}

struct Fixture {
    Mesh mesh = loadModel("quad/osd_catmark_cube.obj"); // 8 vertices of valence 3, 6 quads
    BlendSurface surface = buildBlendSurface(mesh, topologyOf(mesh), {WeightKind::Quintic, ChartType::Isodistance});
    Chunk chunk = encodeBlendChunk(surface, 0x0123456789abcdefull);
};

void expectRejected(const std::vector<uint8_t>& payload, const std::string& what, uint32_t version = 1) {
    Chunk c{kBlendChunk, version, payload};
    try {
        decodeBlendChunk(c);
        ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        std::string msg = std::string(e.what()) + " @ " + e.where();
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
    }
}

constexpr size_t kVertex0 = 24;
size_t vertexAt(uint32_t v) { return 24 + 128 * size_t(v); }
size_t faceAt(uint32_t V, uint32_t f) { return 24 + 128 * size_t(V) + 32 * size_t(f); }

} // namespace

TEST(BlendChunk, LayoutAsSpecified) {
    Fixture fx;
    const auto& b = fx.chunk.payload;
    ASSERT_EQ(b.size(), 24u + 128 * 8 + 32 * 6);
    EXPECT_EQ(fx.chunk.type, FourCC("BLND"));
    EXPECT_EQ(b[0], 1);                                   // quintic
    EXPECT_EQ(b[1], 2);                                   // isodistance
    EXPECT_EQ(at<uint16_t>(b, 2), 0);
    EXPECT_EQ(at<uint32_t>(b, 4), 8u);                    // V
    EXPECT_EQ(at<uint32_t>(b, 8), 6u);                    // F
    EXPECT_EQ(at<uint32_t>(b, 12), 0u);
    EXPECT_EQ(at<uint64_t>(b, 16), 0x0123456789abcdefull);
    for (uint32_t v = 0; v < 8; ++v) {
        size_t o = vertexAt(v);
        EXPECT_EQ(at<uint32_t>(b, o), 3u);                // k
        EXPECT_EQ(at<uint32_t>(b, o + 4), 0u);            // interior
        EXPECT_EQ(at<float>(b, o + 8), float(2 * std::numbers::pi));
        EXPECT_EQ(at<float>(b, o + 12), 1.0f);            // isodistance: p = 1
        EXPECT_EQ(at<float>(b, o + 16), float(4.0 / 3)); // q = 4/k
        // Coefficients component-major: word 5 + 9c + (a + 3b); c_00 is the vertex.
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(at<float>(b, o + 20 + 36 * c), float(fx.mesh.positions[v][c]));
    }
    for (uint32_t f = 0; f < 6; ++f) {
        size_t o = faceAt(8, f);
        for (uint32_t i = 0; i < 4; ++i) {
            EXPECT_EQ(at<uint32_t>(b, o + 4 * i), fx.mesh.face(f)[i]);
            EXPECT_LT(at<uint32_t>(b, o + 16 + 4 * i), 3u);
        }
    }
}

TEST(BlendChunk, RoundTripRoundsToFloat) {
    Fixture fx;
    DecodedBlend d = decodeBlendChunk(fx.chunk);
    EXPECT_EQ(d.meshHash, 0x0123456789abcdefull);
    EXPECT_EQ(d.surface.weights, WeightKind::Quintic);
    EXPECT_EQ(d.surface.chartType, ChartType::Isodistance);
    ASSERT_EQ(d.surface.vertices.size(), 8u);
    for (size_t v = 0; v < 8; ++v)
        for (size_t n = 0; n < 9; ++n)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(d.surface.vertices[v].coef[n][c], double(float(fx.surface.vertices[v].coef[n][c])));
    for (size_t f = 0; f < 6; ++f) {
        EXPECT_EQ(d.surface.faces[f].vertex, fx.surface.faces[f].vertex);
        EXPECT_EQ(d.surface.faces[f].ring, fx.surface.faces[f].ring);
    }
    // Re-encoding the decoded surface gives the same bytes.
    EXPECT_EQ(encodeBlendChunk(d.surface, d.meshHash).payload, fx.chunk.payload);
}

TEST(BlendChunk, EveryTruncationIsRejected) {
    Fixture fx;
    const auto& full = fx.chunk.payload;
    for (size_t n = 0; n < full.size(); ++n) {
        Chunk c{kBlendChunk, 1, std::vector<uint8_t>(full.begin(), full.begin() + n)};
        EXPECT_THROW(decodeBlendChunk(c), Error) << "prefix of " << n << " bytes";
    }
    auto longer = full;
    longer.resize(full.size() + 8, 0);
    expectRejected(longer, "payload length");
}

TEST(BlendChunk, HostileValuesAreRejected) {
    Fixture fx;
    const auto& good = fx.chunk.payload;
    auto mutate = [&](auto f) {
        auto b = good;
        f(b);
        return b;
    };
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    expectRejected(good, "newer than this limn reads", 2);
    expectRejected(mutate([](auto& b) { b[0] = 2; }), "weights kind");
    expectRejected(mutate([](auto& b) { b[1] = 3; }), "chart type");
    expectRejected(mutate([](auto& b) { b[2] = 1; }), "reserved");
    expectRejected(mutate([](auto& b) { put<uint32_t>(b, 12, 1); }), "reserved");
    expectRejected(mutate([](auto& b) { put<uint32_t>(b, 4, 0xFFFFFFFFu); }), "do not fit");
    expectRejected(mutate([](auto& b) { put<uint32_t>(b, 8, 7); }), "payload length");
    expectRejected(mutate([](auto& b) { put<uint32_t>(b, 8, 0x7FFFFFFFu); }), "payload length");
    expectRejected(mutate([&](auto& b) { put<float>(b, kVertex0 + 20 + 4 * 7, nan); }), "not finite");
    expectRejected(mutate([&](auto& b) { put<float>(b, vertexAt(5) + 20 + 4 * 26, inf); }), "not finite");
    expectRejected(mutate([&](auto& b) { put<float>(b, vertexAt(2) + 8, nan); }), "not finite");
    expectRejected(mutate([&](auto& b) { put<float>(b, vertexAt(2) + 8, 3.0f); }), "angle");
    expectRejected(mutate([&](auto& b) { put<float>(b, vertexAt(2) + 16, 1.0f); }), "q is not");
    expectRejected(mutate([&](auto& b) { put<float>(b, vertexAt(2) + 12, -1.0f); }), "p is out of range");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, vertexAt(3) + 4, 3); }), "chart kind");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, vertexAt(3) + 4, 2); }), "corner chart");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, vertexAt(3), 4); }), "q is not");
    expectRejected(mutate([&](auto& b) {
                       put<uint32_t>(b, vertexAt(3), 4); // a consistent chart with k = 4
                       put<float>(b, vertexAt(3) + 16, 1.0f);
                   }),
                   "add up to");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, faceAt(8, 2) + 4, 8); }), "refers to vertex 8");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, faceAt(8, 2) + 4, at<uint32_t>(b, faceAt(8, 2))); }),
                   "twice");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, faceAt(8, 5) + 16 + 8, 3); }), "is not below k");
    expectRejected(mutate([&](auto& b) { put<uint32_t>(b, faceAt(8, 5) + 16 + 8, 0xFFFFFFFFu); }),
                   "is not below k");
    // Swap the ring indices of two faces at one vertex so one index is used twice.
    expectRejected(mutate([&](auto& b) {
                       const BlendFace& f0 = fx.surface.faces[0];
                       uint32_t v = f0.vertex[0], other = (f0.ring[0] + 1) % 3;
                       put<uint32_t>(b, faceAt(8, 0) + 16, other);
                       (void)v;
                   }),
                   "used twice");
}

TEST(BlendChunk, LoadChecksTheMesh) {
    Mesh mesh = loadModel("quad/osd_catmark_cube.obj");
    Container c;
    storeMesh(c, mesh);
    BlendSurface s = buildBlendSurface(mesh, topologyOf(mesh), {});
    c.set(encodeBlendChunk(s, meshPayloadHash(c)));
    BlendSurface loaded = loadBlendSurface(c, mesh);
    EXPECT_EQ(loaded.faces.size(), 6u);

    Mesh moved = mesh;
    moved.positions[0].x += 0.5;
    Container stale = c;
    storeMesh(stale, moved);
    try {
        loadBlendSurface(stale, moved);
        ADD_FAILURE() << "stale BLND accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("different MESH"), std::string::npos) << e.what();
    }
    Container none;
    storeMesh(none, mesh);
    EXPECT_THROW(loadBlendSurface(none, mesh), Error);
}
