// limn-render's options: the parser chain with each option's help, filling RenderJob.
#include "job.h"

#include "base/error.h"
#include "render/blend_draw.h"
#include "render/sequence_plan.h"

#include <cmath>
#include <cstdlib>
#include <string>

namespace limn::render_tool {

namespace {

glm::dvec3 vec3Option(const std::string& option, const std::string& value) {
    auto v = cli::parseNumberList(option, value, 3);
    // Meshes are refused beyond 1e18 (mesh.cpp) for the GPU's float; a camera there sees nothing.
    for (double x : v)
        if (!(std::abs(x) <= 1e18)) throw Error(ErrorKind::Usage, option + ": each coordinate must be within +-1e18");
    return {v[0], v[1], v[2]};
}

// R,G,B with each component 0 to 1 (--color, --background, --back-faces).
glm::dvec3 colourOption(const std::string& option, const std::string& value) {
    auto c = cli::parseNumberList(option, value, 3);
    for (double x : c)
        if (!(x >= 0 && x <= 1)) throwUsage(option + ": each component must be 0 to 1");
    return {c[0], c[1], c[2]};
}

} // namespace

bool parseOptions(int ac, char** av, RenderJob& job) {
    // The parser writes straight into the job (its initial values are the defaults it shows).
    cli::Common& common = job.common;
    common.output.clear(); // "not given" matters with --bench
    std::string &input = job.input, &shade = job.shade, &device = job.device, &meshOut = job.meshOut,
                &eval = job.eval, &surfaceName = job.surfaceName, &trimPath = job.trimPath,
                &displace = job.displace, &texture = job.texture, &upAxis = job.upAxis,
                &camerasPath = job.camerasPath, &framesPattern = job.framesPattern;
    double &displaceScale = job.displaceScale, &displaceMid = job.displaceMid, &edgePixels = job.edgePixels,
           &maxError = job.maxError, &benchOrbit = job.benchOrbit;
    bool &displaceScalePercent = job.displaceScalePercent, &noSeamFix = job.noSeamFix, &wire = job.wire,
         &wireTriangles = job.wireTriangles, &alpha = job.alpha, &validate = job.validate,
         &syncValidation = job.syncValidation, &meshAscii = job.meshAscii, &viewGiven = job.viewGiven,
         &colorGiven = job.colorGiven, &sampleShading = job.sampleShading, &bitDepthGiven = job.bitDepthGiven;
    int &bench = job.bench, &tess = job.tess, &grid = job.grid, &samples = job.samples,
        &supersample = job.supersample, &bitDepth = job.bitDepth;
    uint32_t& turntable = job.turntable;
    uint64_t& maxMemory = job.maxMemory;
    render::RenderSettings& settings = job.settings;
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
                        throwUsage("--size: '" + v + "' is not WIDTHxHEIGHT with each 1 to 16384");
                    return static_cast<unsigned>(n);
                };
                const size_t x = v.find('x');
                if (x == std::string::npos)
                    throwUsage("--size: '" + v + "' is not WIDTHxHEIGHT with each 1 to 16384");
                const unsigned w = side(v.substr(0, x)), h = side(v.substr(x + 1));
                settings.width = w;
                settings.height = h;
            },
            "1024x768", "image size in pixels (each 1 to 16384)")
        .custom(
            "--view", "AZ,EL",
            [&](const std::string& v) {
                auto n = cli::parseNumberList("--view", v, 2);
                if (n[1] < -90 || n[1] > 90) throwUsage("--view: elevation must be -90 to 90");
                // As --light: 1e308 degrees made a NaN camera and a blank image with exit 0.
                if (n[0] < -360 || n[0] > 360) throwUsage("--view: azimuth must be -360 to 360");
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
                    throwUsage("--light: azimuth must be -360 to 360 and elevation -90 to 90");
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
                    throwUsage("--displace-scale: '" + v + "' is not a number (or a percentage "
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
        .real("--max-error", "PX", &maxError, 0, 4096,
              "view-adaptive tessellation: each patch edge gets the fewest segments\n"
              "                            whose chords stay within PX pixels of the limit surface\n"
              "                            on screen (estimated from the surface's second\n"
              "                            differences along the edge, docs/adaptive.md); 0:\n"
              "                            segments of about --edge-pixels (chord tolerance P/40)")
        .real("--interior-error", "PX", &settings.interiorError, 0, 4096,
              "view-adaptive tessellation: the --max-error allowed where an edge faces the\n"
              "                            eye (every sample's normal within 70 degrees of the\n"
              "                            view ray), where the error moves no outline, only where\n"
              "                            the shading lands; 0: --max-error everywhere\n"
              "                            (docs/adaptive.md, per-pixel normals)")
        .flag("--pixel-normals", &settings.pixelNormals,
              "view-adaptive, --shade lit: shade with the limit surface's normal at each\n"
              "                            pixel (evaluated at the triangle's interpolated\n"
              "                            parameters) instead of normals interpolated across the\n"
              "                            triangle; not with --eval compute, --wire, --displace\n"
              "                            or --mesh-out (those draw as without)")
        .real("--edge-pixels", "P", &edgePixels, 0, 4096,
              "view-adaptive tessellation: no segment longer than P pixels on screen,\n"
              "                            decided per frame on the GPU\n"
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
                    throwUsage("--samples: '" + v + "' is not 1 or 4 (the MSAA counts WebGPU offers)");
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
                if (v != "8" && v != "16") throwUsage("--bit-depth: '" + v + "' is not 8 or 16");
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
        .custom(
            "--max-output", "SIZE",
            [&](const std::string& v) { job.maxOutput = cli::parseByteSize("--max-output", v); }, "",
            "most bytes a sequence may write, e.g. 2G: one whose estimated size (frames\n"
            "                            times width x height x channels x bytes per sample,\n"
            "                            uncompressed, plus --mesh-out meshes) is more is refused\n"
            "                            before any work [default: the free space of the frames'\n"
            "                            folder]")
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
                    throwUsage("--turntable: '" + v + "' is not a number of views from 1 to " +
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
              "                            frame k of the input goes to -o NAME_%04d.png with the same k.\n"
              "                            A .gltf or .glb instead: its first animation's morph-target\n"
              "                            weights, frame k at its k-th keyframe (INPUT: that glTF, or a\n"
              "                            container made from it)")
        .custom(
            "--fps", "N", [&](const std::string& v) { job.fps = render::parseFps("--fps", v); }, "",
            "with --frames FILE.gltf: sample the animation N times a second (0 < N <= 1000)\n"
            "                            from its first keyframe to its last, instead of at its keyframes")
        .custom(
            "--shard", "I/N", [&](const std::string& v) { job.shard = render::parseShard("--shard", v); }, "",
            "render only part I of N (0 <= I < N) of the sequence, a contiguous block of\n"
            "                            its frames, framed and lit as the whole sequence: the N\n"
            "                            parts write the one-process frames (a Slurm array task:\n"
            "                            $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)")
        .custom(
            "--frame-range", "A-B",
            [&](const std::string& v) { job.frameRange = render::parseFrameRange("--frame-range", v); }, "",
            "render only the sequence's frames numbered A to B (both included), framed as\n"
            "                            the whole sequence (re-render a few frames; with\n"
            "                            --shard, the range is split)")
        .integer("--bench", "FRAMES", &bench, 0, 100000,
                 "render FRAMES frames after 3 warm-up frames and print one JSON object of\n"
                 "                            medians to standard output; 0 renders once")
        .real("--bench-orbit", "DEG", &benchOrbit, -360, 360,
              "with --bench: turn the camera DEG degrees about its target before every frame")
        .notes(kRenderNotes);
    parser.exitCodes(kRenderExitCodes);
    return parser.parse(ac, av);
}

} // namespace limn::render_tool
