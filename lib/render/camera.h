// The camera: auto-framed on the bounding sphere from an azimuth and elevation (--view), or given
// explicitly (--eye/--target/--up). Computed in double on the CPU, right-handed, with Y or Z as
// the world's up axis (--up-axis); the projection maps depth to 0..1 (Vulkan, WebGPU) and the
// viewport flips Y (lib/gpu).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <vector>

namespace limn::render {

struct Bounds {
    glm::dvec3 min{0.0}, max{0.0};
    // The largest distance of a drawn point from center(), when known (0: not known).
    double sphereRadius = 0;
    // The points the framing fits (the control points, or samples of the subdivision surface);
    // empty: the box's eight corners. min, max and sphereRadius hold everything drawn.
    std::vector<glm::dvec3> hull;
    glm::dvec3 center() const { return (min + max) * 0.5; }
    double radius() const; // sphereRadius when known, else half the diagonal; never 0
};

// The box of `points`, the largest distance of one from the box centre (a bounding sphere about
// the box centre, at most sqrt(3)/2 times larger than the smallest one) and the points as hull.
template <class Points>
Bounds boundsOf(const Points& points);

// What the command line asked for; unset fields take the defaults below.
//
// The view directions are the same for a Y-up and a Z-up asset: "front" is +Z with Y up (glTF's
// convention: an asset faces +Z) and -Y with Z up (Blender's and most Z-up tools': front view
// looks along +Y), "right" is +X in both, so a Z-up asset is seen as if turned to Y up by
// (x, y, z) -> (x, z, -y), the usual Z-up to Y-up export.
struct ViewSpec {
    // Camera in front, on the viewer's left and above: a three-quarter view that shows the
    // front, one side and the top of an asset that faces front.
    double azimuthDeg = -30;  // around the up axis, from front (0) towards right (+90)
    double elevationDeg = 20; // above the horizontal plane
    double fovDeg = 35;       // vertical field of view
    bool zUp = false;         // world up: +Z (else +Y)
    std::optional<glm::dvec3> eye, target, up;
};

// How much of the frame's smaller extent the object spans (--view framing).
inline constexpr double kFrameFill = 0.85;

struct Camera {
    glm::dvec3 eye{0.0}, target{0.0}, up{0.0, 1.0, 0.0};
    double fovYRad = 0.6;
    double nearPlane = 0.1, farPlane = 100.0;

    glm::dmat4 view() const;
    glm::dmat4 projection(double aspect) const;
    glm::dmat4 viewProjection(double aspect) const { return projection(aspect) * view(); }
};

// With spec.eye unset: looks along the azimuth/elevation direction from the nearest distance, and
// with the sideways offset, at which every hull point projects into the centred square of
// kFrameFill times the frame's smaller side: the object's image is centred and its larger extent
// spans kFrameFill of the smaller side exactly (for the hull; a subdivision surface, inside its
// control points' hull, a little less). A round object is framed alike from every direction;
// a long one comes closer where it looks narrow. The fit is exact, not searched: a point
// (x, y) across and z towards the camera at (s, t, D) is inside when |x - s| <= k (D - z) and
// |y - t| <= k (D - z), k the tangent of the square's half-angle; for all points that holds iff
// D >= (max(x + k z) - min(x - k z)) / 2k (and the same in y), with s = (max(x + k z) +
// min(x - k z)) / 2.
// Otherwise uses eye/target (default: box centre)/up (default the world's up). Near and far
// always enclose the bounding sphere. An up vector parallel to the view direction is replaced.
Camera frameCamera(const ViewSpec& spec, const Bounds& bounds, double aspect);

} // namespace limn::render
