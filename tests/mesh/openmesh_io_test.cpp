// PLY and OFF through OpenMesh behind limn's guards (mesh/openmesh_io.cpp): valid files read back
// what limn wrote, and hostile headers that made OpenMesh crash, loop for billions of iterations
// or exhaust memory (found by fuzz_ply) are refused with a clear message.
#include "base/error.h"
#include "mesh/examples.h"
#include "mesh/import.h"
#include "mesh/openmesh_io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace limn;
using namespace std::string_literals;

namespace {

Mesh read(const std::string& text, const std::string& ext) {
    Warnings w;
    return readWithOpenMesh({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, ext, w);
}

void expectRefused(const std::string& text, const std::string& ext, const std::string& message) {
    try {
        read(text, ext);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
}

// OpenMesh reads coordinates as float.
void expectSameMesh(const Mesh& a, const Mesh& b, bool uvs) {
    EXPECT_EQ(a.faceOffsets, b.faceOffsets);
    EXPECT_EQ(a.faceVertices, b.faceVertices);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t i = 0; i < a.positions.size(); ++i)
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(a.positions[i][k], b.positions[i][k],
                        1e-6 * (1 + std::abs(a.positions[i][k])));
    if (!uvs) return;
    ASSERT_TRUE(b.hasUVs());
    for (size_t c = 0; c < a.cornerCount(); ++c)
        for (int k = 0; k < 2; ++k)
            EXPECT_NEAR(a.uvs[a.uvIndices[c]][k], b.uvs[b.uvIndices[c]][k], 1e-6);
}

TEST(OpenMeshIO, ReadsBackWhatLimnWrites) {
    for (const auto& e : builtinExamples()) {
        SCOPED_TRACE(e.name);
        expectSameMesh(e.mesh, read(writePly(e.mesh), ".ply"), true);
        expectSameMesh(e.mesh, read(writeOff(e.mesh), ".off"), false);
    }
    Warnings w;
    Mesh spot = importMeshFile(test::modelPath("quad/spot_control_mesh.obj").string(), w);
    expectSameMesh(spot, read(writePly(spot), ".ply"), true);
}

TEST(OpenMeshIO, ReadsBinaryPly) {
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    ply.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const uint8_t n = 3;
    const int32_t face[3] = {0, 1, 2};
    ply.append(reinterpret_cast<const char*>(&n), 1);
    ply.append(reinterpret_cast<const char*>(face), sizeof face);
    Mesh m = read(ply, ".ply");
    EXPECT_EQ(m.faceVertices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(m.positions[1], glm::dvec3(1, 0, 0));
}

const std::string kPlyStart = "ply\nformat ascii 1.0\n";
const std::string kTriangleOff = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";

TEST(OpenMeshIO, RefusesHostilePly) {
    // Found by fuzz_ply: a mangled "element" line left the next "property" line to write through
    // OpenMesh's empty element list (SEGV in _PLYReader_::can_u_read).
    expectRefused(kPlyStart + "property float x\nelement vertex 1\nend_header\n0\n", ".ply",
                  "a property before any element");
    expectRefused(kPlyStart + "element\0\0\0\3 vertex 4\nproperty float x\nend_header\n"s, ".ply",
                  "not text");
    // Also found by fuzz_ply: "end_header" inside a comment ended limn's header check early.
    expectRefused(kPlyStart + "comment the end_header is below\nproperty float x\nend_header\n",
                  ".ply", "a property before any element");
    // Counts the data cannot hold would make OpenMesh add billions of vertices.
    expectRefused(kPlyStart + "element vertex 2000000000\nproperty float x\nproperty float y\n"
                              "property float z\nend_header\n0 0 0\n",
                  ".ply", "promises 2000000000 elements");
    expectRefused(kPlyStart + "element vertex 4\nend_header\n", ".ply", "no properties");
    // Headers OpenMesh reads in quadratic time (100,000 property lines: over a minute) are
    // refused at once; so are list counts it does not read, by name.
    {
        std::string many = kPlyStart + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
        for (int i = 0; i < 100000; ++i) many += "property float p" + std::to_string(i) + "\n";
        expectRefused(many + "end_header\n", ".ply", "element 'vertex' has more than 256 properties");
        std::string elements = kPlyStart;
        for (int i = 0; i < 100000; ++i) elements += "element e" + std::to_string(i) + " 0\n";
        expectRefused(elements + "end_header\n", ".ply", "more than 64 elements");
    }
    expectRefused(kPlyStart + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                              "element face 1\nproperty list ushort int vertex_indices\nend_header\n"
                              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                  ".ply", "a list count of type 'ushort': limn reads uchar, uint8, uint16 or int counts");
    expectRefused(kPlyStart + "element vertex 1\nproperty quaternion q\nend_header\n1\n", ".ply",
                  "with PLY types");
    expectRefused(kPlyStart + "element vertex -1\nproperty float x\nend_header\n", ".ply",
                  "expected 'element NAME COUNT'");
    expectRefused(kPlyStart + "obj_info property x\nelement vertex 1\nend_header\n", ".ply",
                  "obj_info must not contain 'property'");
    expectRefused(kPlyStart + "element vertex 1\nproperty float x\n", ".ply", "no end_header");
    expectRefused("format ascii 1.0\nply\nend_header\n", ".ply", "must start with 'ply'");
    // List lengths longer than the data. Found by fuzz_ply: OpenMesh reserves a custom list
    // (here per-corner UVs) before reading it, 16 GiB for this one.
    const std::string triangle = "element vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 1\n"
                                 "property list int int vertex_indices\n";
    expectRefused(kPlyStart + triangle + "end_header\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n",
                  ".ply", "has a list of length '2000000000', more than the data holds");
    expectRefused(kPlyStart + triangle +
                      "property list uchar float texcoord\nend_header\n"
                      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4294967295 0 0\n",
                  ".ply", "has a list of length '4294967295'");
    expectRefused(kPlyStart + triangle + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", ".ply",
                  "ends early");
    // Also found by fuzz_ply: OpenMesh reads "2-5" as 2 and -5, and the -5 became the length of
    // the next list (reserved as 4 billion floats); limn's count of words was one behind.
    expectRefused(kPlyStart + triangle +
                      "property list uchar float texcoord\nend_header\n"
                      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2-5 0\n",
                  ".ply", "'2-5' is not an integer");
    expectRefused(kPlyStart + triangle + "end_header\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n", ".ply",
                  "'x' is not a number");
    expectRefused(kPlyStart + triangle + "property list int float texcoord\nend_header\n", ".ply",
                  "needs a uchar or uint16 count");
    expectRefused(kPlyStart + "element face 0\nproperty uchar flags\n"
                              "property list uchar int vertex_indices\nend_header\n",
                  ".ply", "must start with its vertex_indices list");
    // In binary PLY OpenMesh reads a face's vertices until the stream fails.
    std::string binary = "ply\nformat binary_little_endian 1.0\n" + triangle + "end_header\n";
    binary.append(36, '\0');
    const int32_t huge = 2000000000;
    binary.append(reinterpret_cast<const char*>(&huge), 4);
    binary.append(12, '\0');
    expectRefused(binary, ".ply", "ends early");
}

TEST(OpenMeshIO, RefusesHostileOff) {
    // OpenMesh reads the face count into an uninitialized variable when it is missing.
    expectRefused("OFF\n3\n", ".off", "needs three counts");
    expectRefused("OFF\n2000000000 1 0\n0 0 0\n", ".off", "promises 2000000000 vertices");
    expectRefused(kTriangleOff + "4000000000 0 1 2\n", ".off", "ends early");
    expectRefused(kTriangleOff + "3 0 1\n", ".off", "ends early");
    expectRefused(kTriangleOff + "3 0 1 x\n", ".off", "malformed value");
    expectRefused("OFF\n3 1 0\n0 0 0\n1 0 0\n", ".off", "ends early");
    // Given a stream, OpenMesh ignores the keyword: binary data would be read as text, COFF face
    // colours as vertex indices.
    expectRefused("OFF BINARY\n\3\0\0\0"s, ".off", "binary OFF is not supported");
    expectRefused("COFF\n3 1 0\n0 0 0 1 1 1 1\n", ".off", "'COFF' is not supported");
    expectRefused("4OFF\n", ".off", "not supported");
    EXPECT_EQ(read(kTriangleOff + "3 0 1 2\n", ".off").faceVertices,
              (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(
        read("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2", ".off").cornerCount(),
        3u);
}

} // namespace
