// Import -> container -> export OBJ -> import preserves positions, faces, UVs and tags exactly.
#include "container/container.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "mesh/obj.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace limn;

namespace {

Mesh roundTrip(const Mesh& in) {
    Container c;
    storeMesh(c, in);
    Mesh fromContainer = loadMesh(parseContainer(serializeContainer(c)));
    std::string text = writeObj(fromContainer);
    Warnings w;
    return readObj({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, w);
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, PreservesEverything) {
    Warnings w;
    Mesh in = importMeshFile(test::modelPath(GetParam()).string(), w);
    Mesh out = roundTrip(in);
    EXPECT_EQ(in.positions, out.positions);
    EXPECT_EQ(in.faceOffsets, out.faceOffsets);
    EXPECT_EQ(in.faceVertices, out.faceVertices);
    EXPECT_EQ(in.uvs, out.uvs);
    EXPECT_EQ(in.uvIndices, out.uvIndices);
    EXPECT_EQ(in.tags, out.tags);
}

INSTANTIATE_TEST_SUITE_P(SharedModels, RoundTrip,
                         ::testing::Values("quad/spot_control_mesh.obj",
                                           "quad/osd_catmark_lefthanded.obj",
                                           "osd/catmark/catmark_cubes_semisharp.obj",
                                           "osd/catmark/catmark_hole_test2.obj",
                                           "osd/catmark/catmark_chaikin1.obj",
                                           "osd/catmark/catmark_fvar_bound2.obj",
                                           "osd/catmark/catmark_smoothtris1.obj",
                                           "gltf/Avocado/Avocado.gltf",
                                           "gltf/BoxTextured/BoxTextured.glb"));

} // namespace
