// limn-render: renders a .limn container (or any mesh limn reads) headlessly on Vulkan and
// writes a deterministic PNG: the blending surface (BLND), the subdivision surface (TBLS) or the
// control mesh, flat shaded.
#include "base/cli.h"
#include "base/error.h"
#include "base/io.h"
#include "base/json.h"
#include "blend/blend_chunk.h"
#include "container/container.h"
#include "gpu/context.h"
#include "image/image_file.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "render/bench.h"
#include "render/blend_draw.h"
#include "render/mesh_export.h"
#include "render/output_image.h"
#include "render/renderer.h"
#include "render/sequence.h"
#include "seams/seams.h"
#include "subdiv/tables_chunk.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <memory>
#include <iostream>
#include <optional>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>

using namespace limn;

namespace {

glm::dvec3 vec3Option(const std::string& option, const std::string& value) {
    auto v = cli::parseNumberList(option, value, 3);
    // Meshes are refused beyond 1e18 (mesh.cpp) for the GPU's float; a camera there sees nothing.
    for (double x : v)
        if (!(std::abs(x) <= 1e18)) throw Error(ErrorKind::Usage, option + ": each coordinate must be within +-1e18");
    return {v[0], v[1], v[2]};
}

[[noreturn]] void usage(const std::string& message) {
    throw Error(ErrorKind::Usage, message);
}

// R,G,B with each component 0 to 1 (--color, --background, --back-faces).
glm::dvec3 colourOption(const std::string& option, const std::string& value) {
    auto c = cli::parseNumberList(option, value, 3);
    for (double x : c)
        if (!(x >= 0 && x <= 1)) usage(option + ": each component must be 0 to 1");
    return {c[0], c[1], c[2]};
}

double peakRssMb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0; // kilobytes on Linux
}

std::string displayName(const std::string& path) {
    return isStdio(path) ? "<stdin>" : path;
}

// Which surface to draw (--surface); Auto picks the first the container has of BLND, TBLS, MESH.
enum class Surface { Auto, Blend, Subdivision, Control };

// The mesh, and the one surface description that will be drawn (only that chunk is decoded, so a
// stale TBLS does not stop a blending surface from being drawn, or the other way round).
struct Input {
    Mesh mesh;
    std::optional<Tables> tables;
    std::optional<Seams> seams;
    uint64_t seamsHash = 0; // what SEAM must have been made from
    std::optional<blend::BlendSurface> blend;
    std::vector<std::string> filesRead; // a .gltf's buffers and images
    std::optional<MeshMaterial> material; // a glTF's base colour, or the container's MATL
};

// An image given to an option; errors say which option and what to do.
render::FloatImage loadMap(const std::string& option, const std::string& path) {
    try {
        return render::loadImage(path);
    } catch (const Error& e) {
        const std::string what = e.what();
        const bool missing = what.find("cannot open") != std::string::npos;
        Error out(e.kind(), option + ": " + what +
                                (missing ? "; give " + option + " an existing image file" : ""));
        out.setFile(path);
        throw out;
    }
}

Input readInput(const std::string& input, Surface surface, Warnings& warnings) {
    auto bytes = limn::readInput(input);
    try {
        Input in;
        const bool container = looksLikeContainer(bytes);
        Container c;
        if (container) {
            c = parseContainer(bytes);
            in.mesh = loadMesh(c);
            in.material = loadMaterial(c);
        } else {
            in.mesh = importMesh(input, bytes, warnings, &in.filesRead, &in.material);
        }
        const bool hasBlend = container && c.find(blend::kBlendChunk);
        const Chunk* tables = container ? c.find(kTablesChunk) : nullptr;
        if (surface == Surface::Auto)
            surface = hasBlend ? Surface::Blend : tables ? Surface::Subdivision : Surface::Control;
        if (surface == Surface::Blend) {
            if (!hasBlend)
                throwBadInput(
                    "--surface blend: no blending surface (BLND chunk); run limn-blend first");
            in.blend = blend::loadBlendSurface(c, in.mesh);
        }
        if (surface == Surface::Subdivision) {
            if (!tables)
                throwBadInput("--surface subdivision: no subdivision tables (TBLS chunk); run "
                              "limn-tables first");
            in.tables = decodeTablesChunk(*tables, &in.mesh);
        }
        if (in.tables) {
            in.seamsHash = seamsSourceHash(c);
            if (const Chunk* sm = c.find(kSeamsChunk))
                in.seams = decodeSeamsChunk(
                    *sm,
                    static_cast<uint32_t>(in.tables->patches.size() + in.tables->irregular.size()),
                    in.seamsHash);
        }
        return in;
    } catch (Error& e) {
        e.setFile(displayName(input));
        throw;
    }
}

// Prints the first validation messages and fails when the layer reported errors.
void checkValidation(const gpu::ValidationLog& log) {
    auto messages = log.messages();
    const size_t shown = std::min<size_t>(messages.size(), 10);
    for (size_t i = 0; i < shown; ++i)
        if (log.errors() || messages[i].rfind("warning", 0) == 0)
            cli::warn("validation " + messages[i]);
    if (log.errors())
        throw Error(ErrorKind::BadInput, std::to_string(log.errors()) +
                                             " Vulkan validation errors, " +
                                             std::to_string(log.warnings()) +
                                             " warnings (first ones above); no output written");
    cli::info("validation: 0 errors, " + std::to_string(log.warnings()) + " warnings");
}


// One frame of a sequence: the positions of its mesh (--frames), or none (the input's own).
struct SequenceFrame {
    uint64_t number = 0;
    std::string path;                 // the mesh file it came from (--frames)
    std::vector<glm::dvec3> positions; // empty: keep the current control points
};

// Reads every --frames mesh and checks it has the input's topology (the tables are reused, so
// the faces must be the same, vertex for vertex).
std::vector<SequenceFrame> readFrameMeshes(const std::vector<render::FrameFile>& files, const Mesh& mesh,
                                           std::vector<std::string>& filesRead) {
    std::vector<SequenceFrame> frames;
    // Positions are held for all frames (one framing for the whole sequence): refuse what would
    // not fit comfortably before reading them.
    const uint64_t bytes = uint64_t(files.size()) * mesh.vertexCount() * sizeof(glm::dvec3);
    if (bytes > cli::defaultMemoryBudget())
        throwBadInput("--frames: " + std::to_string(files.size()) + " frames of " +
                      std::to_string(mesh.vertexCount()) + " vertices need " + cli::formatBytes(bytes) +
                      " of positions, more than half the machine's memory; render the sequence in parts");
    for (const auto& f : files) {
        Warnings warnings;
        Mesh m;
        try {
            auto fileBytes = limn::readInput(f.path);
            if (looksLikeContainer(fileBytes)) {
                m = loadMesh(parseContainer(fileBytes));
            } else {
                std::vector<std::string> extra;
                m = importMesh(f.path, fileBytes, warnings, &extra);
                filesRead.insert(filesRead.end(), extra.begin(), extra.end());
            }
            if (m.faceOffsets != mesh.faceOffsets || m.faceVertices != mesh.faceVertices ||
                m.vertexCount() != mesh.vertexCount())
                throwBadInput("its faces differ from the input's (" + std::to_string(m.vertexCount()) +
                              " vertices, " + std::to_string(m.faceCount()) + " faces; the input has " +
                              std::to_string(mesh.vertexCount()) + " and " + std::to_string(mesh.faceCount()) +
                              "): --frames reuses the input's tables, so every frame needs its topology");
        } catch (Error& e) {
            e.setFile(f.path);
            throw;
        }
        cli::printWarnings(warnings, f.path);
        // f.path itself is already among the run's inputs (the depfile listed it twice).
        frames.push_back({f.number, f.path, std::move(m.positions)});
    }
    return frames;
}

