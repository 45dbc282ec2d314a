// The FVSF chunk (smooth face-varying UV surface): what it stores is the UV surface (its records,
// evaluated here by a B-spline written from formats/limn.md, match FaceVaryingSurface::uvAt),
// lossless, bound to the mesh's topology and UVs, and hostile input is refused naming it.
#include "base/error.h"
#include "container/container.h"
#include "mesh/import.h"
#include "subdiv/fvar_chunk.h"
#include "subdiv/irregular_basis.h"
#include "subdiv/tables_chunk.h"
#include "subdiv/tables_surface_records.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

using namespace limn;

namespace {

const uint32_t kLevels = 6; // the tables' default irregular levels K

Mesh loadSmooth(const std::string& model, SchemeOptions& options) {
    Warnings w;
    Mesh m = importMeshFile(test::modelPath(model).string(), w);
    m.tags.fvar = FVarRule::Boundaries;
    options = resolveSchemeOptions(m.tags, {});
    return m;
}

// The uniform cubic B-spline basis at t (paper 000, eq. 1).
void bspline(double t, double b[4]) {
    const double s = 1 - t;
    b[0] = s * s * s / 6, b[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, b[3] = t * t * t / 6;
}

// The UV at (u, v) of ptex face `ptex` from the chunk's quadtree and records, probing just
// inside toward the face's centre (formats/limn.md, FVSF).
bool chunkUV(const FvarSurfaceChunk& c, uint32_t ptex, double u, double v, double out[2]) {
    const double pu = u + 1e-6 * (0.5 - u), pv = v + 1e-6 * (0.5 - v);
    double ou = 0, ov = 0, size = 1;
    uint32_t node = c.surface.nodes[ptex];
    while (node != 0xFFFFFFFFu && !(node & 0x80000000u)) {
        size /= 2;
        const uint32_t i = pu >= ou + size, j = pv >= ov + size;
        ou += i * size, ov += j * size;
        node = c.surface.nodes[node + i + 2 * j];
    }
    if (node == 0xFFFFFFFFu) return false;
    const glm::vec4* r = &c.surface.records[9 * size_t(node & 0x7FFFFFFFu)];
    const double s = (u - r[0].x) / r[0].z, t = (v - r[0].y) / r[0].z;
    if (r[0].w != 0) { // an irregular face: the bilinear blend of its corners' limit UVs
        for (int k = 0; k < 2; ++k)
            out[k] = (1 - t) * ((1 - s) * r[1][k] + s * r[1][2 + k]) + t * ((1 - s) * r[2][2 + k] + s * r[2][k]);
        return true;
    }
    double bu[4], bv[4];
    bspline(s, bu), bspline(t, bv);
    out[0] = out[1] = 0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const glm::vec4& p = r[1 + (4 * j + i) / 2];
            for (int k = 0; k < 2; ++k) out[k] += bv[j] * bu[i] * p[(i % 2) * 2 + k];
        }
    return true;
}

TEST(FvarSurfaceChunk, StoresTheUVSurfaceLosslessly) {
    // Spot and the triangulated cube have irregular faces of both kinds (per-valence bases
    // around interior extraordinary vertices, quadtrees along UV seams), each stored as its
    // pieces (the bases' sub-patches turned into the ptex frame).
    for (const char* model : {"quad/osd_catmark_fvar_bound1.obj", "osd/catmark/catmark_fvar_bound3.obj",
                              "quad/spot_control_mesh.obj", "tri/cube_no_bottom.obj"}) {
        SCOPED_TRACE(model);
        SchemeOptions o;
        const Mesh m = loadSmooth(model, o);
        Warnings w;
        const uint32_t depth = 2;
        const Chunk c = encodeFvarSurfaceChunk(makeFvarSurfaceChunk(m, o, depth, kLevels, w));
        FvarSurfaceChunk d = decodeFvarSurfaceChunk(c, &m, &o);
        EXPECT_EQ(encodeFvarSurfaceChunk(d).payload, c.payload);
        EXPECT_EQ(d.ptexCount, ptexFaceCount(m));
        // Faces with a per-valence basis are stored as smooth faces (version 2) and expanded
        // to the pieces limn-render draws: the same nodes and record bits.
        if (std::string(model).find("spot") != std::string::npos || std::string(model).find("cube") != std::string::npos) {
            EXPECT_FALSE(d.surface.smoothFaces.empty());
        }
        d.surface = expandSmoothFaces(d.surface);
        const FaceVaryingSurface surface(m, o, depth, kLevels, w);
        const FaceVaryingSurface::Gpu drawn = surface.gpu();
        EXPECT_EQ(d.surface.nodes, drawn.nodes);
        EXPECT_EQ(0, std::memcmp(d.surface.records.data(), drawn.records.data(),
                                 std::min(d.surface.records.size(), drawn.records.size()) * 16));
        EXPECT_EQ(d.surface.records.size(), drawn.records.size());
        // At every point of a 1/64 lattice of every ptex face: the depth-2 lattice where the
        // fixed grids draw, and the points inside irregular faces the view-adaptive
        // tessellation draws (every band of the bases).
        double worst = 0;
        for (uint32_t p = 0; p < d.ptexCount; ++p)
            for (int i = 0; i <= 64; ++i)
                for (int j = 0; j <= 64; ++j) {
                    double uv[2];
                    ASSERT_TRUE(chunkUV(d, p, i / 64.0, j / 64.0, uv));
                    const glm::dvec2 want = surface.uvAt(p, i / 64.0, j / 64.0, 0.5, 0.5);
                    worst = std::max({worst, std::fabs(uv[0] - want.x), std::fabs(uv[1] - want.y)});
                }
        EXPECT_LT(worst, 1e-5);
    }
}

// The faces along UV seams and boundaries (version 3) are stored as their support and their
// configuration's basis; expanded, they must be the pieces the quadtree of K refined levels gave
// (version 2, boundaryBases off): the same squares, kinds and leaves everywhere, and the same
// control points and leaf corners up to float rounding (the bases' weights are floats over
// float support UVs, the quadtree's stencils ran in double).
TEST(FvarSurfaceChunk, BoundaryBasesExpandToTheQuadtreesPieces) {
    for (const char* model :
         {"tri/cube_no_bottom.obj", "quad/spot_control_mesh.obj", "quad/blub_control_mesh.obj",
          "osd/catmark/catmark_fvar_bound3.obj"}) {
        for (FVarRule rule : {FVarRule::LinearNone, FVarRule::CornersOnly, FVarRule::CornersPlus1,
                              FVarRule::Boundaries}) {
            SCOPED_TRACE(std::string(model) + " rule " + std::to_string(int(rule)));
            Warnings w;
            Mesh m = importMeshFile(test::modelPath(model).string(), w);
            m.tags.fvar = rule;
            const SchemeOptions o = resolveSchemeOptions(m.tags, {});
            for (uint32_t depth : {1u, 2u}) {
                const FaceVaryingSurface before(m, o, depth, kLevels, w,
                                                FaceVaryingSurface::kMaxGpuRecordBytes, false);
                const FvarSurfaceChunk stored = decodeFvarSurfaceChunk(
                    encodeFvarSurfaceChunk(makeFvarSurfaceChunk(m, o, depth, kLevels, w)), &m, &o);
                size_t boundary = 0;
                for (const FaceVaryingSurface::SmoothFace& f : stored.surface.smoothFaces)
                    boundary += stored.surface.bases[f.basis].configuration.boundary;
                if (depth == 2 && rule == FVarRule::CornersOnly &&
                    std::string(model).find("bound3") == std::string::npos) {
                    EXPECT_GT(boundary, 0u);
                }
                const FaceVaryingSurface::Gpu want = before.gpu(),
                                              got = expandSmoothFaces(stored.surface);
                ASSERT_EQ(want.nodes.size() >= stored.ptexCount, true);
                size_t leaves = 0;
                double worst = 0, span = 0;
                for (const glm::vec4& r : want.records)
                    span = std::max({span, double(std::fabs(r.x)), double(std::fabs(r.y))});
                std::function<void(uint32_t, uint32_t)> compare = [&](uint32_t a, uint32_t b) {
                    const uint32_t x = want.nodes[a], y = got.nodes[b];
                    ASSERT_EQ(x == 0xFFFFFFFFu, y == 0xFFFFFFFFu);
                    if (x == 0xFFFFFFFFu) return;
                    ASSERT_EQ(bool(x & 0x80000000u), bool(y & 0x80000000u)) << "node " << a;
                    if (!(x & 0x80000000u)) {
                        for (uint32_t k = 0; k < 4; ++k) compare(x + k, y + k);
                        return;
                    }
                    const glm::vec4* r = &want.records[9 * size_t(x & 0x7FFFFFFFu)];
                    const glm::vec4* q = &got.records[9 * size_t(y & 0x7FFFFFFFu)];
                    ASSERT_EQ(std::memcmp(r, q, 16), 0) << "the domain and kind of node " << a;
                    for (int k = 1; k < 9; ++k)
                        for (int c = 0; c < 4; ++c)
                            worst = std::max(worst, double(std::fabs(r[k][c] - q[k][c])));
                    ++leaves;
                };
                for (uint32_t p = 0; p < stored.ptexCount; ++p) compare(p, p);
                EXPECT_EQ(leaves, want.records.size() / 9);
                // A few float steps of the UVs' range.
                EXPECT_LE(worst, 8 * std::ldexp(span, -24))
                    << boundary << " boundary faces, depth " << depth;
            }
        }
    }
}

// Every boundary configuration limn-tables can build (up to 16 faces at the vertex, every place
// in its fan, smooth or a corner) builds, is self-similar, and stays within what the readers
// accept: its program's rows, its support's size and its weights (phantom points of convex rows:
// [-4, 5]); the FVSF codec gives its weights back bit for bit.
TEST(FvarSurfaceChunk, EveryBoundaryConfigurationIsReadable) {
    size_t built = 0;
    for (uint32_t n = 1; n <= 16; ++n)
        for (uint32_t position = 0; position < n; ++position)
            for (bool corner : {false, true}) {
                SCOPED_TRACE(std::to_string(n) + " faces, face " + std::to_string(position) + (corner ? ", corner" : ""));
                if (n == 2 && !corner) continue; // a regular boundary vertex: no configuration
                IrregularBasis b;
                ASSERT_NO_THROW(b = buildBoundaryBasis({n, true, position, corner}, 3));
                ++built;
                const uint32_t M = b.supportSize();
                EXPECT_GE(M, 4u);
                EXPECT_LE(M, 2 * kMaxBasisValence + 8);
                EXPECT_LE(b.program.rows(), 2 * M + 21);
                for (float x : b.weights) ASSERT_TRUE(x >= -4 && x <= 5) << x;
                ByteWriter w;
                writeProgram(w, b.program);
                const std::vector<uint8_t> bytes = w.take();
                ByteReader r(bytes, "test");
                const std::vector<float> again = expandIrregularBasis(readProgram(r, "test", M, 21), M, 3);
                EXPECT_EQ(0, std::memcmp(again.data(), b.weights.data(), again.size() * 4));
                EXPECT_EQ(again.size(), b.weights.size());
            }
    EXPECT_EQ(built, 16u * 17u - 2);
}

// Where the pieces of every irregular face would take too many GPU records, they stop at fewer
// levels (and say so): still exact on the lattice of their deepest squares.
TEST(FvarSurfaceChunk, FewerLevelsOverTheRecordBudgetStayExactAtTheirCorners) {
    SchemeOptions o;
    const Mesh m = loadSmooth("quad/spot_control_mesh.obj", o);
    const uint32_t depth = 2;
    Warnings none;
    const FaceVaryingSurface full(m, o, depth, kLevels, none);
    EXPECT_EQ(full.gpuLevels(), kLevels);
    EXPECT_TRUE(none.empty());
    uint32_t previous = kLevels;
    for (size_t budget : {size_t(1) << 20, size_t(1) << 19, size_t(0)}) {
        Warnings w;
        const FaceVaryingSurface cut(m, o, depth, kLevels, w, budget);
        const uint32_t L = cut.gpuLevels();
        SCOPED_TRACE(L);
        EXPECT_LE(L, previous);
        previous = L;
        EXPECT_LT(L, kLevels);
        EXPECT_EQ(w.messages.size(), 1u);
        FvarSurfaceChunk c;
        c.surface = cut.gpu();
        // Stored, its bases' programs (made for K levels) expand to the L bands drawn.
        FvarSurfaceChunk compact;
        compact.ptexCount = ptexFaceCount(m);
        compact.surface = cut.compactGpu();
        compact.elementCount = static_cast<uint32_t>(compact.surface.records.size() / 9);
        const FvarSurfaceChunk read = decodeFvarSurfaceChunk(encodeFvarSurfaceChunk(compact), nullptr, nullptr);
        EXPECT_EQ(read.surface.bases.size(), compact.surface.bases.size());
        const FaceVaryingSurface::Gpu expanded = expandSmoothFaces(read.surface);
        EXPECT_EQ(expanded.nodes, c.surface.nodes);
        ASSERT_EQ(expanded.records.size(), c.surface.records.size());
        EXPECT_EQ(0, std::memcmp(expanded.records.data(), c.surface.records.data(), 16 * c.surface.records.size()));
        // Level-2 faces are 1/4 of a quad's ptex face, 1/2 of an n-gon's sub-face's.
        const int n = 1 << (depth - 1 + L);
        double worst = 0;
        for (uint32_t p = 0; p < ptexFaceCount(m); ++p)
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j) {
                    double uv[2];
                    ASSERT_TRUE(chunkUV(c, p, double(i) / n, double(j) / n, uv));
                    const glm::dvec2 want = full.uvAt(p, double(i) / n, double(j) / n, 0.5, 0.5);
                    worst = std::max({worst, std::fabs(uv[0] - want.x), std::fabs(uv[1] - want.y)});
                }
        EXPECT_LT(worst, 1e-5);
    }
    EXPECT_EQ(previous, 0u);
}

