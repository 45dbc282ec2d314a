#include "render/camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace limn::render {

namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double deg) { return deg * kPi / 180.0; }

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

glm::dmat4 Camera::view() const { return glm::lookAtRH(eye, target, safeUp(target - eye, up)); }

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
        glm::dvec3 dir(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
        // The half-angle the sphere must fit in: the narrower of the two fields of view.
        double halfY = cam.fovYRad * 0.5;
        double halfX = std::atan(std::tan(halfY) * aspect);
        double half = std::min(halfY, halfX);
        double distance = r / std::sin(half) * 1.05; // 5% margin around the silhouette
        cam.target = center;
        cam.eye = center + dir * distance;
        cam.up = safeUp(-dir, glm::dvec3(0, 1, 0));
        cam.nearPlane = std::max(distance - r * 1.02, distance * 1e-3);
        cam.farPlane = distance + r * 1.02;
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
