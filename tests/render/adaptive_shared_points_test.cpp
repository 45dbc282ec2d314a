// Shared points (AdaptiveOptions::sharePoints, adaptive_emit.comp): where the draw reads no
// own-chart UV, elements draw their corners from one vertex slot per point, and the points inside
// each edge piece from one slot each, written by the point's or the piece's owner, instead of a
// copy each. The slot holds the owner's (element, s, t), which every element's own copy held
// before, so the evaluation computes the same bits: the image must be the same bytes with and
// without sharing, with 1 and 4 samples, for --shade levels too (its per-triangle level stays the
// emitting element's), in far (mostly flat, sub-pixel elements), framed and close-up views, on
// meshes with boundaries, creases, extraordinary vertices and non-quads, evaluated in the vertex
// stage and (framed) in a compute pass; validation layer on, no error. Sharing must also do
// something: fewer vertices in every view. With --shade uv (a vertex's UV differs across a seam)
// nothing is shared.
#include "gpu/context.h"
#include "render/renderer.h"
#include "model_tables.h"
#include "test_support.h"

#include <gtest/gtest.h>


#include <string>

using namespace limn;
using namespace limn::test;

namespace {

struct View {
    const char* name;
    double azimuth, elevation, distance; // bounding radii from the box centre (0: framed)
};

const View kViews[] = {{"framed", 30, 20, 0}, {"far", 200, 10, 25}, {"close_up", 60, 35, 1.2}};

struct Drawn {
    uint64_t triangles, vertices;
    std::vector<uint8_t> pixels;
};

Drawn draw(gpu::Context& ctx, const ModelTables& b, const View& v, uint32_t samples, render::Shade shade,
           bool share, bool compute = false) {
    render::RenderSettings s;
    s.width = 240, s.height = 180;
    s.samples = samples;
    s.edgePixels = 4;
    s.shade = shade;
    s.sharePoints = share;
    s.evalInCompute = compute;
    orbitView(s.view, b.mesh, v.azimuth, v.elevation, v.distance);
    render::Renderer r(ctx, b.mesh, &b.tables, s);
    r.renderFrame();
    return {r.triangleCount(), r.verticesEvaluated(), r.image().pixels};
}

TEST(AdaptiveSharedPoints, SameImageFewerVertices) {
    gpu::ContextOptions options;
    options.validation = gpu::Validation::On;
    gpu::Context ctx(options);
    for (const auto& [model, depth] : {std::pair<const char*, int>{"quad/spot_control_mesh.obj", 4},
                                       {"osd/catmark/catmark_car.obj", 3},
                                       {"osd/catmark/catmark_gregory_test7.obj", 4},
                                       {"osd/catmark/catmark_cube_creases2.obj", 4},
                                       {"osd/catmark/catmark_bishop.obj", 4}}) {
        const ModelTables b = buildModelTables(model, depth);
        for (const View& v : kViews)
            for (uint32_t samples : {1u, 4u})
                for (render::Shade shade : {render::Shade::Lit, render::Shade::Levels}) {
                    // 4 samples and --shade levels once per model (the far view): the test's time
                    if ((samples == 4 || shade == render::Shade::Levels) && std::string(v.name) != "far") continue;
                    if (shade == render::Shade::Levels && samples == 4) continue;
                    SCOPED_TRACE(std::string(model) + " " + v.name + " samples " + std::to_string(samples) +
                                 (shade == render::Shade::Levels ? " levels" : " lit"));
                    const Drawn shared = draw(ctx, b, v, samples, shade, true);
                    const Drawn own = draw(ctx, b, v, samples, shade, false);
                    EXPECT_EQ(shared.pixels, own.pixels) << "sharing the points changed pixels";
                    EXPECT_EQ(shared.triangles, own.triangles);
                    // Sharing saves the copies of the points on element sides: 16-25% of the
                    // vertices in the far and framed views (8-10% far when only flat elements'
                    // corners were shared), 6-22% close up, where the elements' interior grids
                    // are most of them.
                    const double most = std::string(v.name) == "close_up" ? 0.95 : 0.85;
                    EXPECT_LT(double(shared.vertices), most * double(own.vertices))
                        << shared.vertices << " vertices with shared points, " << own.vertices << " without";
                    if (std::string(v.name) == "framed" && shade == render::Shade::Lit) {
                        // Shared slots evaluated once each by the compute pass: the same bits.
                        const Drawn computed = draw(ctx, b, v, samples, shade, true, true);
                        EXPECT_EQ(computed.pixels, own.pixels) << "shared points evaluated in a compute pass changed pixels";
                        EXPECT_EQ(computed.triangles, own.triangles);
                        EXPECT_EQ(computed.vertices, shared.vertices);
                    }
                }
    }
    ASSERT_NE(ctx.validationLog(), nullptr);
    EXPECT_EQ(ctx.validationLog()->errors(), 0u);
}

TEST(AdaptiveSharedPoints, NotWhereUVsAreDrawn) {
    gpu::Context ctx;
    const ModelTables b = buildModelTables("quad/spot_control_mesh.obj", 4);
    const Drawn shared = draw(ctx, b, kViews[1], 1, render::Shade::Uv, true);
    const Drawn own = draw(ctx, b, kViews[1], 1, render::Shade::Uv, false);
    EXPECT_EQ(shared.vertices, own.vertices);
    EXPECT_EQ(shared.pixels, own.pixels);
}

} // namespace
