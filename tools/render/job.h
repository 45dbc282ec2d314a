// limn-render's one settings struct: what the command line asked for (options.cpp fills it), then
// what it means once the options are checked against each other (job.cpp: the renderer's
// settings, the sequence and the outputs to write). The other files of the tool take it as it is.
#pragma once

#include "base/cli.h"
#include "base/io.h"
#include "base/warnings.h"
#include "blend/blend_surface.h"
#include "gpu/context.h"
#include "gpu/validation.h"
#include "mesh/gltf.h"
#include "mesh/material.h"
#include "mesh/mesh.h"
#include "render/output_plan.h"
#include "render/renderer.h"
#include "render/sequence.h"
#include "seams/seams.h"
#include "subdiv/tables.h"

#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace limn::render_tool {

// Which surface to draw (--surface); Auto picks the first the container has of BLND, TBLS, MESH.
enum class Surface { Auto, Blend, Subdivision, Control };

struct RenderJob {
    // --- the options as given (options.cpp); their initial values are the defaults --help shows
    cli::Common common;
    std::string input = "-", shade = "lit", device, meshOut, eval = "auto", surfaceName = "auto",
                trimPath, displace, texture;
    double displaceScale = 1, displaceMid = 0;
    bool displaceScalePercent = false; // --displace-scale 2%: of the bounding-box diagonal
    bool noSeamFix = false;
    bool wire = false, wireTriangles = false, alpha = false, validate = false, syncValidation = false,
         meshAscii = false;
    bool viewGiven = false, colorGiven = false;
    std::string upAxis = "y";
    int bench = 0, tess = 64, grid = 16;
    uint32_t turntable = 0;
    std::string camerasPath, framesPattern;
    double fps = 0; // --fps (0: a glTF animation's keyframes)
    std::optional<render::Shard> shard;           // --shard I/N
    std::optional<render::FrameRange> frameRange; // --frame-range A-B
    int samples = 4, supersample = 1, bitDepth = 8;
    bool sampleShading = false;
    bool bitDepthGiven = false;
    uint64_t maxMemory = 0;
    uint64_t maxOutput = 0; // --max-output (0: the free space where the frames go)
    double edgePixels = 32, maxError = 0.1, benchOrbit = 0;
    // Options that set the renderer's settings directly (--size, --view, --light, colours, ...).
    render::RenderSettings settings;

    // --- what they mean (job.cpp)
    Surface surface = Surface::Auto;
    bool sequence = false;      // --turntable, --cameras or --frames
    render::OutputPlan outputs; // the image and mesh files, their formats and frame patterns
    // A sequence's frames: their numbers (which name the outputs), and their views or meshes.
    std::vector<render::ViewSpec> views;
    std::vector<render::FrameFile> frameFiles;
    // --frames FILE.gltf|.glb: its morph-target animation, read before any work (its positions
    // move to RenderInput::frames once the input is checked against its base mesh), and the
    // files it pulled in (buffers).
    std::optional<GltfMorphFrames> animation;
    std::vector<std::string> animationFiles;
    std::vector<uint64_t> frameNumbers;
    // The positions in the sequence this run renders and writes (--shard, --frame-range; all of
    // them without), and their frame numbers. The framing still takes every frame, so a part's
    // frames are those of the whole sequence.
    std::vector<size_t> part;
    std::vector<uint64_t> partNumbers;
    // Every file the run reads, for the depfile and so that no output overwrites one.
    std::vector<std::string> inputs;
};

// One frame of a sequence: the positions of its mesh (--frames), or none (the input's own).
struct SequenceFrame {
    uint64_t number = 0;
    std::string path;                 // the mesh file it came from (--frames)
    std::vector<glm::dvec3> positions; // empty: keep the current control points
};