TEST(FvarSurfaceChunk, RefusesAnotherMeshOrOtherUVs) {
    SchemeOptions o;
    Mesh m = loadSmooth("quad/osd_catmark_fvar_bound1.obj", o);
    Warnings w;
    const Chunk c = encodeFvarSurfaceChunk(makeFvarSurfaceChunk(m, o, 2, kLevels, w));
    Mesh moved = m;
    moved.uvs[3].x += 0.25;
    EXPECT_THROW(
        {
            try {
                decodeFvarSurfaceChunk(c, &moved, &o);
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("other UVs"), std::string::npos) << e.what();
                throw;
            }
        },
        Error);
    SchemeOptions all = o;
    all.fvar = FVarRule::CornersOnly;
    EXPECT_THROW(decodeFvarSurfaceChunk(c, &m, &all), Error);
    EXPECT_NO_THROW(decodeFvarSurfaceChunk(c, &m, &o));
}

TEST(FvarSurfaceChunk, HostileBytesAreRefusedNamingTheChunk) {
    SchemeOptions o;
    const Mesh m = loadSmooth("quad/osd_catmark_fvar_bound1.obj", o);
    Warnings w;
    const Chunk c = encodeFvarSurfaceChunk(makeFvarSurfaceChunk(m, o, 1, kLevels, w));
    auto refused = [&](const Chunk& bad, const char* what) {
        try {
            decodeFvarSurfaceChunk(bad, &m, &o);
        } catch (const Error& e) {
            EXPECT_EQ(e.where().rfind("chunk FVSF", 0), 0u) << what << ": " << e.where() << ": " << e.what();
            return true;
        }
        return false;
    };
    for (size_t n = 0; n < c.payload.size(); ++n) {
        Chunk cut{c.type, c.version, {c.payload.begin(), c.payload.begin() + static_cast<long>(n)}};
        EXPECT_TRUE(refused(cut, "truncated")) << "prefix of " << n << " bytes";
    }
    Chunk longer = c;
    longer.payload.push_back(0);
    EXPECT_TRUE(refused(longer, "trailing byte"));
    Chunk newer = c;
    newer.version = kFvarSurfaceChunkVersion + 1;
    EXPECT_TRUE(refused(newer, "newer version"));
    const size_t nodes = 32; // the payload offset of nodes[0]
    auto word = [](Chunk& k, size_t at, uint32_t v) { std::memcpy(k.payload.data() + at, &v, 4); };
    Chunk cycle = c;
    word(cycle, nodes, 0); // a root whose children start at itself
    EXPECT_TRUE(refused(cycle, "cycle"));
    Chunk leaf = c;
    word(leaf, nodes, 0x80000000u | 0x7FFFFFFEu);
    EXPECT_TRUE(refused(leaf, "missing element"));
    Chunk nan = c;
    const uint32_t nodeCount = [&] { uint32_t v; std::memcpy(&v, c.payload.data() + 24, 4); return v; }();
    word(nan, nodes + 4 * nodeCount + 16, 0x7FC00000u); // the first record's first control point
    EXPECT_TRUE(refused(nan, "NaN"));
    // A record whose domain is not its leaf's square: finite, inside [0, 1], yet a walk ending
    // there evaluated the element 1e30 sizes outside it (Inf UVs, NaN displaced points).
    const size_t records = nodes + 4 * size_t(nodeCount);
    Chunk tiny = c;
    const float size = 1e-30f;
    std::memcpy(tiny.payload.data() + records + 8, &size, 4);
    EXPECT_TRUE(refused(tiny, "domain not the leaf's square"));
    const FvarSurfaceChunk good = decodeFvarSurfaceChunk(c, &m, &o);
    // Leaves naming a stored piece (the others name smooth faces, expanded after the records).
    const size_t storedPieces = good.surface.records.size() / 9;
    auto namesPiece = [&](uint32_t v) {
        return v != 0xFFFFFFFFu && (v & 0x80000000u) && (v & 0x7FFFFFFFu) < storedPieces;
    };
    const auto leaf0 = std::find_if(good.surface.nodes.begin(), good.surface.nodes.end(), namesPiece);
    ASSERT_NE(leaf0, good.surface.nodes.end());
    const auto leafOther = std::find_if(leaf0 + 1, good.surface.nodes.end(), [&](uint32_t v) {
        return namesPiece(v) && good.surface.records[9 * (v & 0x7FFFFFFFu)] != good.surface.records[9 * (*leaf0 & 0x7FFFFFFFu)];
    });
    ASSERT_NE(leafOther, good.surface.nodes.end());
    Chunk swapped = c; // a leaf naming an element of another square
    word(swapped, nodes + 4 * size_t(leafOther - good.surface.nodes.begin()), *leaf0);
    EXPECT_TRUE(refused(swapped, "element of another square"));
    const auto inner = std::find_if(good.surface.nodes.begin(), good.surface.nodes.end(), [](uint32_t v) { return !(v & 0x80000000u); });
    const auto inner2 = std::find_if(inner + 1, good.surface.nodes.end(), [](uint32_t v) { return !(v & 0x80000000u); });
    if (inner2 != good.surface.nodes.end()) { // two parents of the same children (a DAG, not a tree)
        Chunk shared = c;
        word(shared, nodes + 4 * size_t(inner2 - good.surface.nodes.begin()), *inner);
        if (*inner > size_t(inner2 - good.surface.nodes.begin())) {
            EXPECT_TRUE(refused(shared, "two parents"));
        }
    }
    // Version 1 (no smooth faces: its tail of zero counts and an empty stream removed) is still
    // read. Its faces along the UV boundary are their pieces (version 3 stores them as smooth
    // faces of boundary configurations).
    FvarSurfaceChunk pieces = good;
    pieces.surface = FaceVaryingSurface(m, o, 1, kLevels, w, FaceVaryingSurface::kMaxGpuRecordBytes, false).compactGpu();
    pieces.elementCount = static_cast<uint32_t>(pieces.surface.records.size() / 9);
    ASSERT_TRUE(pieces.surface.smoothFaces.empty());
    const Chunk v2 = encodeFvarSurfaceChunk(pieces);
    Chunk first = v2;
    first.version = 1;
    ASSERT_GE(first.payload.size(), 16u);
    first.payload.erase(first.payload.end() - 16, first.payload.end());
    EXPECT_NO_THROW(decodeFvarSurfaceChunk(first, &m, &o));
    EXPECT_TRUE(refused(Chunk{v2.type, 1, v2.payload}, "version 1 with a version-2 tail"));
    // Random corruption: refused, or a chunk whose every walk stays in bounds (ASan would tell),
    // its smooth faces expanded as the readers do before drawing.
    std::mt19937 rng(5);
    for (int trial = 0; trial < 500; ++trial) {
        Chunk bad = c;
        bad.payload[rng() % bad.payload.size()] ^= uint8_t(1u << (rng() % 8));
        try {
            FvarSurfaceChunk d = decodeFvarSurfaceChunk(bad, &m, &o);
            d.surface = expandSmoothFaces(std::move(d.surface));
            double uv[2];
            for (uint32_t p = 0; p < d.ptexCount; ++p) chunkUV(d, p, 0.3, 0.7, uv);
        } catch (const Error&) {
        }
    }
}

