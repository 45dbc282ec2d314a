// What the renderer's frame draws: the control mesh, or the subdivision surface. The renderer
// owns the upload, the camera, the render target and the readback; a FramePass owns the buffers
// and pipelines of one kind of surface and records its compute passes and its draw.
#pragma once

#include "base/error.h"
#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "render/camera.h"
#include "export/ply.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace limn::render {

// What --wire overlays: nothing, the outlines of what is drawn (control mesh edges, patch and face
// outlines, blending-surface faces), or the edges of every triangle drawn (subdivision surfaces:
// shows the rates view-adaptive tessellation chose; --wire-triangles).
enum class Wire : uint8_t { None, Outlines, Triangles };

// The surfaces' shading (--shade); DrawPush::shade.
enum class Shade : uint32_t { Lit = 0, Normal = 1, Uv = 2, Levels = 3, Texture = 4 }; // SHADE_*

// Mirrors DrawPush in shaders/draw_common.glsl (std430 push-constant layout).
struct DrawPush {
    float viewProj[16];
    float eye[4];
    float light[4];
    float wireColor[4];
    uint32_t shade;
    float wirePull;
    uint32_t patchCount = 0;
    uint32_t flags = 0;
};
static_assert(sizeof(DrawPush) == 128);
inline constexpr uint32_t kDrawPullIndices = 1; // DRAW_PULL_INDICES
// DRAW_BACK_FACE_KEY: faces seen from behind are painted flat in the sRGB8 colour whose bits
// (0x00BBGGRR) are stored in light[3] (the push block is full at Vulkan's guaranteed 128 bytes).
inline constexpr uint32_t kDrawBackFaceKey = 2;
// The lit shading's base colour, sRGB8 bits 0x00BBGGRR, is stored in eye[3] (lightRig in
// shaders/draw_common.glsl); DRAW_Z_UP: the world's up, for the sky/ground light, is +Z (else +Y).
inline constexpr uint32_t kDrawZUp = 4;

// Records which timed passes are compute (for FrameTimes).
struct TimedPasses {
    std::vector<bool> isCompute;
    void begin(gpu::CommandBuffer& cmd, const std::string& name, bool compute) {
        cmd.beginTimed(name);
        isCompute.push_back(compute);
    }
};

// The positions and normals of `count` drawn vertices, read back from the vec4 buffers the
// surface was evaluated into (null: it was not); the pass fills in ptex, u, v and the triangles.
inline exporting::DrawnMesh readDrawnVertices(gpu::Context& ctx, const gpu::Buffer* positions,
                                   const gpu::Buffer* normals, size_t count) {
    if (!positions || !normals)
        throw Error(ErrorKind::BadInput, "internal: the surface was not evaluated into buffers");
    auto pos = gpu::readbackArrayNow<glm::vec4>(ctx, *positions, count);
    auto nrm = gpu::readbackArrayNow<glm::vec4>(ctx, *normals, count);
    exporting::DrawnMesh out;
    out.vertices.resize(count);
    for (size_t i = 0; i < count; ++i) {
        exporting::DrawnVertex& v = out.vertices[i];
        v.x = pos[i].x, v.y = pos[i].y, v.z = pos[i].z;
        v.nx = nrm[i].x, v.ny = nrm[i].y, v.nz = nrm[i].z;
    }
    return out;
}

class FramePass {
public:
    virtual ~FramePass() = default;
    // Where the control points (level 0) are copied each frame, as vec4.
    virtual const gpu::Buffer& vertexBuffer() const = 0;
    // This frame's camera, before recordCompute (passes that adapt to the view use it).
    virtual void setView(const glm::mat4& /*viewProj*/, const glm::dvec3& /*eye*/, uint32_t /*width*/,
                         uint32_t /*height*/) {}
    // New control points (an animated mesh, same topology): their box and, for a surface that
    // culls back faces, which way it faces now. Passes that keep neither ignore it.
    virtual void setControlPoints(const Bounds& /*bounds*/, float /*orientation*/) {}
    // After the control points are in place; ends with the barrier the draw needs.
    virtual void recordCompute(gpu::CommandBuffer& cmd, TimedPasses& timed) = 0;
    // Inside beginRendering/endRendering.
    virtual void recordDraw(gpu::CommandBuffer& cmd, DrawPush push, Wire wire) = 0;
    // The triangles as drawn, read back after a frame.
    virtual exporting::DrawnMesh drawnMesh() = 0;
    virtual uint64_t triangleCount() const = 0;
    virtual uint64_t verticesEvaluated() const = 0; // per frame, compute and vertex stages
    virtual uint64_t bufferBytes() const = 0;
};

} // namespace limn::render
