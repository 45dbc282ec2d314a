// Auto-framing: the whole bounding box lands inside the image for any view and aspect, and the
// camera looks from the asked direction.
#include "render/camera.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace limn::render;

namespace {

glm::dvec3 project(const glm::dmat4& m, glm::dvec3 p) {
    glm::dvec4 c = m * glm::dvec4(p, 1.0);
    return glm::dvec3(c) / c.w;
}

TEST(Camera, FramesTheBoxFromEveryDirection) {
    Bounds box{{-1.0, 2.0, -0.5}, {3.0, 2.5, 4.0}};
    for (double aspect : {0.5, 1.0, 4.0 / 3.0, 3.0})
        for (double az = -180; az <= 180; az += 45)
            for (double el : {-90.0, -60.0, 0.0, 20.0, 89.0, 90.0}) {
                ViewSpec spec;
                spec.azimuthDeg = az;
                spec.elevationDeg = el;
                Camera cam = frameCamera(spec, box, aspect);
                glm::dmat4 vp = cam.viewProjection(aspect);
                double maxExtent = 0;
                for (int i = 0; i < 8; ++i) {
                    glm::dvec3 corner(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                                      i & 4 ? box.max.z : box.min.z);
                    glm::dvec3 ndc = project(vp, corner);
                    ASSERT_LE(std::abs(ndc.x), 1.0) << az << " " << el << " " << aspect;
                    ASSERT_LE(std::abs(ndc.y), 1.0) << az << " " << el << " " << aspect;
                    ASSERT_GE(ndc.z, 0.0);
                    ASSERT_LE(ndc.z, 1.0);
                    maxExtent = std::max({maxExtent, std::abs(ndc.x), std::abs(ndc.y)});
                }
                // ... and is not lost in the middle of it either.
                EXPECT_GT(maxExtent, 0.8) << az << " " << el << " " << aspect;
                glm::dvec3 dir = glm::normalize(cam.eye - cam.target);
                EXPECT_NEAR(dir.y, std::sin(el * M_PI / 180), 1e-12);
                EXPECT_EQ(cam.target, box.center());
            }
}

TEST(Camera, AzimuthZeroLooksFromPlusZ) {
    Bounds box{{-1, -1, -1}, {1, 1, 1}};
    ViewSpec spec;
    spec.azimuthDeg = 0;
    spec.elevationDeg = 0;
    Camera cam = frameCamera(spec, box, 1.0);
    EXPECT_NEAR(cam.eye.x, 0, 1e-12);
    EXPECT_NEAR(cam.eye.y, 0, 1e-12);
    EXPECT_GT(cam.eye.z, 1.0);
    // +X is to the right and +Y up in the image.
    glm::dmat4 vp = cam.viewProjection(1.0);
    EXPECT_GT(project(vp, {1, 0, 0}).x, 0.0);
    EXPECT_GT(project(vp, {0, 1, 0}).y, 0.0);
}

TEST(Camera, ExplicitCameraUsesEyeTargetUp) {
    Bounds box{{-1, -1, -1}, {1, 1, 1}};
    ViewSpec spec;
    spec.eye = glm::dvec3(0, 0, 10);
    spec.target = glm::dvec3(0, 0, 0);
    spec.up = glm::dvec3(1, 0, 0); // image up is +X
    Camera cam = frameCamera(spec, box, 1.0);
    glm::dmat4 vp = cam.viewProjection(1.0);
    EXPECT_GT(project(vp, {1, 0, 0}).y, 0.0);
    EXPECT_NEAR(project(vp, {0, 0, 0}).x, 0.0, 1e-12);
    EXPECT_LT(cam.nearPlane, 9.0);
    EXPECT_GT(cam.farPlane, 11.0);
    // An up vector along the view direction is replaced, not turned into NaNs.
    spec.up = glm::dvec3(0, 0, 1);
    glm::dmat4 m = frameCamera(spec, box, 1.0).viewProjection(1.0);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(m[c][r]));
}

TEST(Camera, DegenerateBoxesStillFrame) {
    Bounds point{{1, 1, 1}, {1, 1, 1}};
    Camera cam = frameCamera(ViewSpec{}, point, 1.0);
    EXPECT_GT(glm::length(cam.eye - cam.target), 0.0);
    EXPECT_GT(cam.nearPlane, 0.0);
}

} // namespace
