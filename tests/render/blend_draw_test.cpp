// The blending surface's draw data (CPU, no GPU): the shared-grid tessellation with one owner per
// surface point, and the trim atlas layout. Expected values come from counting (Euler: V + E(K−1)
// + F(K−1)² points), from the CPU evaluator (an owner's (face, u, v) and every face's own (u, v)
// of the same point give the same surface point), and from the layout rule of docs/blend.md.
#include "base/error.h"
#include "blend/blend_surface.h"
#include "render/blend_draw.h"
#include "blend/trim.h"
#include "test_meshes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <map>
#include <set>

using namespace limn;
using namespace limn::render;

namespace {

blend::BlendSurface surfaceOf(const Mesh& m) {
    return blend::buildBlendSurface(m, blendtest::topologyOf(m), {});
}

glm::dvec2 gridUV(uint32_t ij, uint32_t K) {
    return {double(ij & 0xFFFF) / K, double(ij >> 16) / K};
}

TEST(BlendDraw, EveryPointOnceOwnedByTheLowestFace) {
    Mesh m = blendtest::quadrangulated(blendtest::bipyramid(5)); // valences 3, 4, 5
    blend::BlendSurface s = surfaceOf(m);
    Topology topo = blendtest::topologyOf(m);
    for (uint32_t K : {1u, 2u, 5u}) {
        BlendDraw d = prepareBlend(m, s, K);
        const size_t V = m.vertexCount(), E = topo.edgeCount(), F = m.faceCount();
        EXPECT_EQ(d.points.size(), V + E * (K - 1) + F * (K - 1) * (K - 1)) << K;
        EXPECT_EQ(d.drawVertices.size(), F * (K + 1) * (K + 1));
        EXPECT_EQ(d.triangles.size(), F * K * K * 6);
        EXPECT_EQ(d.wireLines.size(), E * K * 2);
        EXPECT_EQ(d.drawnFaces, F);
        // Each draw vertex names a point that is the same surface point: evaluate it from the
        // draw vertex's own face and (u, v), and from the owner's.
        std::map<uint32_t, uint32_t> lowestFace;
        const double diag = blendtest::bboxDiagonal(m);
        for (size_t i = 0; i < d.drawVertices.size(); ++i) {
            const GpuBlendDrawVertex& dv = d.drawVertices[i];
            ASSERT_LT(dv.point, d.points.size());
            EXPECT_EQ(dv.pointFace, d.points[dv.point].face);
            EXPECT_EQ(dv.pointIJ, d.points[dv.point].ij);
            EXPECT_EQ(dv.face, i / ((K + 1) * (K + 1)));
            const uint32_t local = uint32_t(i % ((K + 1) * (K + 1)));
            glm::dvec2 own(double(local % (K + 1)) / K, double(local / (K + 1)) / K);
            glm::dvec2 owner = gridUV(dv.pointIJ, K);
            auto a = blend::evaluateBlendSurface(s, dv.face, own.x, own.y);
            auto b = blend::evaluateBlendSurface(s, dv.pointFace, owner.x, owner.y);
            EXPECT_LE(glm::length(a.position - b.position), 1e-12 * diag) << "draw vertex " << i;
            auto [it, inserted] = lowestFace.try_emplace(dv.point, dv.face);
            if (!inserted) it->second = std::min(it->second, dv.face);
        }
        EXPECT_EQ(lowestFace.size(), d.points.size()) << "a point no face draws";
        for (const auto& [p, f] : lowestFace) EXPECT_EQ(d.points[p].face, f) << "point " << p;
    }
}

TEST(BlendDraw, TrianglesAreCounterClockwiseInTheFaceParameters) {
    Mesh m = blendtest::torus(4, 3, 2.0, 0.5);
    const uint32_t K = 3;
    BlendDraw d = prepareBlend(m, surfaceOf(m), K);
    for (size_t t = 0; t < d.triangles.size(); t += 3) {
        glm::dvec2 p[3];
        for (int k = 0; k < 3; ++k) {
            uint32_t local = d.triangles[t + k] % ((K + 1) * (K + 1));
            p[k] = {double(local % (K + 1)), double(local / (K + 1))};
            EXPECT_EQ(d.drawVertices[d.triangles[t + k]].face, d.drawVertices[d.triangles[t]].face);
        }
        glm::dvec2 a = p[1] - p[0], b = p[2] - p[0];
        EXPECT_DOUBLE_EQ(a.x * b.y - a.y * b.x, 0.5 * 2) << "triangle " << t / 3; // twice 1/2 cell
    }
}

TEST(BlendDraw, HolesAreNotDrawnAndOwnNothing) {
    Mesh m = blendtest::torus(4, 3, 2.0, 0.5);
    m.tags.holes = {0, 5};
    const uint32_t K = 4;
    BlendDraw d = prepareBlend(m, surfaceOf(m), K);
    EXPECT_EQ(d.drawnFaces, m.faceCount() - 2);
    EXPECT_EQ(d.triangles.size(), (m.faceCount() - 2) * K * K * 6);
    std::set<uint32_t> drawn;
    for (const auto& dv : d.drawVertices) drawn.insert(dv.face);
    EXPECT_EQ(drawn.count(0), 0u);
    EXPECT_EQ(drawn.count(5), 0u);
    for (const auto& p : d.points) EXPECT_TRUE(p.face != 0 && p.face != 5);
}

TEST(BlendDraw, RecordsMirrorTheChunk) {
    Mesh m = blendtest::quadrangulated(blendtest::fanDisk(6));
    blend::BlendSurface s = surfaceOf(m);
    BlendDraw d = prepareBlend(m, s, 2);
    ASSERT_EQ(d.vertices.size(), m.vertexCount());
    for (size_t v = 0; v < s.vertices.size(); ++v) {
        EXPECT_EQ(d.vertices[v].k, s.vertices[v].chart.k);
        EXPECT_EQ(d.vertices[v].kind, uint32_t(s.vertices[v].chart.kind));
        EXPECT_EQ(d.vertices[v].q, float(s.vertices[v].chart.q));
        for (int c = 0; c < 3; ++c)
            for (int n = 0; n < 9; ++n)
                EXPECT_EQ(d.vertices[v].coef[9 * c + n], float(s.vertices[v].coef[n][c])); // A.9
    }
    for (size_t f = 0; f < s.faces.size(); ++f)
        for (int i = 0; i < 4; ++i) {
            EXPECT_EQ(d.faces[f].vertex[i], s.faces[f].vertex[i]);
            EXPECT_EQ(d.faces[f].ring[i], s.faces[f].ring[i]);
        }
}

TEST(BlendDraw, GridLimits) {
    Mesh m = blendtest::torus(4, 3, 2.0, 0.5);
    blend::BlendSurface s = surfaceOf(m);
    for (uint32_t K : {0u, kMaxBlendGrid + 1}) {
        try {
            prepareBlend(m, s, K);
            ADD_FAILURE() << K;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Usage);
        }
    }
    Mesh big = blendtest::torus(40, 40, 2.0, 0.5); // 1600 faces at K = 1024: far over 128 MiB
    try {
        prepareBlend(big, surfaceOf(big), kMaxBlendGrid);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("--grid"), std::string::npos) << e.what();
    }
}