// The mesh, and the one surface description that will be drawn (only that chunk is decoded, so a
// stale TBLS does not stop a blending surface from being drawn, or the other way round); the
// frames of a --frames sequence, and the maps the settings point to (so it is filled in place
// and never moved).
struct RenderInput {
    Mesh mesh;
    std::optional<Tables> tables;
    std::optional<Seams> seams;
    uint64_t seamsHash = 0; // what SEAM must have been made from
    std::optional<blend::BlendSurface> blend;
    std::vector<std::string> filesRead; // a .gltf's buffers and images, --frames' .gltf ones
    std::optional<MeshMaterial> material; // a glTF's base colour, or the container's MATL
    std::vector<SequenceFrame> frames;
    std::optional<FloatImage> displacementMap, textureMap;

    RenderInput() = default;
    RenderInput(const RenderInput&) = delete;
    RenderInput& operator=(const RenderInput&) = delete;
};

// The files a run writes: a single image and mesh (opened before any work, so a refused
// terminal or an unwritable folder fails first), or a sequence's frames as they are committed;
// and the depfile.
struct OutputFiles {
    std::optional<OutputFile> image, mesh;
    std::vector<std::string> paths;   // every output, for the depfile
    std::vector<std::string> written; // a sequence's frames in place so far
    std::optional<Depfile> depfile;
};

// The encoded image and mesh of a single render.
struct EncodedOutputs {
    std::vector<uint8_t> image, mesh;
};

// options.cpp: fills the options from the command line; false when --help or --version was
// handled. Throws Error(Usage).
bool parseOptions(int argc, char** argv, RenderJob& job);
// job.cpp: the checks across options and what follows from them, before the input is read:
// everything but the surface (which needs the input) is settled here. Throws Error(Usage), and
// Error(BadInput) for a --cameras file or --frames pattern that cannot be used.
void planJob(RenderJob& job);
// help.cpp: what --help prints after the options, and its exit-code table.
extern const char* const kRenderNotes;
extern const char* const kRenderExitCodes;

// input.cpp: reads the input, its --frames meshes and maps, and sets what they decide in
// job.settings (which then points into `in`). Prints the inputs' warnings.
void readRenderInput(RenderJob& job, RenderInput& in);

// output.cpp
// Refuses outputs that would overwrite an input or land in a missing folder, opens a single
// render's files and the depfile.
void openOutputs(const RenderJob& job, OutputFiles& files);
// Refuses (Error(Usage)) a sequence whose estimated size (render/output_plan.h) is more than
// --max-output or the free space of the frames' folder; `in` (when read) adds its meshes.
void refuseOversizedSequence(const RenderJob& job, const RenderInput* in);
// The last frame's pixels as the image's format needs them, and their encoding.
struct FramePixels {
    Image image;        // 8-bit PNG
    LinearImage linear; // 16-bit PNG, EXR
};
FramePixels framePixels(const render::Renderer& renderer, const RenderJob& job);
std::vector<uint8_t> encodeImage(const FramePixels& pixels, const RenderJob& job);
// Writes the depfile and the single render's files, then commits them; on failure removes a
// sequence's frames.
void commitOutputs(const RenderJob& job, const RenderInput& in, OutputFiles& files,
                   const EncodedOutputs& encoded);
// Removes a sequence's frames (after an error) and forgets them for the signal handler.
void removeFrames(const std::vector<std::string>& paths);

// sequence.cpp: renders and writes every frame of a sequence with one renderer.
void renderSequence(render::Renderer& renderer, const RenderJob& job, const RenderInput& in,
                    const gpu::ValidationLog* validation, std::vector<std::string>& written);

// device.cpp
// Starts the Vulkan device on another thread (it overlaps reading the input).
std::future<std::unique_ptr<gpu::Context>> startDevice(const RenderJob& job);
// Draws the single frame (or the sequence, or the --bench frames) and encodes what is written;
// fails on validation errors.
EncodedOutputs renderOnDevice(const RenderJob& job, const RenderInput& in, std::unique_ptr<gpu::Context> context,
                              OutputFiles& files);
// Prints the first validation messages; throws when the layer reported errors.
void checkValidation(const gpu::ValidationLog& log);

} // namespace limn::render_tool