// "frame 3/36, 12 s left" on stderr, rewritten in place; only on a terminal (a log stays clean).
class Progress {
  public:
    Progress(size_t total, bool quiet) : total_(total), show_(!quiet && total > 1 && ::isatty(STDERR_FILENO) == 1) {}
    void done(size_t count) {
        if (!show_) return;
        const double elapsed = seconds();
        const double left = elapsed / double(count) * double(total_ - count);
        std::fprintf(stderr, "\rlimn-render: frame %zu/%zu, %.0f s left   ", count, total_, left);
        if (count == total_) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

  private:
    size_t total_;
    bool show_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The last frame's pixels as read back: what the image's format encodes.
struct FramePixels {
    render::Image image;        // 8-bit PNG
    render::LinearImage linear; // 16-bit PNG, EXR
};

FramePixels framePixels(const render::Renderer& renderer, render::ImageFormat format, int bitDepth) {
    FramePixels p;
    if (format == render::ImageFormat::Exr || bitDepth == 16)
        p.linear = renderer.linearImage();
    else
        p.image = renderer.image();
    return p;
}

// The image in the format its name asked for: 8- or 16-bit PNG, or EXR (linear RGBA and
// camera-space Z).
std::vector<uint8_t> encodeImage(const FramePixels& p, render::ImageFormat format, int bitDepth,
                                 const render::RenderSettings& settings) {
    if (format == render::ImageFormat::Exr) {
        const render::LinearImage& li = p.linear;
        const size_t n = size_t(li.width) * li.height;
        std::vector<float> values(n * 5);
        for (size_t i = 0; i < n; ++i) {
            std::copy_n(&li.rgba[4 * i], 4, &values[5 * i]);
            values[5 * i + 4] = li.depth[i];
        }
        return encodeExr(li.width, li.height, {"R", "G", "B", "A", "Z"}, values);
    }
    if (bitDepth == 16) {
        std::vector<float> background(3);
        for (int i = 0; i < 3; ++i) background[i] = float(render::srgbToLinear(settings.background[i]));
        return render::encodePng(render::toSrgb16(p.linear, settings.alpha, background));
    }
    return render::encodePng(p.image);
}

// A --mesh-out file: the text formats (ASCII PLY, OBJ, .gltf) may go to a terminal, the rest not.
OutputFile::Kind meshFileKind(render::MeshFormat format, bool ascii) {
    return ascii || format == render::MeshFormat::Obj || format == render::MeshFormat::Gltf ? OutputFile::Kind::Text
                                                                                             : OutputFile::Kind::Binary;
}

void removeFrames(const std::vector<std::string>& paths) {
    clearRemovalOnSignal();
    for (const std::string& p : paths) std::filesystem::remove(p);
}

// Renders and writes every frame of a sequence with one renderer: the tables, buffers and
// pipelines stay; per frame only the camera (views) or the control points (frames) change.
// Frame files are committed one by one as they are done (`written` lists them, so the caller
// can remove them if a later step fails); an error here removes them itself.
void renderSequence(render::Renderer& renderer, const render::ViewSpec& view,
                    const std::vector<render::ViewSpec>& views,
                    const std::vector<SequenceFrame>& frames, const std::vector<uint64_t>& numbers,
                    const cli::Common& common, const render::FramePattern& imagePattern,
                    const std::optional<render::FramePattern>& meshPattern,
                    const std::optional<render::MeshFormat>& meshFormat, bool meshAscii,
                    const gpu::ValidationLog* validation, std::vector<std::string>& written,
                    const std::string& inputName, render::ImageFormat format, int bitDepth,
                    const render::RenderSettings& settings) {
    // One framing for the whole animation: the box of every frame's control points.
    if (!frames.empty()) {
        for (const SequenceFrame& f : frames) renderer.extendFraming(f.positions);
        renderer.setCamera(renderer.cameraFor(view));
    }
    Progress progress(numbers.size(), common.quiet);
    // Frame k is encoded and written on a second thread while frame k + 1 is drawn (a 36-view
    // turntable of spot at 640x480 on lavapipe: 0.83x the wall time of encoding in turn, farm-bench
    // median of 6 interleaved pairs). At most one
    // frame is in flight; its bytes depend only on its own pixels. Output files are only ever
    // made by one thread at a time (the signal handler's list of temporary files is not shared
    // safely): the main thread waits for the frame in flight before writing a --mesh-out.
    // A signal (Ctrl-C, SIGTERM) removes the frames already in place, as an error does.
    std::vector<std::string> paths;
    for (uint64_t n : numbers) {
        paths.push_back(render::framePath(imagePattern, n));
        if (meshPattern) paths.push_back(render::framePath(*meshPattern, n));
    }
    prepareRemovalOnSignal(paths);
    std::future<std::string> pending;
    auto finishPending = [&] {
        if (pending.valid()) written.push_back(pending.get());
    };
    try {
        for (size_t k = 0; k < numbers.size(); ++k) {
            if (!views.empty()) renderer.setCamera(renderer.cameraFor(views[k]));
            if (!frames.empty()) {
                renderer.setControlPoints(frames[k].positions);
                cli::info("frame " + std::to_string(numbers[k]) + ": new control points from " + frames[k].path);
            }
            renderer.renderFrame();
            if (validation && validation->errors()) checkValidation(*validation); // throws
            renderer.refuseTessellationShortfall(inputName + ": frame " + std::to_string(numbers[k]));
            FramePixels pixels = framePixels(renderer, format, bitDepth);
            finishPending();
            if (k > 0) progress.done(k);
            if (meshPattern) {
                const std::string mesh = render::framePath(*meshPattern, numbers[k]);
                writeOutput(mesh, render::encodeMesh(renderer.drawnMesh(), *meshFormat, meshAscii),
                            meshFileKind(*meshFormat, meshAscii));
                markLandedForRemovalOnSignal(mesh);
                written.push_back(mesh);
            }
            const std::string image = render::framePath(imagePattern, numbers[k]);
            pending = std::async(std::launch::async, [image, format, bitDepth, &settings, p = std::move(pixels)] {
                writeOutput(image, encodeImage(p, format, bitDepth, settings), OutputFile::Kind::Binary);
                markLandedForRemovalOnSignal(image);
                return image;
            });
        }
        finishPending();
        progress.done(numbers.size());
    } catch (...) {
        // A frame still being written either lands (and is then removed) or fails on its own.
        if (pending.valid()) {
            try {
                written.push_back(pending.get());
            } catch (...) {
            }
        }
        removeFrames(written);
        written.clear();
        throw;
    }
    char line[128];
    std::snprintf(line, sizeof line, "%zu frames in %.2f s (%.1f ms each, encoding and writing included)",
                  numbers.size(), progress.seconds(), 1000 * progress.seconds() / double(numbers.size()));
    cli::info(line);
}

double linearToSrgb(double c) {
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// The material's base colour texture, decoded; nullopt (with a warning) when it cannot be: the
// geometry is still worth drawing, in the base colour factor.
std::optional<render::FloatImage> materialTexture(const MeshMaterial& m, const std::string& input) {
    try {
        return readImageBytes(m.textureBytes, m.textureFormat);
    } catch (const Error& e) {
        cli::warn(displayName(input) + ": the base colour texture cannot be read (" + e.what() +
                  "); drawing the base colour factor instead");
        return std::nullopt;
    }
}

} // namespace

int main(int argc, char** argv) {
    return cli::run("limn-render", argc, argv, [](int ac, char** av) {
        cli::Common common;
        common.output.clear(); // "not given" matters with --bench
        std::string input = "-", shade = "lit", device, meshOut, eval = "auto",
                    surfaceName = "auto", trimPath, displace, texture;
        double displaceScale = 1, displaceMid = 0;
        bool displaceScalePercent = false; // --displace-scale 2%: of the bounding-box diagonal
        bool noSeamFix = false;
        render::RenderSettings settings;
        bool wire = false, wireTriangles = false, alpha = false, validate = false, syncValidation = false,
             meshAscii = false;
        bool viewGiven = false, colorGiven = false;
        std::string upAxis = "y";
        int bench = 0, tess = 64, grid = 16;
        uint32_t turntable = 0;
        std::string camerasPath, framesPattern;
        int samples = 4, supersample = 1, bitDepth = 8;
        bool sampleShading = false;
        bool bitDepthGiven = false;
        uint64_t maxMemory = 0;
        double edgePixels = 4, benchOrbit = 0;
        cli::Parser parser("limn-render", "[options] [INPUT|-] [-o OUTPUT.png|.exr] [--mesh-out FILE]",
                           "Renders a .limn container (output of limn-classify, limn-tables, "
                           "limn-seams, limn-blend)\n"
                           "headlessly "
                           "on Vulkan and writes a PNG (8- or 16-bit sRGB) or an OpenEXR (linear "
                           "float RGBA + Z),\nanti-aliased (4x MSAA by default), the same bytes "
                           "for the same inputs and options.\n"
                           "It draws the container's blending surface (limn-blend), else its "
                           "subdivision surface\n"
                           "(limn-tables), else its control mesh, flat shaded, with n-gons as "
                           "triangle fans (see\n"
                           "--surface); faces tagged as holes are not drawn.",
                           common);
        parser.positional("INPUT", &input, ".limn container (or any mesh file limn-classify reads)")
            .custom(
                "--size", "WxH",
                [&](const std::string& v) {
                    // Digits only, no wrap-around: 4294967297x1 is refused, not read as 1x1.
                    auto side = [&](const std::string& text) {
                        unsigned long long n = 0;
                        const bool digits = !text.empty() && text.size() <= 6 &&
                                            text.find_first_not_of("0123456789") == std::string::npos;
                        if (digits) n = std::stoull(text);
                        if (!digits || n < 1 || n > 16384)
                            usage("--size: '" + v + "' is not WIDTHxHEIGHT with each 1 to 16384");
                        return static_cast<unsigned>(n);
                    };
                    const size_t x = v.find('x');
                    if (x == std::string::npos)
                        usage("--size: '" + v + "' is not WIDTHxHEIGHT with each 1 to 16384");
                    const unsigned w = side(v.substr(0, x)), h = side(v.substr(x + 1));
                    settings.width = w;
                    settings.height = h;
                },
                "1024x768", "image size in pixels (each 1 to 16384)")
            .custom(
                "--view", "AZ,EL",
                [&](const std::string& v) {
                    auto n = cli::parseNumberList("--view", v, 2);
                    if (n[1] < -90 || n[1] > 90) usage("--view: elevation must be -90 to 90");
                    // As --light: 1e308 degrees made a NaN camera and a blank image with exit 0.
                    if (n[0] < -360 || n[0] > 360) usage("--view: azimuth must be -360 to 360");
                    settings.view.azimuthDeg = n[0];
                    settings.view.elevationDeg = n[1];
                    viewGiven = true;
                },
                "-30,20",
                "camera direction in degrees: azimuth around the up axis from the front (0)\n"
                "                            towards the right (90; -360 to 360), elevation above\n"
                "                            the horizon (-90 to 90); front is +Z with --up-axis y,\n"
                "                            -Y with z, right +X. The default looks from\n"
                "                            front-left-above.\n"
                "                            The object is centred and spans 85% of the image's\n"
                "                            smaller side (its larger extent)")
            .choice("--up-axis", &upAxis, {"y", "z"},
                    "the asset's up axis, for --view and the sky light: y (glTF's, by its spec,\n"
                    "                            and most OBJ/PLY/OFF files', which are exported\n"
                    "                            Y-up by Blender, Maya and most tools) or z (CAD,\n"
                    "                            Blender's own, the catmark car); a Z-up asset is\n"
                    "                            seen as if turned Y-up by (x, y, z) -> (x, z, -y)")
            .custom(
                "--eye", "X,Y,Z",
                [&](const std::string& v) { settings.view.eye = vec3Option("--eye", v); }, "",
                "explicit camera position (instead of --view)")
            .custom(
                "--target", "X,Y,Z",
                [&](const std::string& v) { settings.view.target = vec3Option("--target", v); }, "",
                "point the explicit camera looks at [default: bounding-box centre]")
            .custom(
                "--up", "X,Y,Z",
                [&](const std::string& v) { settings.view.up = vec3Option("--up", v); }, "",
                "up direction of the explicit camera [default: the --up-axis, 0,1,0 or\n"
                "                            0,0,1]")
            .real("--fov", "DEG", &settings.view.fovDeg, 1, 170, "vertical field of view")
            .custom(
                "--light", "AZ,EL",
                [&](const std::string& v) {
                    auto n = cli::parseNumberList("--light", v, 2);
                    if (!(n[0] >= -360 && n[0] <= 360) || !(n[1] >= -90 && n[1] <= 90))
                        usage("--light: azimuth must be -360 to 360 and elevation -90 to 90");
                    settings.lightAzimuthDeg = n[0];
                    settings.lightElevationDeg = n[1];
                },
                "-40,35",
                "key light direction in degrees relative to the camera: azimuth from the view\n"
                "                            axis towards the camera's right, elevation towards its\n"
                "                            up (0,0: a headlight); the default is upper left")
            .custom(
                "--color", "R,G,B",
                [&](const std::string& v) {
                    settings.baseColor = colourOption("--color", v);
                    colorGiven = true;
                },
                "0.8,0.8,0.8",
                "base colour of lit shading, sRGB components 0 to 1; it multiplies the texture\n"
                "                            [default: a glTF's baseColorFactor, else light grey,\n"
                "                            or white with a texture]")
            .custom(
                "--background", "R,G,B",
                [&](const std::string& v) {
                    settings.background = colourOption("--background", v);
                },
                "0.2,0.2,0.2", "background colour, sRGB components 0 to 1 (as stored in the PNG)")
            .custom(
                "--back-faces", "R,G,B",
                [&](const std::string& v) {
                    settings.backFaceColor = colourOption("--back-faces", v);
                },
                "",
                "paint faces seen from behind flat in this sRGB colour [default: shade both\n"
                "                            sides]; with a key --background, cracks in a closed\n"
                "                            surface show as key pixels (see --displace)")
            .choice("--surface", &surfaceName, {"auto", "blend", "subdivision", "control"},
                    "what to draw: the blending surface (BLND), the subdivision surface (TBLS)\n"
                    "                            or the control mesh; auto: the first the "
                    "container has")
            .choice(
                "--shade", &shade, {"lit", "normal", "uv", "levels", "texture"},
                "lit: studio light (sky/ground, key, fill, highlight); normal: normal * 0.5 +\n"
                "                            0.5 as colour;\n"
                "                            uv: (u, v, 0) as colour, needs UVs; levels: patches\n"
                "                            coloured by subdivision level (paper 000, Fig. 1),\n"
                "                            irregular faces blue, needs tables; on a blending\n"
                "                            surface each quarter face by the valence of its "
                "vertex;\n"
                "                            texture: the --texture map, lit (the default with\n"
                "                            --texture; subdivision surface)")
            .text("--displace", "MAP", &displace,
                  "displace the subdivision surface along its normal by a height map (any image\n"
                  "                            OpenImageIO reads; channel 0), sampled bilinearly "
                  "with\n"
                  "                            wrap-around at the mesh UVs: texel centres at half\n"
                  "                            integers, v = 0 at the bottom row")
            .custom(
                "--displace-scale", "S|P%",
                [&](const std::string& v) {
                    displaceScalePercent = !v.empty() && v.back() == '%';
                    const std::string number = displaceScalePercent ? v.substr(0, v.size() - 1) : v;
                    char* end = nullptr;
                    displaceScale = std::strtod(number.c_str(), &end);
                    if (number.empty() || *end != '\0' || !std::isfinite(displaceScale) ||
                        std::abs(displaceScale) > 1e6)
                        usage("--displace-scale: '" + v + "' is not a number (or a percentage "
                              "like 2%) within -1e6 to 1e6");
                },
                "1", "world units per unit of map value, or P% of the control mesh's bounding-box "
                     "diagonal (limn-info prints it)")
            .real("--displace-mid", "M", &displaceMid, -1e6, 1e6, "the map value meaning zero")
            .flag("--no-seam-fix", &noSeamFix,
                  "sample the map with each face's own UV only (shows the cracks that the\n"
                  "                            seam fix of paper 000, 4.5 removes)")
            .text("--texture", "MAP", &texture,
                  "colour texture (any image OpenImageIO reads) [default: a glTF's (or a MATL\n"
                  "                            chunk's) base colour texture]")
            .flag("--wire", &wire,
                  "overlay the control mesh edges, the patch and face outlines (drawn on the\n"
                  "                            fixed grids), or a blending surface's face outlines")
            .flag("--wire-triangles", &wireTriangles,
                  "overlay the edges of every triangle drawn (subdivision surfaces): with\n"
                  "                            view-adaptive tessellation, the rates this view chose")
            .choice("--eval", &eval, {"auto", "compute", "vertex"},
                    "where the surface is evaluated: vertex: in the vertex stage as the draw\n"
                    "                            needs it (paper 000, 3.2; paper 001, 4.2); compute: each\n"
                    "                            drawn vertex once in a compute pass, the draw fetches it;\n"
                    "                            auto: vertex for subdivision surfaces (fastest on\n"
                    "                            lavapipe, bench_render), compute with --displace (the\n"
                    "                            displaced normals need it) and for blending surfaces")
            .integer("--tess", "N", &tess, 1, 4096,
                     "most segments per patch edge, at any level. View-adaptive: each edge piece\n"
                     "                            gets what its pixels need, 1 to N; --edge-pixels 0: a\n"
                     "                            level-l patch side gets min(2^(depth-l), N) (N rounded\n"
                     "                            down to a power of two)")
            .real("--edge-pixels", "P", &edgePixels, 0, 4096,
                  "view-adaptive tessellation (issue 11): each patch edge is cut into segments of\n"
                  "                            about P pixels on screen, decided per frame on the GPU\n"
                  "                            (compute passes; patches outside the view, between\n"
                  "                            the samples or facing away are not drawn, which changes\n"
                  "                            no pixel); 0: the fixed grids of 2^(depth-l) segments per\n"
                  "                            level-l patch side (paper 000, 4.3). With --displace\n"
                  "                            an edge also gets a segment per map texel along it (up\n"
                  "                            to one per 2 pixels) and nothing is culled; --wire uses\n"
                  "                            the fixed grids (--wire-triangles shows these rates)")
            .integer("--grid", "K", &grid, 1, static_cast<int>(render::kMaxBlendGrid),
                     "blending surface: each face drawn as a K x K grid of cells")
            .text(
                "--trim", "MAP", &trimPath,
                "blending surface: trim atlas image (any format OpenImageIO reads, e.g. from\n"
                "                            limn-trim): one square tile per face, in face order;\n"
                "                            fragments where it is below 0.5 are discarded")
            .flag("--alpha", &alpha, "write RGBA with a transparent background (default RGB)")
            .custom(
                "--samples", "1|4",
                [&](const std::string& v) {
                    if (v != "1" && v != "4")
                        usage("--samples: '" + v + "' is not 1 or 4 (the MSAA counts WebGPU offers)");
                    samples = v == "1" ? 1 : 4;
                },
                "4",
                "samples per pixel (Vulkan multisampling, resolved on the GPU: colour averaged\n"
                "                            in linear light, alpha too; wire lines included); 1:\n"
                "                            one sample at each pixel centre, no anti-aliasing, so\n"
                "                            every pixel is exactly a surface or the background\n"
                "                            (pixel-exact tests, crack counts with --back-faces)")
            .flag("--sample-shading", &sampleShading,
                  "shade each of the --samples on its own (not once per pixel and triangle):\n"
                  "                            highlights where the surface bends within a pixel (semi-\n"
                  "                            sharp creases) and trim edges are anti-aliased too;\n"
                  "                            on lavapipe about 2.2-2.7x the frame (1.2-1.6x a whole\n"
                  "                            render of a still)")
            .integer("--supersample", "K", &supersample, 1, 4,
                     "reference-quality stills: draw K*W x K*H (each with --samples), then average\n"
                     "                            each K x K block on the CPU (a box filter, weights\n"
                     "                            1/K^2, in linear light with premultiplied alpha)\n"
                     "                            before encoding; K*W and K*H must fit the device's\n"
                     "                            largest image (usage error otherwise). Segments of\n"
                     "                            --edge-pixels and wire lines are in drawn pixels")
            .custom(
                "--bit-depth", "8|16",
                [&](const std::string& v) {
                    if (v != "8" && v != "16") usage("--bit-depth: '" + v + "' is not 8 or 16");
                    bitDepth = v == "8" ? 8 : 16;
                    bitDepthGiven = true;
                },
                "8",
                "PNG samples: 8 (from an RGBA8 sRGB target) or 16 (from an RGBA16F linear\n"
                "                            target, sRGB-encoded on the CPU: about 11 significant\n"
                "                            bits of linear light, not 16); not with .exr")
            .custom(
                "--max-memory", "SIZE",
                [&](const std::string& v) { maxMemory = cli::parseByteSize("--max-memory", v); },
                "",
                "most bytes the image may take (render target with its samples and resolves,\n"
                "                            readback, CPU float copies), e.g. 512M, 2G; more is\n"
                "                            refused before drawing [default: the smaller of half\n"
                "                            the machine's memory and the device's memory]")
            .text("--device", "NAME", &device,
                  "Vulkan device: case-insensitive substring of its name [default: a discrete or\n"
                  "                            integrated GPU if present, else the CPU device "
                  "(lavapipe)]")
            .flag("--validate", &validate,
                  "enable the Vulkan validation layer; any validation error fails the run")
            .flag("--sync-validation", &syncValidation,
                  "as --validate, plus synchronization validation")
            .text("--mesh-out", "FILE", &meshOut,
                  "write the triangles as drawn (positions, normals, texture UVs) to FILE, as\n"
                  "                            PLY, OBJ or glTF 2.0 by its extension: .ply, .obj,\n"
                  "                            .gltf, .glb (-: PLY on standard output); without -o\n"
                  "                            no image is written (see below)")
            .flag("--mesh-ascii", &meshAscii,
                  "write a .ply --mesh-out as ASCII PLY (default binary little-endian)")
            .custom(
                "--turntable", "N",
                [&](const std::string& v) {
                    const bool digits = !v.empty() && v.size() <= 6 && v.find_first_not_of("0123456789") == std::string::npos;
                    const unsigned long n = digits ? std::stoul(v) : 0;
                    if (n < 1 || n > render::kMaxFrames)
                        usage("--turntable: '" + v + "' is not a number of views from 1 to " +
                              std::to_string(render::kMaxFrames));
                    turntable = static_cast<uint32_t>(n);
                },
                "",
                "render N views around the up axis, from --view's azimuth in steps of 360/N\n"
                "                            degrees, all framed alike, into -o NAME_%04d.png (frames 0..N-1)")
            .text("--cameras", "FILE", &camerasPath,
                  "render one view per line of FILE: eye, target and up (9 numbers) and an\n"
                  "                            optional vertical field of view; '#' comments; into -o NAME_%04d.png")
            .text("--frames", "PATTERN", &framesPattern,
                  "render the meshes PATTERN names (walk_%04d.obj: every existing number) with\n"
                  "                            INPUT's topology and tables, uploading only their positions;\n"
                  "                            frame k of the input goes to -o NAME_%04d.png with the same k")
            .integer("--bench", "FRAMES", &bench, 0, 100000,
                     "render FRAMES frames after 3 warm-up frames and print one JSON object of\n"
                     "                            medians to standard output; 0 renders once")
            .real("--bench-orbit", "DEG", &benchOrbit, -360, 360,
                  "with --bench: turn the camera DEG degrees about its target before every frame")
            .notes(
                "Output: -o FILE.png, -o FILE.exr, or -o - for standard output (PNG, refused on a\n"
                "terminal; a device or FIFO such as /dev/null also gets PNG); any other extension\n"
                "is a usage error and nothing is written. With\n"
                "--bench, standard output carries the JSON and the image is written only with\n"
                "-o FILE; with --mesh-out, only with -o FILE or -o -.\n"
                "--mesh-out: the triangles as drawn, every file written atomically, the same bytes\n"
                "for the same inputs; positions, normals and texture UVs are the same floats in\n"
                "every format. Normals: per vertex (the unit limit or surface normal) for\n"
                "subdivision and blending surfaces, per face (flat) for the control mesh. The\n"
                "texture UV is the mesh's face-varying UV in the chart of the face that drew the\n"
                "vertex; vertices are split where it differs (UV seams; the copies' positions are\n"
                "bit-identical). Meshes without UVs, and blending surfaces (whose vertices are\n"
                "shared across faces), get none: no s t, vt or TEXCOORD_0.\n"
                "  .ply: per vertex float x y z nx ny nz, int ptex, float u v, then float s t (the\n"
                "  texture UV, v = 0 at the image's bottom) when there are UVs; triangles as list\n"
                "  uchar int vertex_indices. Control mesh: one vertex per face corner, ptex the\n"
                "  face's Ptex index (OpenSubdiv numbering: a quad has one Ptex face, an n-gon n;\n"
                "  a fan triangle carries its face's first), u, v its UV (0 without UVs).\n"
                "  Subdivision surfaces: one vertex per surface point (one per chart at UV seams),\n"
                "  blending surfaces: one per surface point, shared by the faces that meet there;\n"
                "  ptex and (u, v) of the face that evaluated it (a blending surface: the face\n"
                "  index, (u, v) on its grid).\n"
                "  .obj: v, vt (v = 0 at the bottom), vn, each distinct value once, and triangles\n"
                "  f v/vt/vn (f v//vn without UVs); seam copies share their v.\n"
                "  .gltf / .glb: glTF 2.0, one indexed triangle mesh with POSITION, NORMAL and\n"
                "  TEXCOORD_0 (glTF's top-left origin: v flipped, 1 - t); .gltf embeds its buffer\n"
                "  as a base64 data: URI (one file), .glb as its binary chunk.\n"
                "View-adaptive (--edge-pixels > 0): each patch writes its own copy of the points on\n"
                "its sides, with the same bits as its neighbour's (weld by exact position), and the\n"
                "whole surface is written, patches outside the view at their smallest rate.\n"                "Trimming does not change --mesh-out.\n"
                "Sequences (--turntable, --cameras, --frames): one run renders every frame with\n"
                "the same tables and GPU buffers, only the camera or the control points change\n"
                "between frames; -o (and --mesh-out) must hold a frame number, %d or %04d (%% is a\n"
                "literal %), and each frame is the same bytes as a single render with its camera\n"
                "and mesh. Frames are written as they are done, each atomically; an error removes\n"
                "the frames this run wrote. All frames are framed alike: for --frames the box of\n"
                "every frame's control points. Progress (frame i/N, time left) goes to stderr\n"
                "when it is a terminal.\n"
                "PNG: 8-bit (or --bit-depth 16) sRGB with an sRGB chunk; RGB, or RGBA with straight\n"
                "alpha (--alpha). EXR (through the OpenImageIO plugin; exit 3 without it): 32-bit\n"
                "float channels R, G, B, A, Z, ZIP compressed. R, G, B are linear light,\n"
                "premultiplied by A (with --alpha the background is 0, 0, 0, 0; without, it is\n"
                "the --background colour decoded to linear, A = 1).\n"
                "Z is the camera-space depth: the distance from the eye along the view direction,\n"
                "in world units, not anti-aliased (with --samples 4 the pixel's first sample,\n"
                "with --supersample the nearest of the block's), +Inf where nothing was drawn.\n"
                "--bench JSON: frames, samples, sample_shading, supersample, size, gpu_ms\n"
                "{compute, draw, total} (GPU timestamps; total includes upload and readback),\n"
                "passes {name: ms}, cpu_ms (host time per frame: record, submit, wait),\n"
                "triangles, vertices_evaluated, buffer_bytes, peak_rss_mb, device.\n"
                "Examples:\n"
                "  limn-classify spot.obj | limn-render --view 45,30 --wire -o spot.png\n"
                "  limn-render frog.limn --bench 50 --size 1920x1080\n"
                "  limn-render frog.limn --supersample 2 -o still.exr   (linear RGBA + Z)\n"
                "  limn-render frog.limn --mesh-out frog.glb      (the drawn mesh only, no image)\n"
                "  limn-classify spot.obj | limn-blend --quadrangulate | limn-render --grid 8 -o "
                "s.png\n"
                "  limn-trim spot.limn -o holes.png && limn-render spot.limn --trim holes.png -o "
                "t.png\n"
                "  limn-render spot.limn --turntable 36 -o spin_%02d.png\n"
                "  limn-render twist.limn --frames twist/twist_%04d.obj -o twist_%04d.png\n");
        parser.exitCodes("Exit codes:\n"
                         "  0  success\n"
                         "  1  bad input, failed processing or Vulkan validation errors\n"
                         "  2  usage error (including binary output to a terminal)\n"
                         "  3  missing capability: no Vulkan loader or device, no device matching\n"
                         "     --device, validation layer not installed, OpenImageIO plugin\n"
                         "     missing for -o FILE.exr, device without --samples 4\n");
        if (!parser.parse(ac, av)) return 0;

        if (settings.view.eye && viewGiven) usage("--view and --eye exclude each other");
        if ((settings.view.target || settings.view.up) && !settings.view.eye)
            usage("--target and --up describe an explicit camera; give --eye too");
        if (settings.view.eye && settings.view.target && *settings.view.eye == *settings.view.target)
            usage("--eye and --target are the same point, so the camera has no direction");
        // The same checks as a --cameras line (sequence.cpp), so both ways of placing a camera agree.
        if (settings.view.up && glm::length(*settings.view.up) == 0) usage("--up: the up vector is zero");
        if (settings.view.up && settings.view.eye && settings.view.target &&
            glm::length(glm::cross(glm::normalize(*settings.view.target - *settings.view.eye),
                                   glm::normalize(*settings.view.up))) < 1e-9)
            usage("--up is parallel to the view direction (--eye to --target), so the image has no up");
        const int sequenceOptions = (turntable > 0) + !camerasPath.empty() + !framesPattern.empty();
        const bool sequence = sequenceOptions > 0;
        if (sequenceOptions > 1) usage("--turntable, --cameras and --frames exclude each other");
        if (turntable && settings.view.eye)
            usage("--turntable turns the --view camera around the up axis; leave out --eye");
        if (!camerasPath.empty() && (settings.view.eye || viewGiven))
            usage("--cameras gives every frame's camera; leave out --view and --eye");
        if (benchOrbit != 0 && !bench) usage("--bench-orbit turns the camera between --bench frames; give --bench FRAMES too");
        if (sequence && bench) usage("--bench measures one frame; leave out --turntable, --cameras and --frames");
        // A sequence's output names: -o and --mesh-out with their frame number.
        std::optional<render::FramePattern> imagePattern, meshPattern;
        if (sequence) {
            if (common.output.empty() || isStdio(common.output))
                usage("a sequence writes one image per frame: give -o NAME_%04d.png");
            imagePattern = render::parseFramePattern("-o", common.output); // exactly one frame number
            if (!meshOut.empty()) meshPattern = render::parseFramePattern("--mesh-out", meshOut);
        } else {
            for (const std::string* path : {&common.output, &meshOut})
                if (render::hasFrameNumber(*path))
                    usage("'" + *path + "' numbers frames, but there is one image; give --turntable, "
                          "--cameras or --frames (or write %% for a literal %)");
        }
        if (shade == "normal") settings.shade = render::Shade::Normal;
        if (shade == "uv") settings.shade = render::Shade::Uv;
        if (shade == "levels") settings.shade = render::Shade::Levels;
        if (shade == "texture") settings.shade = render::Shade::Texture;
        if (wire && wireTriangles)
            throw Error(ErrorKind::Usage, "--wire and --wire-triangles draw different overlays; choose one");
        settings.wire = wire ? render::Wire::Outlines : wireTriangles ? render::Wire::Triangles : render::Wire::None;
        settings.alpha = alpha;
        settings.samples = static_cast<uint32_t>(samples);
        settings.supersample = static_cast<uint32_t>(supersample);
        settings.sampleShading = sampleShading;
        settings.maxImageBytes = maxMemory;
        settings.view.zUp = upAxis == "z";
        if (bench && isStdio(common.output) && !common.output.empty())
            usage("--bench prints JSON on standard output; write the image with -o FILE");
        std::optional<render::MeshFormat> meshFormat;
        if (!meshOut.empty()) {
            meshFormat = render::meshFormatFromPath(meshOut);
            if (!meshFormat)
                throw Error(ErrorKind::Usage,
                            std::string("--mesh-out: unknown extension; limn-render writes ") +
                                render::kMeshFormats,
                            meshOut);
            if (meshAscii && *meshFormat != render::MeshFormat::Ply)
                usage("--mesh-ascii applies to a .ply --mesh-out, not " + meshOut);
        }
        if (meshAscii && meshOut.empty()) usage("--mesh-ascii applies to a .ply --mesh-out; give --mesh-out FILE.ply");
        // The image goes to standard output by default, unless --bench or --mesh-out is the
        // output asked for.
        const bool writeImage = !common.output.empty() || (!bench && meshOut.empty());
        if (isStdio(meshOut) && !meshOut.empty() &&
            (bench || (writeImage && isStdio(common.output))))
            usage("--mesh-out - and the image (or --bench JSON) cannot share standard output");
        if (common.output.empty() && writeImage) common.output = "-";
        // The image format comes from the name, before any work; never silently another one.
        render::ImageFormat imageFormat = render::ImageFormat::Png;
        if (writeImage) {
            // A device or pipe (-o /dev/null, a FIFO) is a stream like standard output: PNG.
            auto f = isStreamPath(common.output) ? std::optional(render::ImageFormat::Png)
                            : render::imageFormatFromPath(common.output);
            if (!f)
                throw Error(ErrorKind::Usage,
                            std::string("unknown image extension; limn-render writes ") +
                                render::kImageFormats + " (or - for PNG on standard output)",
                            common.output);
            imageFormat = *f;
        }
        if (bitDepthGiven && (!writeImage || imageFormat == render::ImageFormat::Exr))
            usage(writeImage ? "--bit-depth sets PNG samples; an .exr is always 32-bit float"
                             : "--bit-depth applies to the image, and none is written");
        settings.floatOutput = writeImage && (imageFormat == render::ImageFormat::Exr || bitDepth == 16);
        settings.depth = writeImage && imageFormat == render::ImageFormat::Exr;
        // Without the OpenImageIO plugin no .exr can be written: fail before any file exists.
        if (settings.depth) requireImageWriter();
        const Surface surface = surfaceName == "blend"         ? Surface::Blend
                                : surfaceName == "subdivision" ? Surface::Subdivision
                                : surfaceName == "control"     ? Surface::Control
                                                               : Surface::Auto;
        if (!trimPath.empty() && (surface == Surface::Subdivision || surface == Surface::Control))
            usage("--trim cuts blending surfaces; it does not go with --surface " + surfaceName);
        if (surface == Surface::Control && (!texture.empty() || !displace.empty() || shade == "levels"))
            usage("--texture, --displace and --shade levels draw the subdivision surface, and "
                  "--surface control draws the control mesh; leave out --surface control");

        // A sequence's frames: their numbers (which name the outputs), and their views or meshes.
        std::vector<render::ViewSpec> views;
        std::vector<render::FrameFile> frameFiles;
        std::vector<uint64_t> frameNumbers;
        if (turntable) views = render::turntableViews(settings.view, turntable);
        if (!camerasPath.empty()) {
            if (isStdio(camerasPath) && isStdio(input))
                usage("--cameras - and the input cannot both be standard input");
            auto bytes = limn::readInput(camerasPath);
            try {
                views = render::parseCameraFile(std::string(bytes.begin(), bytes.end()), settings.view.fovDeg);
            } catch (Error& e) {
                e.setFile(displayName(camerasPath));
                throw;
            }
        }
        if (!framesPattern.empty())
            frameFiles = render::findFrameFiles(render::parseFramePattern("--frames", framesPattern));
        for (size_t k = 0; k < views.size(); ++k) frameNumbers.push_back(k);
        for (const auto& f : frameFiles) frameNumbers.push_back(f.number);

        // Open outputs first: a refused terminal or an unwritable directory fails before any work.
        std::vector<std::string> inputs = {input};
        for (const std::string* extra : {&trimPath, &displace, &texture, &camerasPath})
            if (!extra->empty()) inputs.push_back(*extra);
        for (const auto& f : frameFiles) inputs.push_back(f.path);
        std::optional<OutputFile> png, ply;
        std::vector<std::string> outputs;
        if (sequence) {
            for (uint64_t n : frameNumbers) {
                outputs.push_back(render::framePath(*imagePattern, n));
                if (meshPattern) outputs.push_back(render::framePath(*meshPattern, n));
            }
            for (const std::string& o : outputs) refuseOverwritingInputs(o, inputs);
            for (const std::string& o : {outputs.front(), outputs.back()}) {
                const std::filesystem::path folder = std::filesystem::path(o).parent_path();
                if (!folder.empty() && !std::filesystem::is_directory(folder)) {
                    Error e(ErrorKind::BadInput, "cannot write the frames: no folder " + folder.string());
                    e.setFile(o);
                    throw e;
                }
            }
        } else {
            if (writeImage) refuseOverwritingInputs(common.output, inputs);
            if (!meshOut.empty()) refuseOverwritingInputs(meshOut, inputs);
            if (writeImage) png.emplace(common.output, OutputFile::Kind::Binary);
            if (!meshOut.empty()) ply.emplace(meshOut, meshFileKind(*meshFormat, meshAscii));
            if (writeImage) outputs.push_back(common.output);
            if (!meshOut.empty()) outputs.push_back(meshOut);
        }
        Depfile depfile(writeImage || ply || sequence ? common.depfile : std::string(), outputs, inputs);

        gpu::ContextOptions options;
        options.device = device;
        options.validation = syncValidation ? gpu::Validation::Synchronization
                             : validate     ? gpu::Validation::On
                                            : gpu::Validation::Off;
        // The device starts up (Vulkan instance, lavapipe's threads and LLVM) while the input is
        // read and checked: on two cores the two overlap. A bad input still reports first; the
        // future's destructor then waits for the unused context and releases it.
        std::future<std::unique_ptr<gpu::Context>> pendingContext =
            std::async(std::launch::async, [options] { return std::make_unique<gpu::Context>(options); });
        Warnings warnings;
        Input in = readInput(input, surface, warnings);
        cli::printWarnings(warnings, displayName(input));
        if (in.blend && !frameFiles.empty())
            usage("--frames: a blending surface is built from its control points on the CPU (charts, "
                  "local surfaces); render the frames' subdivision surface (--surface subdivision) or "
                  "run limn-blend per frame");
        const std::vector<SequenceFrame> frames = readFrameMeshes(frameFiles, in.mesh, in.filesRead);
        // No silent fallbacks: a classified container without tables draws its control mesh,
        // which is rarely what was meant; a --grid without a blending surface does nothing.
        if (surface == Surface::Auto && !in.tables && !in.blend && isContainerFile(input))
            cli::warn(displayName(input) + ": no subdivision tables (TBLS) or blending surface "
                      "(BLND): drawing the control mesh; run limn-tables for the smooth surface");
        if (!in.blend && grid != 16)
            cli::warn("--grid sets the blending surface's cells; " + displayName(input) +
                      " draws no blending surface, so it does nothing");
        if (displace.empty() && (displaceScale != 1 || displaceScalePercent || displaceMid != 0 || noSeamFix))
            cli::warn("--displace-scale, --displace-mid and --no-seam-fix shape the --displace map; "
                      "without --displace they do nothing");
        if (!trimPath.empty()) {
            try {
                settings.trim = render::trimMaskFromImage(
                    render::readImageFile(trimPath), static_cast<uint32_t>(in.mesh.faceCount()));
            } catch (Error& e) {
                e.setFile(trimPath);
                throw;
            }
        }
        settings.tessCap = static_cast<uint32_t>(tess);
        settings.edgePixels = edgePixels;
        // The fixed grids draw irregular faces' corners only; uniform tables (the full-subdivision
        // baseline) draw every face from its corners by design.
        if (in.tables && !in.tables->uniform && edgePixels > 0) {
            // Never silently approximate (docs/irregular.md): say when drawn points can fall where
            // the irregular faces' surface is only bilinear.
            const IrregularSurfaceCounts irr = irregularSurfaceCounts(*in.tables);
            if (irr.bilinear)
                cli::warn(displayName(input) + ": " + std::to_string(irr.bilinear) + " irregular faces are drawn " +
                          "bilinear between their corners (tables without their surface); re-run limn-tables");
            else if (irr.basis + irr.subPatches && uint64_t(tess) > (uint64_t(1) << irr.exactLevels))
                cli::warn(displayName(input) + ": --tess " + std::to_string(tess) + " can draw points within 2^-" +
                          std::to_string(irr.exactLevels) + " of extraordinary corners, where the surface is " +
                          "bilinear; re-run limn-tables with --irregular-levels " +
                          std::to_string(std::bit_width(uint32_t(tess) - 1)));
        }
        std::optional<render::FloatImage> displacementMap, textureMap;
        if (!displace.empty()) {
            displacementMap = loadMap("--displace", displace);
            settings.displacementMap = &*displacementMap;
            settings.displaceScale = displaceScale;
            if (displaceScalePercent) {
                settings.displaceScale = displaceScale / 100 * boundingBox(in.mesh).diagonal();
                cli::info("--displace-scale " + std::to_string(displaceScale) + "% = " +
                          std::to_string(settings.displaceScale) + " world units");
            }
            settings.displaceMid = displaceMid;
            settings.seamFix = !noSeamFix;
            if (in.tables && !in.seams && in.mesh.hasUVs()) {
                cli::info("no SEAM chunk (limn-seams): computing the seam UVs now");
                in.seams = computeSeams(in.mesh, *in.tables, in.seamsHash);
            }
            if (in.seams) settings.seams = &*in.seams;
        }
        if (!texture.empty()) {
            textureMap = loadMap("--texture", texture);
            settings.texture = &*textureMap;
            if (shade == "lit") settings.shade = render::Shade::Texture;
        }
        if (in.material) { // a glTF's base colour (limn-classify keeps it in MATL)
            const glm::dvec4& f = in.material->baseColorFactor;
            if (!colorGiven)
                settings.baseColor =
                    glm::dvec3(linearToSrgb(f.r), linearToSrgb(f.g), linearToSrgb(f.b));
            // Textures are drawn on the subdivision surface only (as --texture is).
            const bool drawsTexture = in.tables && !in.blend && in.mesh.hasUVs() &&
                                      (shade == "lit" || shade == "texture");
            if (texture.empty() && in.material->hasTexture()) {
                if (!drawsTexture)
                    cli::info("the base colour texture is drawn on the subdivision surface with "
                              "--shade lit or texture only; not drawn");
                else if ((textureMap = materialTexture(*in.material, input))) {
                    settings.texture = &*textureMap;
                    settings.shade = render::Shade::Texture;
                }
            }
        }
        settings.blendGrid = static_cast<uint32_t>(grid);
        if (in.blend && (!displace.empty() || !texture.empty()))
            usage(
                "--displace and --texture apply to the subdivision surface, not a blending surface "
                "(--surface subdivision draws the TBLS one)");
        settings.evalInCompute =
            eval == "compute" || (eval == "auto" && (in.blend || !displace.empty()));
        settings.evaluateVertices = !meshOut.empty();

        std::shared_ptr<gpu::ValidationLog> validation;
        std::vector<uint8_t> pngBytes, plyBytes;
        std::vector<std::string> written; // a sequence's frames, as they are committed
        {
            const std::unique_ptr<gpu::Context> context = pendingContext.get();
            gpu::Context& ctx = *context;
            validation = ctx.sharedValidationLog();
            for (const auto& line : ctx.selectionReport()) cli::info(line);
            std::optional<render::Renderer> chosen;
            if (in.blend)
                chosen.emplace(ctx, in.mesh, *in.blend, settings);
            else
                chosen.emplace(ctx, in.mesh, in.tables ? &*in.tables : nullptr, settings);
            render::Renderer& renderer = *chosen;
            // Once per run, also for a sequence: its frames reuse these buffers and pipelines.
            cli::info("set up the GPU surface: " + cli::formatBytes(renderer.bufferBytes()) +
                      " of buffers (tables, tessellation, frame)");
            const auto& cam = renderer.camera();
            cli::info("camera eye " + std::to_string(cam.eye.x) + "," + std::to_string(cam.eye.y) +
                      "," + std::to_string(cam.eye.z) + " target " + std::to_string(cam.target.x) +
                      "," + std::to_string(cam.target.y) + "," + std::to_string(cam.target.z));

            if (sequence) {
                renderSequence(renderer, settings.view, views, frames, frameNumbers, common, *imagePattern,
                               meshPattern, meshFormat,
                               meshAscii, validation.get(), written, displayName(input), imageFormat,
                               bitDepth, settings);
            } else if (bench) {
                render::BenchResult b = render::runBenchmark(renderer, bench, 3, benchOrbit);
                renderer.refuseTessellationShortfall(displayName(input)); // before any JSON
                JsonWriter j;
                j.beginObject().field("frames", b.frames);
                j.field("samples", settings.samples).field("sample_shading", settings.sampleShading);
                j.field("supersample", settings.supersample);
                j.field("size", std::to_string(settings.width) + "x" + std::to_string(settings.height));
                j.key("gpu_ms").beginObject();
                j.field("compute", b.computeMs).field("draw", b.drawMs).field("total", b.totalMs);
                j.endObject();
                j.key("passes").beginObject();
                for (const auto& [name, ms] : b.passes) j.field(name, ms);
                j.endObject();
                j.field("cpu_ms", b.cpuMs)
                    .field("triangles", renderer.triangleCount())
                    .field("vertices_evaluated", renderer.verticesEvaluated())
                    .field("buffer_bytes", renderer.bufferBytes())
                    .field("peak_rss_mb", peakRssMb())
                    .field("device", ctx.deviceName());
                j.endObject();
                std::cout << j.str() << "\n";
                std::cout.flush();
            } else {
                renderer.renderFrame();
            }
            if (!sequence) renderer.refuseTessellationShortfall(displayName(input));
            for (const auto& p : renderer.frameTimes().passes) {
                char ms[32];
                std::snprintf(ms, sizeof ms, "%.3f", p.ms);
                cli::info("GPU " + p.name + ": " + ms + " ms");
            }
            if (writeImage)
                pngBytes = encodeImage(framePixels(renderer, imageFormat, bitDepth), imageFormat, bitDepth, settings);
            if (ply) {
                if (in.blend && in.mesh.hasUVs())
                    cli::info("--mesh-out: a blending surface shares its vertices across faces; "
                              "no texture UVs written");
                plyBytes = render::encodeMesh(renderer.drawnMesh(), *meshFormat, meshAscii);
            }
        }
        if (validation) {
            try {
                checkValidation(*validation);
            } catch (...) {
                removeFrames(written);
                throw;
            }
        }

        inputs.insert(inputs.end(), in.filesRead.begin(), in.filesRead.end());
        depfile.setRule(outputs, inputs); // the image and/or the mesh
        try {
            // A depfile that cannot be written fails the run before the outputs land; a sequence's
            // frames, already written, are removed.
            depfile.prepare();
            if (png) {
                png->write(pngBytes);
                png->finishWriting();
            }
            if (ply) {
                ply->write(plyBytes);
                ply->finishWriting();
            }
            if (png) png->commit();
            if (ply) ply->commit();
            depfile.commit();
            clearRemovalOnSignal(); // the run is complete: its frames stay
        } catch (...) {
            removeFrames(written);
            throw;
        }
        return 0;
    });
}
