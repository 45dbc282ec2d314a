// limn-render's frame: per-frame upload of the control points, the compute passes, the draw and
// the readback, recorded from scratch every frame as an animated mesh would be.
//
//   upload        staging -> controlPoints                      (transfer)
//   compute       copy control points -> level 0 of the pass's vertex buffer
//                 the pass's compute: for a subdivision surface, per level face, edge and
//                 vertex points, then limit points (paper 000, 4.2, 4.4); for a blending
//                 surface, each grid point once (paper 001, 4.2; unless the vertex stage does
//                 it); for a control mesh, face normals
//   draw          the pass's draw (+ wire)
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
#include "render/frame_pass.h"
#include "image/output_image.h"
#include "export/ply.h"
#include "image/srgb_image.h"
#include "image/texture_image.h"
#include "blend/trim.h"
#include "seams/seams.h"
#include "subdiv/tables.h"

#include <glm/vec3.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace limn::blend {
struct BlendSurface;
}

namespace limn::render {

// From the camera's upper left: it lights the faces turned up and to the left, shades the ones
// turned right and down, and from 40 degrees off the view axis puts the terminator well inside
// the silhouette, which is what shows the form.
inline constexpr double kDefaultLightAzimuth = -40, kDefaultLightElevation = 35;
inline constexpr double kDefaultBaseColor = 0.8; // light grey, sRGB (linear 0.60)

struct RenderSettings {
    uint32_t width = 1024, height = 768;
    ViewSpec view;
    Shade shade = Shade::Lit;
    Wire wire = Wire::None;               // --wire / --wire-triangles (subdivision surfaces)
    glm::dvec3 background{0.2, 0.2, 0.2}; // sRGB-encoded, 0..1, as it appears in the PNG
    bool alpha = false;                   // RGBA output, background transparent
    uint32_t tessCap = 64;                // segments per patch side / edge piece, at most (subdivision)
    // View-adaptive tessellation: target pixels per segment; 0 keeps the fixed grids
    // of 2^(N-l) segments per level-l patch side. (limn-render's default is 4; the library's 0
    // keeps callers that compare with fixed references unchanged.) Wire::Outlines uses the fixed grids.
    double edgePixels = 0;
    // ... and the on-screen distance in pixels between the drawn chords and the surface, at
    // most (the rates' error estimate, AdaptiveOptions::maxError); 0: segments of about
    // edgePixels. limn-render's default is 0.1 with edgePixels 32.
    double maxError = 0;
    bool cull = true;                     // view-adaptive: skip elements outside the frustum
    // ... and those between the image's sample positions (they draw nothing; not with wires)
    bool sampleCull = true;
    // ... and flat elements draw their corners from one shared vertex per point (the same
    // image; only where no own-chart UV is drawn, see AdaptiveOptions::sharePoints)
    bool sharePoints = true;
    // ... and --shade lit evaluates the limit normal at each pixel (the triangle's element at its
    // interpolated (s, t)) instead of interpolating the vertices' normals (AdaptiveOptions::
    // pixelNormals; not with --eval compute, wires, displacement or --mesh-out).
    bool pixelNormals = false;
    // ... and the on-screen error allowed where a piece faces the eye (every sample's normal within
    // 70 degrees of the view ray; AdaptiveOptions::interiorError); 0: maxError everywhere.
    double interiorError = 0;
    uint32_t blendGrid = 16;              // cells per face side (blending surface, --grid)
    bool evaluateVertices = false;        // keep the drawn vertices in buffers (--mesh-out)
    bool evalInCompute = true;            // surface vertices: compute pass (else vertex stage)
    // Limit tables are uploaded in chunks with at most this many bytes of indices each (WebGPU's
    // binding limit; tests lower it to run the chunked path on small meshes).
    uint64_t limitChunkBytes = uint64_t(128) << 20;
    std::optional<blend::TrimMask> trim;  // blending surface only (--trim)
    // Displacement of the subdivision surface (paper 000, 4.5) and a colour texture.
    const FloatImage* displacementMap = nullptr;
    double displaceScale = 1, displaceMid = 0;
    bool seamFix = true;
    const Seams* seams = nullptr; // for the seam fix; required with a displacement map
    const FloatImage* texture = nullptr;
    // The lit shading (shaders/draw_common.glsl, lightRig): the key light's direction in degrees
    // relative to the camera (--light AZ,EL: azimuth from the view direction towards the
    // camera's right, elevation towards its up; 0,0 is a headlight), and the base colour, sRGB
    // 0..1, that multiplies the texture (--color; unset: kDefaultBaseColor, white with a texture).
    double lightAzimuthDeg = kDefaultLightAzimuth, lightElevationDeg = kDefaultLightElevation;
    std::optional<glm::dvec3> baseColor;
    // Faces seen from behind drawn flat in this sRGB colour (--back-faces), for crack counts.
    std::optional<glm::dvec3> backFaceColor;
    // Anti-aliasing. `samples`: MSAA samples per pixel, 1 or 4 (WebGPU's counts),
    // resolved on the GPU; limn-render's default is 4, the library's 1 keeps callers that count
    // exact pixels unchanged. `supersample` K (1..4): draws K*width x K*height and box-filters
    // each K x K block in linear light on the CPU (render/output_image.h).
    uint32_t samples = 1;
    uint32_t supersample = 1;
    // `sampleShading` (--sample-shading): the smooth surfaces shade each of the samples on its
    // own instead of once per pixel and triangle, so highlights where the surface bends within a
    // pixel (semi-sharp creases) and trim edges are anti-aliased too; on lavapipe about 2.2-2.7x
    // the frame (bench_aa, docs/benchmarks.md). No effect with one sample.
    bool sampleShading = false;
    // Whether linearImage() is wanted (16-bit PNG, EXR): the frame is drawn into an RGBA16F
    // target in linear light. Supersampling and --alpha with MSAA use that target too (they
    // average in linear light, with premultiplied alpha); otherwise an 8-bit PNG comes straight
    // from an RGBA8 sRGB target.
    bool floatOutput = false;
    bool depth = false; // keep the depth for LinearImage::depth (EXR Z)
    // The most bytes the render target and its CPU-side copies may take (0: the smaller of half
    // the machine's memory and the largest device-local heap); more is refused before any work.
    uint64_t maxImageBytes = 0;
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
    // Draws the subdivision surface of `tables` when given, else the control mesh. Throws
    // Error(BadInput) when --shade uv is asked of a mesh without UVs, --shade levels without
    // tables, or when a buffer would exceed the storage-buffer limit.
    Renderer(gpu::Context& ctx, const Mesh& mesh, const Tables* tables,
             const RenderSettings& settings);
    // Draws the blending surface of `mesh` (paper 001), trimmed when settings.trim is set; --shade
    // levels colours by vertex valence. Throws Error(BadInput) for --shade uv without UVs.
    Renderer(gpu::Context& ctx, const Mesh& mesh, const blend::BlendSurface& surface,
             const RenderSettings& settings);
    ~Renderer();