// Version 2's smooth faces (support UVs, per-valence bases as programs): every count and index is
// checked before anything is allocated or expanded (a valence over 64, a program reading what
// is not there, a support beyond the points, a face without its basis, a weight outside [0, 1],
// a face named twice or by no node).
TEST(FvarSurfaceChunk, HostileSmoothFacesAreRefused) {
    SchemeOptions o;
    const Mesh m = loadSmooth("tri/cube_no_bottom.obj", o);
    Warnings w;
    const Chunk c = encodeFvarSurfaceChunk(makeFvarSurfaceChunk(m, o, 2, 2, w));
    const FvarSurfaceChunk good = decodeFvarSurfaceChunk(c, &m, &o);
    ASSERT_GE(good.surface.smoothFaces.size(), 2u);
    auto refused = [&](const Chunk& bad) {
        try {
            decodeFvarSurfaceChunk(bad, &m, &o);
        } catch (const Error& e) {
            EXPECT_EQ(e.where().rfind("chunk FVSF", 0), 0u) << e.what();
            return true;
        }
        return false;
    };
    auto word = [](Chunk& k, size_t at, uint32_t v) { std::memcpy(k.payload.data() + at, &v, 4); };
    auto at = [&](size_t offset) {
        uint32_t v = 0;
        if (offset + 4 <= c.payload.size()) std::memcpy(&v, c.payload.data() + offset, 4);
        return v;
    };
    const size_t S = good.surface.smoothFaces.size(), B = good.surface.bases.size();
    ASSERT_LT(B, 32u);
    // After the records: the bases (each u32 n, configuration, support size, k, palette size P,
    // f32 palette[P], then its program's stream: u32 bytes, the bytes padded to 4), the values,
    // the smooth faces' count and stream.
    const size_t bases = 32 + 4 * good.surface.nodes.size() + 144 * good.surface.records.size() / 9;
    std::vector<size_t> basisAt;
    size_t values = bases + 4;
    for (uint32_t b = 0; b < at(bases); ++b) {
        basisAt.push_back(values);
        const size_t stream = values + 20 + 4 * size_t(at(values + 16));
        values = stream + 4 + (size_t(at(stream)) + 3) / 4 * 4;
    }
    ASSERT_EQ(basisAt.size(), B);
    size_t interior = B, boundary = B;
    for (size_t b = B; b-- > 0;)
        (good.surface.bases[b].configuration.boundary ? boundary : interior) = b;
    ASSERT_LT(interior, B);
    ASSERT_LT(boundary, B);
    const size_t in = basisAt[interior], bd = basisAt[boundary];
    const size_t palette = in + 20, stream = palette + 4 * size_t(at(in + 16));
    const size_t faces = values + 4 + 8 * size_t(at(values));
    ASSERT_EQ(at(faces), S);
    const uint32_t n = good.surface.bases[boundary].valence;
    const std::pair<size_t, uint32_t> cases[] = {
        {bases, 0x10000000u},       // basis count
        {in, 65},                   // a valence over 64
        {in + 4, 2},                // a corner that is not on a boundary
        {in + 8, 0xFFFFu},          // a support size past any valence's
        {in + 12, 17},              // deeper than 16 levels
        {in + 16, 0xFFFFFFFFu},     // a palette past the end
        {bd + 4, 1u | n << 2},      // a boundary face beyond the vertex's fan
        {bd + 8, 3},                // a support smaller than a face
        {palette, 0x7F800000u},     // an infinite weight
        {palette, 0x40000000u},     // a weight of 2: expanded, some weight outside [0, 1]
        {palette, 0xBF800000u},     // a weight of -1
        {stream, 0xFFFFFFFFu},      // a program past the end
        {stream + 4, 0},            // no rows
        {values, 0x40000000u},      // value count
        {values + 4, 0x7F800000u},  // an infinite value
        {values + 8, 0x7FC00000u},  // a NaN value
        {faces, 0xFFFFFFFFu},       // smooth face count
        {faces + 8, (at(faces + 8) & 0xFFFFFF00u) | uint32_t(B << 2)}, // a missing basis in the stream
        {faces + 8, 0xFFFFFF00u | (at(faces + 8) & 0xFFu)}, // a value index beyond the values
    };
    for (const auto& [offset, v] : cases) {
        Chunk bad = c;
        word(bad, offset, v);
        EXPECT_TRUE(refused(bad)) << "offset " << offset << " value " << v;
    }
    // Two nodes naming one smooth face (it would be expanded twice), and so none naming another.
    std::vector<size_t> named;
    for (size_t i = 0; i < good.surface.nodes.size(); ++i)
        if (good.surface.nodes[i] != 0xFFFFFFFFu && (good.surface.nodes[i] & 0x80000000u) &&
            (good.surface.nodes[i] & 0x7FFFFFFFu) >= good.surface.records.size() / 9)
            named.push_back(i);
    ASSERT_EQ(named.size(), S);
    Chunk twice = c;
    word(twice, 32 + 4 * named[1], good.surface.nodes[named[0]]);
    EXPECT_TRUE(refused(twice));
    // A program the reader would run out of bounds (TBLS version 5's checks, tables_chunk_test's
    // HostileBasisProgramIsRefused has them all): re-encoded as it is, refused naming the fault.
    const uint32_t M = good.surface.bases[interior].supportSize();
    const std::pair<const char*, std::function<void(BasisProgram&)>> programs[] = {
        {"reads neither a support point nor an earlier row", [&](BasisProgram& p) { p.source[p.start[3]] = M + 3; }},
        {"names a missing row", [&](BasisProgram& p) { p.nextSupport[0] = p.rows(); }},
        {"has a bad weight", [&](BasisProgram& p) { p.weight[p.start[p.rows() - 1]] = 3e38f; }},
        {"bad configuration", [&](BasisProgram&) {}}, // the regular valence (the program is never run)
    };
    for (const auto& [why, damage] : programs) {
        FvarSurfaceChunk bad = good;
        FaceVaryingSurface::Basis& b = bad.surface.bases[interior];
        damage(b.program);
        if (std::string(why) == "bad configuration") { // a valid program over 16 support points: one row
            b.valence = 4;
            b.program = BasisProgram{};
            b.program.source = {0};
            b.program.weight = {1.0f};
            b.program.start = {0, 1};
            b.program.averaged = {1};
            b.program.nextSupport.assign(16, 0);
            // The encoder reads each face's support (now 16 points) from points: keep the last
            // face's reads inside the vector, so that the reader is what refuses it.
            bad.surface.points.resize(bad.surface.points.size() + 16);
        }
        try {
            decodeFvarSurfaceChunk(encodeFvarSurfaceChunk(bad), &m, &o);
            ADD_FAILURE() << "accepted: " << why;
        } catch (const Error& e) {
            EXPECT_EQ(e.where().rfind("chunk FVSF", 0), 0u) << e.what();
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    }
    // Random corruption of the bases, values and smooth faces: refused, or expanded in bounds.
    std::mt19937 rng(7);
    for (int trial = 0; trial < 300; ++trial) {
        Chunk bad = c;
        bad.payload[bases + rng() % (bad.payload.size() - bases)] ^= uint8_t(1u << (rng() % 8));
        try {
            FvarSurfaceChunk d = decodeFvarSurfaceChunk(bad, &m, &o);
            d.surface = expandSmoothFaces(d.surface);
            double uv[2];
            for (uint32_t p = 0; p < d.ptexCount; ++p) chunkUV(d, p, 0.3, 0.7, uv);
        } catch (const Error&) {
        }
    }
}

} // namespace
