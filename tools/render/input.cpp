// limn-render's input: the container or mesh file with the one surface it draws, a sequence's
// frame meshes (--frames), the maps (--trim, --displace, --texture) and a glTF's material, and
// what they set in the renderer's settings.
#include "job.h"

#include "base/error.h"
#include "base/io.h"
#include "blend/blend_chunk.h"
#include "container/container.h"
#include "image/image_file.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"
#include "image/output_image.h"
#include "subdiv/tables_chunk.h"

#include <algorithm>
#include <bit>
#include <cstdio>

namespace limn::render_tool {

namespace {

// An image given to an option; errors say which option and what to do.
FloatImage loadMap(const std::string& option, const std::string& path) {
    try {
        return loadImage(path);
    } catch (const Error& e) {
        const std::string what = e.what();
        const bool missing = what.find("cannot open") != std::string::npos;
        Error out(e.kind(), option + ": " + what +
                                (missing ? "; give " + option + " an existing image file" : ""));
        out.setFile(path);
        throw out;
    }
}

void readSurface(const std::string& input, Surface surface, Warnings& warnings, RenderInput& in) {
    auto bytes = limn::readInput(input);
    try {
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
    } catch (Error& e) {
        e.setFile(displayName(input));
        throw;
    }
}

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
            m = loadOrImportMesh(f.path, limn::readInput(f.path), warnings, &filesRead);
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

// --frames FILE.gltf: the animation's frames, once the input is known to be the glTF's base mesh
// (its default-weight positions, vertex for vertex: the frames replace the control points by
// index, so a container made from another mesh, or the vertices in another order, would draw
// garbage). The input's faces may differ (limn-classify --quads joins triangles; the vertices
// stay).
std::vector<SequenceFrame> animationFrames(RenderJob& job, const Mesh& mesh) {
    GltfMorphFrames& a = *job.animation;
    const std::string glTF = displayName(job.framesPattern);
    if (a.base.size() != mesh.positions.size())
        throwBadInput("--frames " + glTF + ": the glTF's base mesh has " + std::to_string(a.base.size()) +
                      " vertices, the input has " + std::to_string(mesh.positions.size()) +
                      "; give the glTF itself or a container made from it");
    // Containers keep positions as f64, so a container made from the glTF has them exactly; the
    // tolerance only forgives a round trip through text.
    const double tolerance = 1e-9 * std::max(1.0, boundingBox(mesh).diagonal());
    for (size_t v = 0; v < a.base.size(); ++v)
        if (glm::length(a.base[v] - mesh.positions[v]) > tolerance)
            throwBadInput("--frames " + glTF + ": the input's vertex " + std::to_string(v) +
                          " is not where the glTF's base mesh (its default weights) has it; give the glTF "
                          "itself or a container made from it");
    std::vector<SequenceFrame> frames;
    for (size_t k = 0; k < a.positions.size(); ++k) {
        char when[64];
        std::snprintf(when, sizeof when, " at %.4g s", a.times[k]);
        frames.push_back({k, glTF + when, std::move(a.positions[k])});
    }
    a.positions.clear();
    return frames;
}

// The material's base colour texture, decoded; nullopt (with a warning) when it cannot be: the
// geometry is still worth drawing, in the base colour factor.
std::optional<FloatImage> materialTexture(const MeshMaterial& m, const std::string& input) {
    try {
        return readImageBytes(m.textureBytes, m.textureFormat);
    } catch (const Error& e) {
        cli::warn(displayName(input) + ": the base colour texture cannot be read (" + e.what() +
                  "); drawing the base colour factor instead");
        return std::nullopt;
    }
}

// The fixed grids draw irregular faces' corners only, and uniform tables (the full-subdivision
// baseline) draw every face from its corners by design; the view-adaptive tessellation draws
// points inside irregular faces. Never silently approximate (docs/irregular.md): say when drawn
// points can fall where the irregular faces' surface is only bilinear.
void warnApproximateIrregularFaces(const RenderJob& job, const RenderInput& in) {
    if (!in.tables || in.tables->uniform || job.edgePixels <= 0) return;
    const IrregularSurfaceCounts irr = irregularSurfaceCounts(*in.tables);
    if (irr.bilinear)
        cli::warn(displayName(job.input) + ": " + std::to_string(irr.bilinear) + " irregular faces are drawn " +
                  "bilinear between their corners (around a vertex of more than " +
                  std::to_string(kMaxBasisValence) + " faces, or tables made without their surface: " +
                  "re-run limn-tables)");
    else if (irr.basis + irr.subPatches && uint64_t(job.tess) > (uint64_t(1) << irr.exactLevels))
        cli::warn(displayName(job.input) + ": --tess " + std::to_string(job.tess) + " can draw points within 2^-" +
                  std::to_string(irr.exactLevels) + " of extraordinary corners, where the surface is " +
                  "bilinear; re-run limn-tables with --irregular-levels " +
                  std::to_string(std::bit_width(uint32_t(job.tess) - 1)));
}

} // namespace

void readRenderInput(RenderJob& job, RenderInput& in) {
    render::RenderSettings& settings = job.settings;
    const std::string &input = job.input, &displace = job.displace, &texture = job.texture,
                      &shade = job.shade;
    Warnings warnings;
    readSurface(input, job.surface, warnings, in);
    cli::printWarnings(warnings, displayName(input));
    if (in.blend && (!job.frameFiles.empty() || job.animation))
        throwUsage("--frames: a blending surface is built from its control points on the CPU (charts, "
              "local surfaces); render the frames' subdivision surface (--surface subdivision) or "
              "run limn-blend per frame");
    in.frames = job.animation ? animationFrames(job, in.mesh) : readFrameMeshes(job.frameFiles, in.mesh, in.filesRead);
    // No silent fallbacks: a classified container without tables draws its control mesh,
    // which is rarely what was meant; a --grid without a blending surface does nothing.
    if (job.surface == Surface::Auto && !in.tables && !in.blend && isContainerFile(input))
        cli::warn(displayName(input) + ": no subdivision tables (TBLS) or blending surface "
                  "(BLND): drawing the control mesh; run limn-tables for the smooth surface");
    if (!in.blend && job.grid != 16)
        cli::warn("--grid sets the blending surface's cells; " + displayName(input) +
                  " draws no blending surface, so it does nothing");
    if (job.displace.empty() && (job.displaceScale != 1 || job.displaceScalePercent || job.displaceMid != 0 || job.noSeamFix))
        cli::warn("--displace-scale, --displace-mid and --no-seam-fix shape the --displace map; "
                  "without --displace they do nothing");
    if (!job.trimPath.empty()) {
        try {
            settings.trim = blend::trimMaskFromImage(
                readImageFile8(job.trimPath), static_cast<uint32_t>(in.mesh.faceCount()));
        } catch (Error& e) {
            e.setFile(job.trimPath);
            throw;
        }
    }
    settings.tessCap = static_cast<uint32_t>(job.tess);
    settings.edgePixels = job.edgePixels;
    settings.maxError = job.maxError;
    warnApproximateIrregularFaces(job, in);
    if (!displace.empty()) {
        in.displacementMap = loadMap("--displace", displace);
        settings.displacementMap = &*in.displacementMap;
        settings.displaceScale = job.displaceScale;
        if (job.displaceScalePercent) {
            settings.displaceScale = job.displaceScale / 100 * boundingBox(in.mesh).diagonal();
            cli::info("--displace-scale " + std::to_string(job.displaceScale) + "% = " +
                      std::to_string(settings.displaceScale) + " world units");
        }
        settings.displaceMid = job.displaceMid;
        settings.seamFix = !job.noSeamFix;
        if (in.tables && !in.seams && in.mesh.hasUVs()) {
            cli::info("no SEAM chunk (limn-seams): computing the seam UVs now");
            in.seams = computeSeams(in.mesh, *in.tables, in.seamsHash);
        }
        if (in.seams) settings.seams = &*in.seams;
    }
    if (!texture.empty()) {
        in.textureMap = loadMap("--texture", texture);
        settings.texture = &*in.textureMap;
        if (shade == "lit") settings.shade = render::Shade::Texture;
    }
    if (in.material) { // a glTF's base colour (limn-classify keeps it in MATL)
        const glm::dvec4& f = in.material->baseColorFactor;
        if (!job.colorGiven)
            settings.baseColor =
                glm::dvec3(linearToSrgb(f.r), linearToSrgb(f.g), linearToSrgb(f.b));
        // Textures are drawn on the subdivision surface and the control mesh (as --texture is),
        // not on a blending surface; --shade normal and uv ask for something else.
        const bool shaded = shade == "lit" || shade == "texture";
        if (texture.empty() && in.material->hasTexture()) {
            if (shaded && in.blend)
                cli::warn(displayName(input) + ": the base colour texture is not drawn on a blending surface "
                          "(--surface subdivision draws it on the subdivision surface)");
            else if (shaded && !in.mesh.hasUVs())
                cli::warn(displayName(input) + ": the base colour texture is not drawn: the mesh has no "
                          "texture coordinates");
            else if (!shaded)
                cli::info("the base colour texture is drawn with --shade lit or texture; not drawn");
            else if ((in.textureMap = materialTexture(*in.material, input))) {
                settings.texture = &*in.textureMap;
                settings.shade = render::Shade::Texture;
            }
        }
    }
    settings.blendGrid = static_cast<uint32_t>(job.grid);
    if (in.blend && (!displace.empty() || !texture.empty()))
        throwUsage(
            "--displace and --texture apply to the subdivision surface, not a blending surface "
            "(--surface subdivision draws the TBLS one)");
    settings.evalInCompute =
        job.eval == "compute" || (job.eval == "auto" && (in.blend || !displace.empty()));
    settings.evaluateVertices = !job.meshOut.empty();
}

} // namespace limn::render_tool
