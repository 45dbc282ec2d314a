// The camera: auto-framed on the bounding box from an azimuth and elevation (--view), or given
// explicitly (--eye/--target/--up). Computed in double on the CPU, Y up, right-handed; the
// projection maps depth to 0..1 (Vulkan, WebGPU) and the viewport flips Y (lib/gpu).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace limn::render {

struct Bounds {
    glm::dvec3 min{0.0}, max{0.0};
    glm::dvec3 center() const { return (min + max) * 0.5; }
    double radius() const; // half the diagonal, never 0
};

// What the command line asked for; unset fields take the defaults below.
struct ViewSpec {
    double azimuthDeg = 30;   // around +Y, from +Z towards +X
    double elevationDeg = 20; // above the XZ plane
    double fovDeg = 35;       // vertical field of view
    std::optional<glm::dvec3> eye, target, up;
};

struct Camera {
    glm::dvec3 eye{0.0}, target{0.0}, up{0.0, 1.0, 0.0};
    double fovYRad = 0.6;
    double nearPlane = 0.1, farPlane = 100.0;

    glm::dmat4 view() const;
    glm::dmat4 projection(double aspect) const;
    glm::dmat4 viewProjection(double aspect) const { return projection(aspect) * view(); }
};

// With spec.eye unset: looks at the box centre from the azimuth/elevation direction, from the
// nearest distance at which all eight box corners fit both the vertical and horizontal fields of
// view (plus a 5% margin).
// Otherwise uses eye/target (default: box centre)/up (default +Y). Near and far always enclose
// the bounding sphere. An up vector parallel to the view direction is replaced.
Camera frameCamera(const ViewSpec& spec, const Bounds& bounds, double aspect);

} // namespace limn::render
