// Quads back from triangles (joinTrianglePairs), measured on real meshes: Keenan Crane's spot as
// published triangulated (tests/data/tri/spot_triangulated.obj) against spot's own quads
// (tests/data/quad/spot_quadrangulated.obj, the same vertices and UVs), spot's coarse control
// mesh split along alternating diagonals here, and all-triangle remeshed scans that have no
// quads to find. The surface check is OpenSubdiv's limit (tests/support/osd_oracle.h).
#include "base/warnings.h"
#include "mesh/import.h"
#include "osd_oracle.h"
#include "test_support.h"
#include "topology/quad_pairs.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <numbers>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

using namespace limn;

namespace {

Mesh load(const std::string& relative) {
    Warnings w;
    return importMeshFile(test::modelPath(relative).string(), w);
}

// A face as its corners rotated to start at the smallest vertex (orientation kept).
std::vector<uint32_t> canonical(std::span<const uint32_t> face) {
    std::vector<uint32_t> f(face.begin(), face.end());
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
}

// How many of `reference`'s quads are faces of `mesh`, same corners in the same cyclic order.
size_t quadCount(const Mesh& m) {
    size_t n = 0;
    for (size_t f = 0; f < m.faceCount(); ++f) n += m.faceSize(f) == 4;
    return n;
}

size_t quadsFound(const Mesh& mesh, const Mesh& reference) {
    std::set<std::vector<uint32_t>> faces;
    for (size_t f = 0; f < mesh.faceCount(); ++f) faces.insert(canonical(mesh.face(f)));
    size_t found = 0;
    for (size_t f = 0; f < reference.faceCount(); ++f)
        found += reference.faceSize(f) == 4 && faces.count(canonical(reference.face(f)));
    return found;
}

// Every quad split along one diagonal, alternating between the two by face index (as an
// exporter's triangulation may), UVs kept per corner; other faces kept.
Mesh triangulate(const Mesh& m) {
    Mesh out;
    out.positions = m.positions;
    out.uvs = m.uvs;
    out.tags = m.tags;
    for (size_t f = 0; f < m.faceCount(); ++f) {
        auto v = m.face(f);
        if (v.size() != 4) { // kept as it is
            out.addFace(v);
            if (m.hasUVs())
                for (uint32_t uv : m.faceUVs(f)) out.uvIndices.push_back(uv);
            continue;
        }
        const int s = int(f % 2);
        const uint32_t t[2][3] = {{0u + s, 1u + s, 2u + s}, {2u + s, (3u + s) % 4, 0u + s}};
        for (const auto& tri : t) {
            const uint32_t face[3] = {v[tri[0]], v[tri[1]], v[tri[2] % 4]};
            out.addFace(face);
            if (m.hasUVs())
                for (uint32_t k : tri) out.uvIndices.push_back(m.faceUVs(f)[k % 4]);
        }
    }
    return out;
}

// The limit position of every vertex and of every quad's centre agree between `a` and `b`
// within `tolerance` (quads matched by their corners).
double limitDifference(const Mesh& a, const Mesh& b) {
    const SchemeOptions options = resolveSchemeOptions(a.tags, std::nullopt);
    const test::OsdLimitSurface sa(a, options), sb(b, options);
    auto vertexLimits = [&](const Mesh& m, const test::OsdLimitSurface& s) {
        std::map<int, glm::dvec3> limits;
        for (int ptex = 0; ptex < s.ptexFaceCount(); ++ptex)
            for (auto [u, v] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}) {
                const int vertex = test::baseVertexAt(m, uint32_t(ptex), u, v);
                glm::dvec3 p, n;
                if (vertex >= 0 && s.evaluate(ptex, u, v, p, n)) limits[vertex] = p;
            }
        return limits;
    };
    const auto la = vertexLimits(a, sa), lb = vertexLimits(b, sb);
    double worst = 0;
    EXPECT_EQ(la.size(), lb.size());
    for (const auto& [v, p] : la) worst = std::max(worst, glm::length(p - lb.at(v)));
    // Each quad's centre, quads matched by corners; a quad is one ptex face, an n-gon n.
    auto ptexOffsets = [](const Mesh& m) {
        std::vector<int> offsets(m.faceCount() + 1, 0);
        for (size_t f = 0; f < m.faceCount(); ++f)
            offsets[f + 1] = offsets[f] + (m.faceSize(f) == 4 ? 1 : int(m.faceSize(f)));
        return offsets;
    };
    const auto pa = ptexOffsets(a), pb = ptexOffsets(b);
    std::map<std::vector<uint32_t>, size_t> faceOfB;
    for (size_t f = 0; f < b.faceCount(); ++f) faceOfB[canonical(b.face(f))] = f;
    for (size_t f = 0; f < a.faceCount(); ++f) {
        auto it = faceOfB.find(canonical(a.face(f)));
        if (it == faceOfB.end()) return 1e30; // a face of one is not a face of the other
        if (a.faceSize(f) != 4) continue;
        glm::dvec3 p, q, n;
        EXPECT_TRUE(sa.evaluate(pa[f], 0.5, 0.5, p, n));
        EXPECT_TRUE(sb.evaluate(pb[it->second], 0.5, 0.5, q, n));
        worst = std::max(worst, glm::length(p - q));
    }
    return worst;
}

