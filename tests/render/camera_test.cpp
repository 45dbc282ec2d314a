// Auto-framing: the object fills a centred square of kFrameFill of the image's smaller side for
// any view and aspect, the camera looks from the asked direction, and Z up is Y up turned.
#include "render/camera.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace limn::render;

namespace {

glm::dvec3 project(const glm::dmat4& m, glm::dvec3 p) {
    glm::dvec4 c = m * glm::dvec4(p, 1.0);
    return glm::dvec3(c) / c.w;
}

// The box's corners (its hull when no points are given) fill a centred square of kFrameFill of
// the image's smaller side: inside it, touching it on one axis, and centred on both.
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
                // NDC units per unit of the smaller side's half-extent.
                const double sx = aspect >= 1 ? aspect : 1.0, sy = aspect >= 1 ? 1.0 : 1.0 / aspect;
                double loX = 1e9, hiX = -1e9, loY = 1e9, hiY = -1e9;
                for (int i = 0; i < 8; ++i) {
                    glm::dvec3 corner(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                                      i & 4 ? box.max.z : box.min.z);
                    glm::dvec3 ndc = project(vp, corner);
                    ASSERT_GE(ndc.z, 0.0);
                    ASSERT_LE(ndc.z, 1.0);
                    loX = std::min(loX, ndc.x * sx), hiX = std::max(hiX, ndc.x * sx);
                    loY = std::min(loY, ndc.y * sy), hiY = std::max(hiY, ndc.y * sy);
                }
                const std::string what = std::to_string(az) + " " + std::to_string(el) + " " +
                                         std::to_string(aspect);
                const double extent = std::max(hiX - loX, hiY - loY) / 2;
                EXPECT_NEAR(extent, kFrameFill, 1e-9) << what;
                EXPECT_LE(std::max(hiX - loX, hiY - loY) / 2, kFrameFill + 1e-9) << what;
                EXPECT_NEAR(hiX + loX, 0.0, 1e-9) << what; // centred
                EXPECT_NEAR(hiY + loY, 0.0, 1e-9) << what;
                glm::dvec3 dir = glm::normalize(cam.eye - cam.target);
                EXPECT_NEAR(dir.y, std::sin(el * M_PI / 180), 1e-12);
            }
}

// Points given as the hull are what is fitted: a sphere's points fill the same from every
// direction, and a sphere gives the same camera distance from every direction.
TEST(Camera, FitsTheHullPoints) {
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j <= 20; ++j) {
            const double t = 2 * M_PI * i / 40, p = M_PI * j / 20 - M_PI / 2;
            points.push_back(glm::dvec3(std::cos(p) * std::cos(t), std::sin(p), std::cos(p) * std::sin(t)) * 2.0 +
                             glm::dvec3(5, 1, -3));
        }
    const Bounds b = boundsOf(points);
    EXPECT_NEAR(b.sphereRadius, 2.0, 1e-12);
    double lo = 1e9, hi = 0;
    for (double az : {-30.0, 0.0, 45.0, 100.0, 200.0}) {
        ViewSpec spec;
        spec.azimuthDeg = az;
        const Camera cam = frameCamera(spec, b, 4.0 / 3.0);
        const double d = glm::length(cam.eye - glm::dvec3(5, 1, -3));
        lo = std::min(lo, d), hi = std::max(hi, d);
    }
    EXPECT_LT(hi - lo, 1e-2 * lo); // the sampled sphere is nearly round
}

// --up-axis z: the same view of a box turned from Z up to Y up by (x, y, z) -> (x, z, -y).
TEST(Camera, ZUpSeesWhatYUpSeesOfTheTurnedBox) {
    const glm::dvec3 lo(-1.0, -4.0, 0.0), hi(1.5, 0.0, 1.2); // a Z-up car's box
    const Bounds zUp{lo, hi};
    const Bounds yUp{{lo.x, lo.z, -hi.y}, {hi.x, hi.z, -lo.y}};
    for (double az : {-30.0, 0.0, 90.0, 150.0})
        for (double el : {-40.0, 20.0, 90.0}) {
            ViewSpec z, y;
            z.zUp = true;
            z.azimuthDeg = y.azimuthDeg = az;
            z.elevationDeg = y.elevationDeg = el;
            const glm::dmat4 mz = frameCamera(z, zUp, 1.5).viewProjection(1.5);
            const glm::dmat4 my = frameCamera(y, yUp, 1.5).viewProjection(1.5);
            for (int i = 0; i < 8; ++i) {
                const glm::dvec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
                const glm::dvec3 a = project(mz, p), b = project(my, {p.x, p.z, -p.y});
                EXPECT_NEAR(a.x, b.x, 1e-9) << az << " " << el;
                EXPECT_NEAR(a.y, b.y, 1e-9) << az << " " << el;
            }
        }
    // Azimuth 0 with Z up looks from -Y (the front), with +Z up in the image.
    ViewSpec front;
    front.zUp = true;
    front.azimuthDeg = front.elevationDeg = 0;
    const Camera cam = frameCamera(front, zUp, 1.0);
    EXPECT_LT(cam.eye.y, lo.y);
    EXPECT_GT(project(cam.viewProjection(1.0), {0, -2, 1.1}).y, project(cam.viewProjection(1.0), {0, -2, 0.1}).y);
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
