// The draw data built from a control mesh: fans, holes, edges, Ptex numbering, bounds.
#include "render/control_mesh.h"

#include <gtest/gtest.h>

using namespace limn;
using namespace limn::render;

namespace {

// A quad, a triangle and a pentagon side by side; face 1 (the triangle) is a hole.
Mesh mixedMesh() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0},   {1, 1, 0},   {0, 1, 0}, {2, 0, 0},
                   {3, 0, 0}, {3.5, 1, 0}, {3, 2, 0.5}, {2, 2, 0}, {9, 9, 9}};
    m.addFace(std::vector<uint32_t>{0, 1, 2, 3});
    m.addFace(std::vector<uint32_t>{1, 4, 2});
    m.addFace(std::vector<uint32_t>{4, 5, 6, 7, 8});
    m.tags.holes = {1};
    return m;
}

TEST(ControlMesh, FansSkipHolesAndKeepOrientation) {
    ControlMeshDraw d = prepareControlMesh(mixedMesh());
    EXPECT_EQ(d.drawnFaces, 2u);
    ASSERT_EQ(d.corners.size(), 4u + 5u);
    ASSERT_EQ(d.triangles.size(), 3u * (2 + 3));
    // Quad: corners 0..3 -> (0,1,2), (0,2,3); pentagon: corners 4..8 -> (4,5,6), (4,6,7), (4,7,8).
    std::vector<uint32_t> expected = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 4, 7, 8};
    EXPECT_EQ(d.triangles, expected);
    EXPECT_EQ(d.corners[4].vertex, 4u);
    EXPECT_EQ(d.corners[4].face, 2u);
    EXPECT_EQ(d.corners[8].vertex, 8u);
    // Every face still gets a normal slot (the normal pass runs over all faces).
    EXPECT_EQ(d.faceOffsets.size(), 4u);
}

TEST(ControlMesh, EdgesOfDrawnFacesOnce) {
    ControlMeshDraw d = prepareControlMesh(mixedMesh());
    // Quad 4 + pentagon 5 edges; the hole's edges 1-4 and 4-2 are not drawn, 1-2 is (quad's).
    ASSERT_EQ(d.edges.size(), 2u * 9);
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    for (size_t i = 0; i < d.edges.size(); i += 2) pairs.emplace_back(d.edges[i], d.edges[i + 1]);
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    EXPECT_NE(std::find(pairs.begin(), pairs.end(), std::make_pair(1u, 2u)), pairs.end());
    EXPECT_EQ(std::find(pairs.begin(), pairs.end(), std::make_pair(1u, 4u)), pairs.end());
}

TEST(ControlMesh, PtexNumberingFollowsOpenSubdiv) {
    // Quad: 1 Ptex face, triangle: 3, pentagon: 5.
    EXPECT_EQ(ptexFaceBase(mixedMesh()), (std::vector<uint32_t>{0, 1, 4}));
    ControlMeshDraw d = prepareControlMesh(mixedMesh());
    EXPECT_EQ(d.corners[0].ptex, 0u);
    EXPECT_EQ(d.corners[4].ptex, 4u);
}

TEST(ControlMesh, BoundsCoverDrawnVerticesOnly) {
    ControlMeshDraw d = prepareControlMesh(mixedMesh());
    // Vertex 9 is used by no face: it must not stretch the framing.
    EXPECT_EQ(d.bounds.min, glm::dvec3(0, 0, 0));
    EXPECT_EQ(d.bounds.max, glm::dvec3(3.5, 2, 0.5));
}

TEST(ControlMesh, FloatPositionsAndUVs) {
    Mesh m = mixedMesh();
    m.positions[0] = {0.1, 0.2, 0.3};
    ControlMeshDraw d = prepareControlMesh(m);
    EXPECT_EQ(d.controlPoints[0].x, 0.1f);
    EXPECT_EQ(d.controlPoints[0].w, 1.0f);
    EXPECT_FALSE(d.hasUVs);
    EXPECT_EQ(d.uvs.size(), 1u); // a placeholder so the binding is never empty
}

// Colour textures are packed RGBA8 after a {width, height} header. Grey and grey + alpha images
// are grey in R, G and B (the web runtime's pngjs path expands them the same way); the alpha
// channel is never read as a colour.
TEST(ControlMesh, TextureWordsGreyAndGreyAlphaAreGrey) {
    FloatImage grey;
    grey.width = 2;
    grey.height = 1;
    grey.channels = 1;
    grey.values = {0.0f, 1.0f};
    EXPECT_EQ(textureWords(&grey), (std::vector<uint32_t>{2, 1, 0xFF000000u, 0xFFFFFFFFu}));

    FloatImage greyAlpha;
    greyAlpha.width = 2;
    greyAlpha.height = 1;
    greyAlpha.channels = 2;
    greyAlpha.values = {0.2f, 1.0f, 0.6f, 0.0f}; // (grey, alpha) per texel
    // 0.2 * 255 = 51 = 0x33, 0.6 * 255 = 153 = 0x99.
    EXPECT_EQ(textureWords(&greyAlpha), (std::vector<uint32_t>{2, 1, 0xFF333333u, 0xFF999999u}));

    FloatImage rgba;
    rgba.width = 1;
    rgba.height = 1;
    rgba.channels = 4;
    rgba.values = {1.0f, 0.0f, 0.2f, 0.0f};
    EXPECT_EQ(textureWords(&rgba), (std::vector<uint32_t>{1, 1, 0xFF3300FFu}));
}

} // namespace
