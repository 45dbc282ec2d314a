// limn_refine_mesh IN LEVELS OUT.obj: OpenSubdiv's uniform Catmull-Clark refinement of IN as an
// OBJ with the same limit surface (the sharpness left after LEVELS steps is kept as tags). The
// build uses it to make the dense benchmark and test meshes (the 100,800-quad car is
// catmark_car refined 3 times) instead of keeping megabytes of generated text in the repository.
#include "mesh/import.h"
#include "mesh/obj.h"
#include "osd_oracle.h"
#include "topology/features.h"

#include "base/io.h"

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: limn_refine_mesh IN LEVELS OUT.obj\n");
        return 2;
    }
    try {
        const int levels = std::stoi(argv[2]);
        if (levels < 0 || levels > 6) throw std::runtime_error("LEVELS must be 0-6");
        limn::Warnings w;
        limn::Mesh mesh = limn::importMeshFile(argv[1], w);
        const limn::SchemeOptions so = limn::resolveSchemeOptions(mesh.tags, {});
        limn::Mesh refined = limn::test::osdUniformRefinedMesh(mesh, so, levels);
        const std::string text = limn::writeObj(refined);
        limn::writeOutput(argv[3], {reinterpret_cast<const uint8_t*>(text.data()), text.size()},
                          limn::OutputFile::Kind::Text);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "limn_refine_mesh: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
