// The view-adaptive cull (adaptive_cull.comp) leaves out elements outside the frustum,
// facing away, or whose projected Bezier hull holds none of the image's sample positions, and
// the flat elements' fan triangles that hold none (adaptive_counts.comp). All
// three are meant to drop only what draws no sample: the image with the cull is the image
// without it, byte for byte, in views where most of the surface is sub-pixel (deep isolation
// seen from far away), where part of it is off screen (a close-up), and the default framing.
// With 1 sample the whole cull is compared with none; with 4 the sample test alone (without any
// cull the back faces are drawn, and a silhouette sample may see one that the rasterizer's
// back-face cull drops). And the cull must do something: in the far views it leaves out at
// least 10% of the triangles, and some in the close-ups; on catmark_smoothtris0 at depth 2, whose
// surface near its extraordinary vertices is faces on per-valence bases (docs/irregular.md), the
// close-up's cull must leave out more than 38% of the triangles, which it does only with the
// hull of those faces' support points (80,814 triangles without a cull; 56,910, 0.70, when only
// patches were culled; 44,348, 0.55, with those faces culled too).
#include "gpu/context.h"
#include "render/renderer.h"
#include "model_tables.h"
#include "test_support.h"

#include <gtest/gtest.h>


#include <cstdio>
#include <string>

using namespace limn;
using namespace limn::test;

namespace {

struct CullView {
    const char* name;
    double azimuth, elevation, distance; // distance: bounding radii from the box centre (0: framed)
    bool far, offScreen;                 // mostly sub-pixel; partly off screen
};

const CullView kViews[] = {
    {"framed", 30, 20, 0, false, false},
    {"far", 200, 10, 40, true, false},
    {"close_up", 60, 35, 1.2, false, true},
};

TEST(AdaptiveCull, LeavesOutOnlyWhatDrawsNothing) {
    gpu::Context ctx;
    // The paper's sphere at depth 6: most of its elements ring its 34 extraordinary vertices at
    // a fraction of a pixel, where the flat elements' triangle test (adaptive_counts.comp)
    // decides what is drawn.
    for (const auto& [model, depth] : {std::pair<const char*, int>{"quad/spot_control_mesh.obj", 6},
                                       {"osd/catmark/catmark_car.obj", 4},
                                       {"osd/catmark/catmark_gregory_test7.obj", 5},
                                       {"osd/catmark/catmark_smoothtris0.obj", 2},
                                       {"sphere", 6}}) {
        const ModelTables b = std::string(model) == "sphere" ? buildMeshTables(paperSphere(1), depth)
                                                             : buildModelTables(model, depth);
        for (const CullView& v : kViews)
            for (uint32_t samples : {1u, 4u}) {
                SCOPED_TRACE(std::string(model) + " " + v.name + " samples " + std::to_string(samples));
                auto draw = [&](bool cull, bool sampleCull) {
                    render::RenderSettings s;
                    s.width = 240, s.height = 180;
                    s.samples = samples;
                    s.edgePixels = 4;
                    s.cull = cull;
                    s.sampleCull = sampleCull;
                    orbitView(s.view, b.mesh, v.azimuth, v.elevation, v.distance);
                    render::Renderer r(ctx, b.mesh, &b.tables, s);
                    r.renderFrame();
                    return std::make_pair(r.triangleCount(), r.image().pixels);
                };
                const auto with = draw(true, true), without = draw(samples == 4, false);
                EXPECT_EQ(with.second, without.second) << "the cull changed pixels";
                if (samples == 4 && !ctx.limits().standardSampleLocations) continue; // no sample test
                if (v.far) {
                    EXPECT_LT(double(with.first), 0.9 * double(without.first))
                        << with.first << " triangles drawn with the cull, " << without.first << " without";
                } else if (v.offScreen && samples == 1) {
                    EXPECT_LT(with.first, without.first);
                    if (std::string(model).find("smoothtris0") != std::string::npos) {
                        EXPECT_LT(double(with.first), 0.62 * double(without.first))
                            << with.first << " triangles drawn with the cull, " << without.first << " without";
                    }
                }
                std::printf("%s %s, %u samples: %llu triangles with the cull, %llu without\n", model, v.name,
                            samples, (unsigned long long)with.first, (unsigned long long)without.first);
            }
    }
}

} // namespace
