// fuzz_render_input: arbitrary bytes through everything limn-render does on the CPU with a
// container before the GPU sees it: framing, mesh, subdivision tables (TBLS), seam UVs (SEAM),
// the smooth UV surface (FVSF, walked as the GPU walks it), and the tessellation built from the
// tables. A mutated TBLS keeps its mesh hash, so the decoder's
// own index checks are all that stands between it and the tessellation. Anything but
// Error(BadInput) is a bug.
#include "base/error.h"
#include "container/container.h"
#include "mesh/mesh_chunks.h"
#include "seams/seams.h"
#include "subdiv/fvar_chunk.h"
#include "subdiv/tables_chunk.h"
#include "tess/tessellation.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace limn;
    try {
        Container c = parseContainer({data, size});
        Mesh mesh = loadMesh(c);
        const Chunk* tb = c.find(kTablesChunk);
        if (!tb) return 0;
        Tables tables = decodeTablesChunk(*tb, &mesh);
        if (const Chunk* sm = c.find(kSeamsChunk))
            decodeSeamsChunk(*sm, static_cast<uint32_t>(tables.patches.size() + tables.irregular.size()),
                             seamsSourceHash(c));
        if (const Chunk* fv = c.find(kFvarSurfaceChunk)) {
            const FvarSurfaceChunk f = decodeFvarSurfaceChunk(*fv, &mesh, &tables.options);
            // Every root's walk down its quadtree (fvar_eval.glsl) stays within the nodes.
            for (uint32_t p = 0; p < f.ptexCount; ++p)
                for (uint32_t v = f.surface.nodes[p]; v != 0xFFFFFFFFu && !(v & 0x80000000u);)
                    v = f.surface.nodes.at(v + 3);
            if (f.depth == tables.depth) checkFvarSurfaceCoverage(f, tables);
            // Its smooth faces expand into the records the GPU reads, every leaf naming one.
            const FaceVaryingSurface::Gpu g = expandSmoothFaces(f.surface);
            for (uint32_t v : g.nodes)
                if (v != 0xFFFFFFFFu && (v & 0x80000000u) && size_t(v & 0x7FFFFFFFu) * 9 >= g.records.size()) std::abort();
        }
        buildTessellation(mesh, tables, 2, mesh.hasUVs());
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::BadInput) std::abort();
    }
    return 0;
}
