#include "render/output_plan.h"

#include "base/error.h"

namespace limn::render {

using exporting::ExportFormat;

OutputFile::Kind meshFileKind(ExportFormat format, bool ascii) {
    return ascii || format == ExportFormat::Obj || format == ExportFormat::Gltf ? OutputFile::Kind::Text
                                                                            : OutputFile::Kind::Binary;
}

uint64_t estimateFrameBytes(const OutputPlan& plan, const FrameSize& size) {
    uint64_t bytes = 0;
    if (plan.writeImage) {
        const uint64_t pixels = uint64_t(size.width) * size.height;
        bytes += plan.imageFormat == ImageFormat::Exr ? pixels * 5 * sizeof(float)
                                                      : pixels * (size.alpha ? 4 : 3) * uint64_t(size.bitDepth / 8);
    }
    // Per triangle three 4-byte indices, and half a vertex of 24 bytes (a closed triangle mesh
    // has about half as many vertices as triangles; splits at UV seams and creases add more):
    // binary PLY's size at the least; the text formats take more.
    if (plan.meshPattern || !plan.mesh.empty()) bytes += size.meshTriangles * (3 * 4 + 24 / 2);
    return bytes;
}

OutputFile::Kind OutputPlan::meshFileKind() const {
    return render::meshFileKind(*meshFormat, meshAscii);
}

std::vector<std::string> OutputPlan::framePaths(const std::vector<uint64_t>& numbers) const {
    std::vector<std::string> paths;
    for (uint64_t n : numbers) {
        paths.push_back(framePath(*imagePattern, n));
        if (meshPattern) paths.push_back(framePath(*meshPattern, n));
    }
    return paths;
}

OutputPlan planOutputs(const OutputRequest& request) {
    OutputPlan plan;
    plan.image = request.image;
    plan.mesh = request.mesh;
    plan.meshAscii = request.meshAscii;
    if (request.sequence) {
        if (plan.image.empty() || isStdio(plan.image))
            throwUsage("a sequence writes one image per frame: give -o NAME_%04d.png");
        plan.imagePattern = parseFramePattern("-o", plan.image); // exactly one frame number
        if (!plan.mesh.empty()) plan.meshPattern = parseFramePattern("--mesh-out", plan.mesh);
    } else {
        for (const std::string* path : {&plan.image, &plan.mesh})
            if (hasFrameNumber(*path))
                throwUsage("'" + *path + "' numbers frames, but there is one image; give --turntable, "
                      "--cameras or --frames (or write %% for a literal %)");
    }
    if (request.bench && isStdio(plan.image) && !plan.image.empty())
        throwUsage("--bench prints JSON on standard output; write the image with -o FILE");
    if (!plan.mesh.empty()) {
        plan.meshFormat = exporting::exportFormatFromPath(plan.mesh);
        if (!plan.meshFormat)
            throw Error(ErrorKind::Usage,
                        std::string("--mesh-out: unknown extension; limn-render writes ") +
                            exporting::kExportFormats,
                        plan.mesh);
        if (plan.meshAscii && *plan.meshFormat != ExportFormat::Ply)
            throwUsage("--mesh-ascii applies to a .ply --mesh-out, not " + plan.mesh);
    }
    if (plan.meshAscii && plan.mesh.empty())
        throwUsage("--mesh-ascii applies to a .ply --mesh-out; give --mesh-out FILE.ply");
    // The image goes to standard output by default, unless --bench or --mesh-out is the
    // output asked for.
    plan.writeImage = !plan.image.empty() || (!request.bench && plan.mesh.empty());
    if (isStdio(plan.mesh) && !plan.mesh.empty() &&
        (request.bench || (plan.writeImage && isStdio(plan.image))))
        throwUsage("--mesh-out - and the image (or --bench JSON) cannot share standard output");
    if (plan.image.empty() && plan.writeImage) plan.image = "-";
    // The image format comes from the name, before any work; never silently another one.
    if (plan.writeImage) {
        // A device or pipe (-o /dev/null, a FIFO) is a stream like standard output: PNG.
        auto f = isStreamPath(plan.image) ? std::optional(ImageFormat::Png) : imageFormatFromPath(plan.image);
        if (!f)
            throw Error(ErrorKind::Usage,
                        std::string("unknown image extension; limn-render writes ") + kImageFormats +
                            " (or - for PNG on standard output)",
                        plan.image);
        plan.imageFormat = *f;
    }
    if (request.bitDepthGiven && (!plan.writeImage || plan.imageFormat == ImageFormat::Exr))
        throwUsage(plan.writeImage ? "--bit-depth sets PNG samples; an .exr is always 32-bit float"
                              : "--bit-depth applies to the image, and none is written");
    return plan;
}

} // namespace limn::render
