#include "render/camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace limn::render {

namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double deg) {
    return deg * kPi / 180.0;
}

// An up vector usable with this view direction.
glm::dvec3 safeUp(glm::dvec3 forward, glm::dvec3 up) {
    if (glm::length(glm::cross(forward, up)) > 1e-9 * glm::length(up)) return up;
    // Looking straight along the wanted up: use the world axis least aligned with the view.
    glm::dvec3 axis = std::abs(forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, -1);
    return axis;
}

} // namespace

double Bounds::radius() const {
    double r = glm::length(max - min) * 0.5;
    return r > 0 && std::isfinite(r) ? r : 1.0;
}

glm::dmat4 Camera::view() const {
    return glm::lookAtRH(eye, target, safeUp(target - eye, up));
}

glm::dmat4 Camera::projection(double aspect) const {
    return glm::perspectiveRH_ZO(fovYRad, aspect, nearPlane, farPlane);
}

Camera frameCamera(const ViewSpec& spec, const Bounds& bounds, double aspect) {
    Camera cam;
    const glm::dvec3 center = bounds.center();
    const double r = bounds.radius();
    cam.fovYRad = radians(spec.fovDeg);
    if (!spec.eye) {
        const double az = radians(spec.azimuthDeg), el = radians(spec.elevationDeg);
        const glm::dvec3 dir(std::cos(el) * std::sin(az), std::sin(el),
                             std::cos(el) * std::cos(az));
        cam.target = center;
        cam.up = safeUp(-dir, glm::dvec3(0, 1, 0));
        const glm::dvec3 right = glm::normalize(glm::cross(-dir, cam.up));
        const glm::dvec3 up = glm::cross(right, -dir);
        // The nearest distance along `dir` at which every box corner is inside both fields of
        // view: a corner at (x, y) across and z towards the camera needs D >= z + |x| / tan(halfX)
        // and D >= z + |y| / tan(halfY). Tighter than fitting the bounding sphere for flat or long
        // boxes.
        const double tanY = std::tan(cam.fovYRad * 0.5), tanX = tanY * aspect;
        double distance = 0, zMax = -r, zMin = r;
        for (int i = 0; i < 8; ++i) {
            glm::dvec3 corner(i & 1 ? bounds.max.x : bounds.min.x,
                              i & 2 ? bounds.max.y : bounds.min.y,
                              i & 4 ? bounds.max.z : bounds.min.z);
            glm::dvec3 d = corner - center;
            double x = glm::dot(d, right), y = glm::dot(d, up), z = glm::dot(d, dir);
            distance = std::max({distance, z + std::abs(x) / tanX, z + std::abs(y) / tanY});
            zMax = std::max(zMax, z);
            zMin = std::min(zMin, z);
        }
        distance = std::max(distance * 1.05, zMax + r * 0.05); // 5% margin; never inside the box
        cam.eye = center + dir * distance;
        cam.nearPlane = std::max((distance - zMax) * 0.98, distance * 1e-4);
        cam.farPlane = (distance - zMin) * 1.02;
        return cam;
    }
    cam.eye = *spec.eye;
    cam.target = spec.target.value_or(center);
    if (glm::length(cam.target - cam.eye) == 0) cam.target = cam.eye + glm::dvec3(0, 0, -1);
    cam.up = safeUp(cam.target - cam.eye, spec.up.value_or(glm::dvec3(0, 1, 0)));
    const double toCenter = glm::length(center - cam.eye);
    cam.farPlane = toCenter + r * 1.02;
    cam.nearPlane = std::max(toCenter - r * 1.02, cam.farPlane * 1e-4);
    return cam;
}

} // namespace limn::render