// ----------------------------------------------------------------------------------------------

TEST(TrimAtlas, LayoutIsCeilSqrtTilesPerRow) {
    for (uint32_t F : {1u, 2u, 3u, 4u, 5u, 10u, 16u, 17u, 732u}) {
        blend::TrimLayout l = blend::trimAtlasLayout(F, 8);
        uint32_t x = 1;
        while (x * x < F) ++x;
        EXPECT_EQ(l.tilesX, x) << F;
        EXPECT_GE(l.tilesX * l.tilesY, F);
        EXPECT_LT((l.tilesY - 1) * l.tilesX, F);
        EXPECT_EQ(l.width(), x * 8);
    }
    EXPECT_EQ(blend::trimAtlasLayout(732, 32).tilesY, 27u); // 28 × 27 tiles
}

TEST(TrimAtlas, TexelAddressingVRunsUp) {
    blend::TrimLayout l = blend::trimAtlasLayout(5, 4); // 3 × 2 tiles of 4 × 4
    // Face 0's (0,0) corner is the bottom-left texel of the top-left tile.
    EXPECT_EQ(blend::trimTexel(l, 0, 0, 0).x, 0u);
    EXPECT_EQ(blend::trimTexel(l, 0, 0, 0).y, 3u);
    EXPECT_EQ(blend::trimTexel(l, 0, 1, 1).x, 3u); // u = 1 and v = 1 clamp into the tile
    EXPECT_EQ(blend::trimTexel(l, 0, 1, 1).y, 0u);
    EXPECT_EQ(blend::trimTexel(l, 4, 0.3, 0.8).x, 4u + 1);     // face 4: tile (1, 1)
    EXPECT_EQ(blend::trimTexel(l, 4, 0.3, 0.8).y, 4u + 3 - 3); // floor(0.8 · 4) = 3 from the bottom
}

TEST(TrimAtlas, ImageSizeMustBeAnAtlasForTheFaces) {
    Image img;
    img.channels = 1;
    for (auto [w, h, ok] : {std::tuple{6u, 4u, true},
                            {12u, 8u, true},
                            {6u, 6u, false},
                            {7u, 4u, false},
                            {0u, 0u, false}}) {
        img.width = w, img.height = h;
        img.pixels.assign(size_t(w) * h, 255);
        try {
            blend::TrimMask mask = blend::trimMaskFromImage(img, 5); // 3 × 2 tiles
            EXPECT_TRUE(ok) << w << "x" << h;
            EXPECT_EQ(mask.layout.tile, w / 3);
        } catch (const Error& e) {
            EXPECT_FALSE(ok) << w << "x" << h;
            EXPECT_NE(std::string(e.what()).find("3x2"), std::string::npos) << e.what();
        }
    }
}

TEST(TrimAtlas, PatternHolesAndRemovedFaces) {
    blend::TrimPattern p;
    p.tile = 16;
    p.holeRadius = 0.25;
    p.every = 2;
    p.removed = {3};
    Image img = blend::makeTrimAtlas(5, p);
    blend::TrimLayout l = blend::trimAtlasLayout(5, 16);
    ASSERT_EQ(img.width, l.width());
    ASSERT_EQ(img.height, l.height());
    ASSERT_EQ(img.channels, 1u);
    auto at = [&](uint32_t f, double u, double v) {
        blend::TrimTexel t = blend::trimTexel(l, f, u, v);
        return img.pixels[size_t(t.y) * img.width + t.x];
    };
    EXPECT_EQ(at(0, 0.5, 0.5), 0);   // hole (face 0 mod 2 = 0)
    EXPECT_EQ(at(0, 0.9, 0.1), 255); // outside the hole
    EXPECT_EQ(at(1, 0.5, 0.5), 255); // odd faces keep their centre
    EXPECT_EQ(at(2, 0.5, 0.5), 0);
    EXPECT_EQ(at(3, 0.05, 0.95), 0); // removed whole
    EXPECT_EQ(at(4, 0.95, 0.95), 255);
    EXPECT_EQ(img.pixels[size_t(l.height() - 1) * img.width + img.width - 1], 0); // unused tile
}

} // namespace
