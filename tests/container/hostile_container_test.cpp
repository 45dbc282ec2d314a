// Hostile .limn input (formats/limn.md section 4): every truncation, bad framing, out-of-range
// counts, indices and values, NaN and Inf. Each must be refused by the readers with a clear
// message (BadInput) and without a crash; the tools' side is in hostile_container_cli_test.cpp.
#include "base/bytes.h"
#include "base/error.h"
#include "container/container.h"
#include "hostile_containers.h"
#include "mesh/mesh_chunks.h"
#include "topology/classification.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>

using namespace limn;
using namespace limn::test::hostile;

namespace {

// What every reader does with a file: frame, mesh chunks, classification.
void readEverything(std::span<const uint8_t> bytes) {
    Container c = parseContainer(bytes);
    Mesh m = loadMesh(c);
    if (const Chunk* clsf = c.find(kClassificationChunk)) decodeClassificationChunk(*clsf, m);
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