    // Records, submits and waits for one whole frame.
    void renderFrame();

    // The last frame's image (RGB, or RGBA with settings.alpha), 8-bit sRGB.
    Image image() const;
    // The last frame's image in linear light, premultiplied, with depth when settings.depth
    // (after the supersample filter; any target).
    LinearImage linearImage() const;
    // What the target takes (RenderTarget::estimateBytes plus the CPU-side float copies).
    uint64_t imageBytes() const { return imageBytes_; }
    // The last frame's triangles, read back from the GPU buffers the draw used.
    exporting::DrawnMesh drawnMesh();
    FrameTimes frameTimes() const;

    const Camera& camera() const { return camera_; }
    // Moves the camera (the next frame re-runs only GPU passes; --bench-orbit).
    void setCamera(const Camera& camera) { camera_ = camera; }
    // The camera a view gets with this surface's framing (the box of the control points, grown by
    // extendFraming and padded for displacement): what the constructor set for settings.view.
    Camera cameraFor(const ViewSpec& view) const;
    // Grows the framing box by these positions (a sequence frames all its frames alike).
    void extendFraming(const std::vector<glm::dvec3>& positions);
    // New control points, one per control mesh vertex (an animated mesh, same topology): the next
    // frame uploads them and re-runs only the GPU passes, with the same tables and buffers.
    // Throws Error(BadInput) for a wrong count, Error(Usage) for a blending surface (its charts
    // and local surfaces are built from the positions on the CPU).
    void setControlPoints(const std::vector<glm::dvec3>& positions);
    // Whether the subdivision surface is tessellated view-adaptively.
    bool viewAdaptive() const { return viewAdaptive_; }
    // After a frame: throws Error(BadInput), prefixed with `where`, when the view-adaptive
    // tessellation did not fit its buffers or a patch's loops were cut short (parts of the
    // surface were left out): an image with holes is not written.
    void refuseTessellationShortfall(const std::string& where) const;
    uint64_t triangleCount() const { return pass_->triangleCount(); }
    // Vertices computed per frame: table vertices, limit points, drawn surface vertices.
    uint64_t verticesEvaluated() const { return pass_->verticesEvaluated(); }
    uint64_t bufferBytes() const;

  private:
    void checkImageSize(const gpu::Context& ctx);
    void finishSetup(const Mesh& mesh, const Bounds& bounds);
    // The view-projection of the GPU's coordinates (world minus origin_) at this aspect.
    glm::dmat4 gpuViewProjection(double aspect) const;
    LinearImage drawnLinear() const; // before the supersample filter
    void recordUpload();
    void recordCompute();
    void recordDraw();

    gpu::Context& ctx_;
    RenderSettings settings_;
    std::vector<glm::vec4> controlPoints_;
    // The GPU works relative to this point (renderOrigin): control points, eye and view are
    // uploaded minus it, and the drawn mesh read back plus it.
    glm::dvec3 origin_{0.0};
    Camera camera_;
    Bounds framing_;       // what cameraFor frames
    glm::dvec3 framingPad_{0.0}; // added around every box (displacement)
    bool blend_ = false;
    Mesh faces_;           // the control mesh's faces (no positions): orientation of new points
    std::unique_ptr<FramePass> pass_;
    struct Gpu;
    std::unique_ptr<Gpu> gpu_;
    TimedPasses timed_;
    bool viewAdaptive_ = false;
    // The drawn size (width, height times the supersample factor) and the target's format.
    uint32_t drawWidth_ = 0, drawHeight_ = 0;
    gpu::TargetFormat targetFormat_;
    uint64_t imageBytes_ = 0;
};

} // namespace limn::render
