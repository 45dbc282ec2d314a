// Limit tables over WebGPU's 128 MiB binding limit are uploaded in chunks of rows (uniform
// tables of catmark_car at depth 5 need 154 MiB of limit indices). The chunks are checked
// against the uncut tables row by row, and through the GPU: a render whose limit tables are cut
// into many small chunks draws the same vertices, bit for bit, as one with a single chunk, on
// meshes with extraordinary vertices, boundaries, creases and n-gons, adaptive and uniform.
#include "gpu/context.h"
#include "render/renderer.h"
#include "render/subdivision_draw.h"
#include "model_tables.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace limn;
using namespace limn::test;

namespace {

const char* const kModels[] = {"osd/catmark/catmark_car.obj", "osd/catmark/catmark_gregory_test7.obj",
                               "osd/catmark/catmark_fvar_bound1.obj", "osd/catmark/catmark_cube_creases2.obj"};

TEST(LimitChunks, RowsAreTheUncutTablesRows) {
    for (const char* model : kModels) {
        SCOPED_TRACE(model);
        const ModelTables b = buildModelTables(model, 3, false);
        const render::SubdivisionDraw d = render::prepareSubdivision(b.mesh, b.tables, 64, nullptr, true);
        ASSERT_GT(d.limitCount, 10u);
        const uint32_t stride = d.limitCount + 1;
        for (uint64_t bytes : {uint64_t(1), uint64_t(400), uint64_t(4096), uint64_t(128) << 20}) {
            const auto chunks = render::limitChunks(d, bytes);
            uint32_t next = 0;
            for (const auto& c : chunks) {
                ASSERT_EQ(c.firstRow, next);
                ASSERT_GT(c.rows, 0u);
                ASSERT_EQ(c.starts.size(), 3u * (c.rows + 1));
                // Under the budget, unless a single row is larger.
                EXPECT_TRUE(c.indices.size() * 4 <= bytes || c.rows == 1) << bytes;
                for (uint32_t k = 0; k < 3; ++k)
                    for (uint32_t r = 0; r < c.rows; ++r) {
                        const uint32_t row = c.firstRow + r;
                        const uint32_t b0 = d.limitStarts[k * stride + row], e0 = d.limitStarts[k * stride + row + 1];
                        const uint32_t b1 = c.starts[k * (c.rows + 1) + r], e1 = c.starts[k * (c.rows + 1) + r + 1];
                        ASSERT_EQ(e1 - b1, e0 - b0);
                        for (uint32_t i = 0; i < e0 - b0; ++i) {
                            ASSERT_EQ(c.indices[b1 + i], d.limitIndices[b0 + i]);
                            ASSERT_EQ(c.weights[b1 + i], d.limitWeights[b0 + i]);
                        }
                    }
                next += c.rows;
            }
            EXPECT_EQ(next, d.limitCount);
            if (bytes == 1) {
                EXPECT_EQ(chunks.size(), d.limitCount);
            }
            if (bytes == (uint64_t(128) << 20)) {
                EXPECT_EQ(chunks.size(), 1u);
            }
        }
    }
}

TEST(LimitChunks, ChunkedRenderDrawsTheSameVertices) {
    gpu::Context ctx;
    for (bool uniform : {false, true})
        for (const char* model : kModels) {
            SCOPED_TRACE(std::string(model) + (uniform ? " uniform" : " adaptive"));
            const ModelTables b = buildModelTables(model, uniform ? 2 : 3, uniform);
            auto drawn = [&](uint64_t chunkBytes) {
                render::RenderSettings s;
                s.width = 160, s.height = 120;
                s.edgePixels = 4;
                s.evaluateVertices = true;
                s.limitChunkBytes = chunkBytes;
                render::Renderer r(ctx, b.mesh, &b.tables, s);
                r.renderFrame();
                return std::make_pair(r.drawnMesh(), r.image());
            };
            const auto whole = drawn(uint64_t(128) << 20), cut = drawn(512);
            ASSERT_EQ(whole.first.vertices.size(), cut.first.vertices.size());
            ASSERT_GT(whole.first.vertices.size(), 100u);
            for (size_t i = 0; i < whole.first.vertices.size(); ++i)
                ASSERT_EQ(std::memcmp(&whole.first.vertices[i], &cut.first.vertices[i],
                                      sizeof(exporting::DrawnVertex)),
                          0)
                    << "vertex " << i;
            EXPECT_EQ(whole.first.triangles, cut.first.triangles);
            EXPECT_EQ(whole.second.pixels, cut.second.pixels);
        }
}

} // namespace
