// limn-render's frame: per-frame upload of the control points, the compute passes, the draw and
// the readback, recorded from scratch every frame as an animated mesh would be.
//
//   upload        staging -> controlPoints                      (transfer)
//   compute       copy control points -> vertices[0, V)         (level 0 of the vertex buffer)
//                 [subdivision passes go here: per level, face/edge/vertex points appended
//                  to `vertices`, then limit points; see recordCompute]
//                 face normals over the drawn level
//   draw          fan triangles of the drawn faces (+ wire edges)
//   readback      colour image -> host
//
// Every pass is timed with GPU timestamps (FrameTimes).
#pragma once

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/render_target.h"
#include "mesh/mesh.h"
#include "render/camera.h"
#include "render/control_mesh.h"
#include "render/ply.h"
#include "render/png.h"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

namespace limn::render {

enum class Shade : uint32_t { Lit = 0, Normal = 1, Uv = 2 }; // mirrors SHADE_* (draw_common.glsl)

struct RenderSettings {
    uint32_t width = 1024, height = 768;
    ViewSpec view;
    Shade shade = Shade::Lit;
    bool wire = false;
    glm::dvec3 background{0.2, 0.2, 0.2}; // sRGB-encoded, 0..1, as it appears in the PNG
    bool alpha = false;                   // RGBA output, background transparent
};

// GPU milliseconds of one frame; NaN when the device has no timestamps.
struct FrameTimes {
    std::vector<gpu::PassTime> passes; // in recording order
    double computeMs = 0;              // upload + compute passes
    double drawMs = 0;
    double totalMs = 0; // every timed pass, readback included
};

class Renderer {
  public:
    // Throws Error(BadInput) when --shade uv is asked of a mesh without UVs, or when a buffer
    // would exceed the storage-buffer limit.
    Renderer(gpu::Context& ctx, const Mesh& mesh, const RenderSettings& settings);
    ~Renderer();

    // Records, submits and waits for one whole frame.
    void renderFrame();

    // The last frame's image (RGB, or RGBA with settings.alpha).
    Image image() const;
    // The last frame's triangles, read back from the GPU buffers the draw used.
    DrawnMesh drawnMesh();
    FrameTimes frameTimes() const;

    const Camera& camera() const { return camera_; }
    uint32_t triangleCount() const { return static_cast<uint32_t>(draw_.triangles.size() / 3); }
    // Vertices the compute passes wrote per frame (for now the control points).
    uint32_t verticesEvaluated() const { return static_cast<uint32_t>(draw_.controlPoints.size()); }

  private:
    void recordUpload();
    void recordCompute();
    void recordDraw();

    gpu::Context& ctx_;
    RenderSettings settings_;
    ControlMeshDraw draw_;
    Camera camera_;
    struct Gpu;
    std::unique_ptr<Gpu> gpu_;
    std::vector<bool> timedIsCompute_;
};

} // namespace limn::render
