// What a limn-render run writes, decided from its options before any work: whether an image is
// written and where (standard output by default), its format by the name's extension, the
// --mesh-out format, and for a sequence the frame-numbered names of every frame's files. Nothing
// here reads or writes a file (but for telling a device or FIFO from a file name); every refusal
// is an Error(Usage) with the message the tool prints.
#pragma once

#include "base/io.h"
#include "export/mesh_export.h"
#include "image/output_image.h"
#include "render/sequence.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace limn::render {

struct OutputRequest {
    std::string image;      // -o as given; empty: not given
    std::string mesh;       // --mesh-out; empty: none
    bool meshAscii = false; // --mesh-ascii
    bool bitDepthGiven = false;
    bool bench = false;    // --bench: its JSON goes to standard output
    bool sequence = false; // --turntable, --cameras or --frames: one image per frame
};

struct OutputPlan {
    // Whether an image is written: with -o, and by default unless --bench or --mesh-out is the
    // output asked for. `image` is then its path ("-": standard output).
    bool writeImage = false;
    std::string image;
    // By the name (a device or FIFO such as /dev/null, and standard output: PNG).
    ImageFormat imageFormat = ImageFormat::Png;
    std::string mesh; // empty: no --mesh-out
    std::optional<exporting::ExportFormat> meshFormat;
    bool meshAscii = false;
    // A sequence's -o and --mesh-out, with their frame number.
    std::optional<FramePattern> imagePattern, meshPattern;

    // The text formats (ASCII PLY, OBJ, .gltf) may go to a terminal, the rest not.
    OutputFile::Kind meshFileKind() const;
    // A sequence's files for frames `numbers`: per frame its image, then its mesh (--mesh-out).
    std::vector<std::string> framePaths(const std::vector<uint64_t>& numbers) const;
};

// Throws Error(Usage): a sequence without a frame-numbered -o (or with a --mesh-out without
// one), a frame number in a single image's name, an unknown image or mesh extension, the image
// and the mesh (or --bench's JSON) both on standard output, --mesh-ascii without a .ply
// --mesh-out, --bit-depth without a PNG.
OutputPlan planOutputs(const OutputRequest& request);

// A sequence's size on disk, estimated before any work so that a run that cannot fit is refused
// before it writes anything (--max-output). An image counts uncompressed: width x height x
// channels x bytes per sample (PNG: RGB, or RGBA with `alpha`, 1 or 2 bytes; EXR: RGBA and Z as
// 32-bit floats); PNG's compression makes most frames smaller, but what a frame compresses to is
// not known before it is drawn. A mesh counts the least its drawn triangles take (indices, and
// vertices of six 32-bit floats), from the control mesh's triangles (a subdivision surface draws
// more): a lower bound.
struct FrameSize {
    uint32_t width = 0, height = 0;
    bool alpha = false;
    int bitDepth = 8;
    uint64_t meshTriangles = 0; // the control mesh's triangles; 0: not known yet
};
uint64_t estimateFrameBytes(const OutputPlan& plan, const FrameSize& size);

// A --mesh-out file's kind, as OutputPlan::meshFileKind.
OutputFile::Kind meshFileKind(exporting::ExportFormat format, bool ascii);

} // namespace limn::render
