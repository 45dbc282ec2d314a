#include "render/camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

// A direction given in the Y-up frame (right +X, up +Y, front +Z) in world coordinates: the
// inverse of the Z-up to Y-up turn (x, y, z) -> (x, z, -y).
glm::dvec3 fromYUp(glm::dvec3 d, bool zUp) {
    return zUp ? glm::dvec3(d.x, -d.z, d.y) : d;
}

} // namespace

double Bounds::radius() const {
    double r = sphereRadius > 0 ? sphereRadius : glm::length(max - min) * 0.5;
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
    const glm::dvec3 worldUp = fromYUp(glm::dvec3(0, 1, 0), spec.zUp);
    cam.fovYRad = radians(spec.fovDeg);
    if (!spec.eye) {
        const double az = radians(spec.azimuthDeg), el = radians(spec.elevationDeg);
        const glm::dvec3 dir = fromYUp(glm::dvec3(std::cos(el) * std::sin(az), std::sin(el),
                                                  std::cos(el) * std::cos(az)),
                                       spec.zUp);
        cam.up = safeUp(-dir, worldUp);
        const glm::dvec3 right = glm::normalize(glm::cross(-dir, cam.up));
        const glm::dvec3 up = glm::cross(right, -dir);
        const double tanY = std::tan(cam.fovYRad * 0.5);
        const double k = std::min(tanY, tanY * aspect) * kFrameFill;
        constexpr double inf = std::numeric_limits<double>::infinity();
        double hiX = -inf, loX = inf, hiY = -inf, loY = inf, zMax = -inf, zMin = inf;
        // What is fitted: the hull's points, or the box's eight corners.
        std::vector<glm::dvec3> corners;
        if (bounds.hull.empty())
            for (int i = 0; i < 8; ++i)
                corners.push_back({i & 1 ? bounds.max.x : bounds.min.x, i & 2 ? bounds.max.y : bounds.min.y,
                                   i & 4 ? bounds.max.z : bounds.min.z});
        const std::vector<glm::dvec3>& points = bounds.hull.empty() ? corners : bounds.hull;
        auto add = [&](const glm::dvec3& p) {
            const glm::dvec3 d = p - center;
            const double x = glm::dot(d, right), y = glm::dot(d, up), z = glm::dot(d, dir);
            hiX = std::max(hiX, x + k * z), loX = std::min(loX, x - k * z);
            hiY = std::max(hiY, y + k * z), loY = std::min(loY, y - k * z);
            zMax = std::max(zMax, z), zMin = std::min(zMin, z);
        };
        for (const auto& p : points) add(p);
        // Never inside the object (a single point, or a hull seen edge-on, would put it there).
        const double distance =
            std::max({(hiX - loX) / (2 * k), (hiY - loY) / (2 * k), zMax + r * 0.05});
        // Sideways: the fit's offset is exact where the object is tight; the other way it leaves
        // slack, and the offset that centres the image there is found from the two extreme
        // points' projections (y_a - t) / d_a = -(y_b - t) / d_b, re-picking them until they stay.
        auto centre = [&](const glm::dvec3& axis, double t) {
            for (int iteration = 0; iteration < 8; ++iteration) {
                double hi = -inf, lo = inf;
                glm::dvec2 a{0.0, 1.0}, b{0.0, 1.0}; // (y, depth) of the extremes
                auto visit = [&](const glm::dvec3& p) {
                    const glm::dvec3 d = p - center;
                    const double y = glm::dot(d, axis), depth = distance - glm::dot(d, dir);
                    const double projected = (y - t) / depth;
                    if (projected > hi) hi = projected, a = {y, depth};
                    if (projected < lo) lo = projected, b = {y, depth};
                };
                for (const auto& p : points) visit(p);
                const double next = (a.x * b.y + b.x * a.y) / (a.y + b.y);
                if (next == t || !(a.y > 0 && b.y > 0)) break;
                t = next;
            }
            return t;
        };
        const double s = centre(right, (hiX + loX) * 0.5), t = centre(up, (hiY + loY) * 0.5);
        cam.target = center + right * s + up * t;
        cam.eye = cam.target + dir * distance;
        // Near and far enclose the hull and the bounding sphere (the hull may be samples of the
        // surface, the sphere holds its control points).
        cam.nearPlane = std::max(std::min(distance - zMax, distance - r) * 0.98, distance * 1e-4);
        cam.farPlane = std::max(distance - zMin, distance + r) * 1.02;
        return cam;
    }
    cam.eye = *spec.eye;
    cam.target = spec.target.value_or(center);
    if (glm::length(cam.target - cam.eye) == 0) cam.target = cam.eye + glm::dvec3(0, 0, -1);
    cam.up = safeUp(cam.target - cam.eye, spec.up.value_or(worldUp));
    const double toCenter = glm::length(center - cam.eye);
    cam.farPlane = toCenter + r * 1.02;
    cam.nearPlane = std::max(toCenter - r * 1.02, cam.farPlane * 1e-4);
    return cam;
}

template <class Points>
Bounds boundsOf(const Points& points) {
    Bounds b;
    bool first = true;
    for (const auto& p : points) {
        const glm::dvec3 q(p);
        b.min = first ? q : glm::min(b.min, q);
        b.max = first ? q : glm::max(b.max, q);
        first = false;
    }
    const glm::dvec3 c = b.center();
    double r2 = 0;
    for (const auto& p : points) {
        const glm::dvec3 d = glm::dvec3(p) - c;
        r2 = std::max(r2, glm::dot(d, d));
    }
    b.sphereRadius = std::sqrt(r2);
    for (const auto& p : points) b.hull.emplace_back(p);
    return b;
}

template Bounds boundsOf(const std::vector<glm::dvec3>&);

} // namespace limn::render