TEST(QuadPairs, SpotTriangulatedGetsItsQuadsBack) {
    const Mesh quads = load("quad/spot_quadrangulated.obj");
    Mesh joined = load("tri/spot_triangulated.obj");
    ASSERT_EQ(joined.positions, quads.positions); // the same vertices, as the data README says
    const QuadJoinReport r = joinTrianglePairs(joined);
    const size_t found = quadsFound(joined, quads);
    std::printf("spot_triangulated: %zu quads made from %zu triangles, %zu left; %zu of spot's %zu quads back\n",
                r.quadsMade, r.trianglesBefore, r.trianglesLeft, found, quads.faceCount());
    EXPECT_GE(double(found), 0.95 * double(quads.faceCount()));
    EXPECT_LT(limitDifference(joined, quads), 1e-5);
}

// Spot's coarse control cage (160 quads, 16 pentagons, 4 triangles), its quads split here: the
// quads are far from planar and square, so the default limits keep some apart; with both limits
// off (180 degrees) the neighbour order alone brings every one back.
TEST(QuadPairs, SpotControlMeshSplitAndRejoined) {
    const Mesh quads = load("quad/spot_control_mesh.obj");
    Mesh joined = triangulate(quads);
    const QuadJoinReport r = joinTrianglePairs(joined);
    std::printf("spot_control_mesh split, default limits: %zu quads made, %zu triangles left; %zu of %zu quads back\n",
                r.quadsMade, r.trianglesLeft, quadsFound(joined, quads), quadCount(quads));
    EXPECT_GE(quadsFound(joined, quads), 130u);
    Mesh open = triangulate(quads);
    QuadJoinOptions off;
    off.maxFaceAngle = off.maxShapeAngle = std::numbers::pi;
    const QuadJoinReport all = joinTrianglePairs(open, off);
    std::printf("spot_control_mesh split, limits off: %zu quads made, %zu triangles left; %zu of %zu quads back\n",
                all.quadsMade, all.trianglesLeft, quadsFound(open, quads), quadCount(quads));
    EXPECT_EQ(quadsFound(open, quads), quadCount(quads));
    EXPECT_LT(limitDifference(open, quads), 1e-5);
}

// All-triangle remeshed scans have no quads to find: pairs are joined where the limits allow,
// triangles without a partner stay, and the result is a valid mesh of the same surface area.
TEST(QuadPairs, ScansKeepTrianglesWithoutPartners) {
    for (const char* name : {"tri/goathead.obj", "tri/cat_lowres.obj", "tri/sphere.obj"}) {
        SCOPED_TRACE(name);
        Mesh m = load(name);
        const size_t triangles = m.faceCount();
        auto area = [](const Mesh& mesh) {
            double a = 0;
            for (size_t f = 0; f < mesh.faceCount(); ++f) {
                auto v = mesh.face(f);
                for (size_t k = 1; k + 1 < v.size(); ++k)
                    a += 0.5 * glm::length(glm::cross(mesh.positions[v[k]] - mesh.positions[v[0]],
                                                      mesh.positions[v[k + 1]] - mesh.positions[v[0]]));
            }
            return a;
        };
        const double before = area(m);
        const QuadJoinReport r = joinTrianglePairs(m);
        std::printf("%s: %zu quads made from %zu triangles, %zu left\n", name, r.quadsMade, triangles, r.trianglesLeft);
        EXPECT_EQ(r.trianglesBefore, triangles);
        EXPECT_EQ(r.quadsMade * 2 + r.trianglesLeft, triangles);
        EXPECT_GT(r.trianglesLeft, 0u);
        EXPECT_EQ(m.faceCount(), r.quadsMade + r.trianglesLeft);
        EXPECT_NO_THROW(validateMesh(m));
        // A quad's two diagonal splits differ in area only as far as it is non-planar (60 degrees).
        EXPECT_NEAR(area(m), before, 0.05 * before);
        Mesh again = load(name);
        joinTrianglePairs(again);
        EXPECT_EQ(again, m); // deterministic
    }
}

} // namespace
