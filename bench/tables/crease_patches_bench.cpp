// Crease patches: per mesh and depth, limn's elements (patches, single-crease
// patches among them, irregular faces) and table bytes with crease patches off and on, next to
// OpenSubdiv's patch table with useInfSharpPatch / useSingleCreasePatch off and on (same
// isolation, Gregory end caps; bytes as osd_oracle.h counts them). One JSON object per line on
// stdout, a table on stderr. Usage: bench_crease_patches [--depth N]... MESH...
#include "mesh/import.h"
#include "osd_oracle.h"
#include "subdiv/tables.h"
#include "subdiv/tables_chunk.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace limn;

int main(int argc, char** argv) {
    std::vector<int> depths;
    std::vector<std::string> meshes;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--depth") && i + 1 < argc)
            depths.push_back(std::atoi(argv[++i]));
        else
            meshes.push_back(argv[i]);
    }
    if (depths.empty()) depths = {3, 5};
    std::fprintf(stderr, "%-26s %2s | %-22s %-28s | %-17s %-17s\n", "mesh", "N",
                 "limn off: elem bytes", "limn on: elem (sc) bytes", "osd off: p bytes",
                 "osd on: p (sc) bytes");
    for (const std::string& path : meshes) {
        Warnings w;
        Mesh mesh;
        try {
            mesh = importMeshFile(path, w);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench_crease_patches: error: %s: %s\n", path.c_str(), e.what());
            return 1;
        }
        const SchemeOptions options = resolveSchemeOptions(mesh.tags, {});
        const std::string name = path.substr(path.find_last_of('/') + 1);
        for (int depth : depths) {
            struct Limn {
                size_t patches = 0, single = 0, irregular = 0, bytes = 0;
            } limn[2];
            try {
                for (int on = 0; on < 2; ++on) {
                    TablesOptions to;
                    to.depth = depth;
                    to.infSharpPatches = to.singleCreasePatches = on;
                    Warnings ww;
                    Tables t = buildTables(mesh, options, to, ww);
                    limn[on].patches = t.patches.size();
                    for (const Patch& p : t.patches) limn[on].single += p.crease != 0;
                    limn[on].irregular = t.irregular.size();
                    limn[on].bytes = encodeTablesChunk(t).payload.size();
                }
            } catch (const std::exception& e) {
                std::fprintf(stderr, "%-26s %2d   skipped: %s\n", name.c_str(), depth, e.what());
                continue;
            }
            const test::OsdPatchCounts off = test::osdPatchCounts(mesh, options, depth, false, false);
            const test::OsdPatchCounts on = test::osdPatchCounts(mesh, options, depth, true, true);
            std::printf("{\"mesh\":\"%s\",\"depth\":%d,"
                        "\"limn_off\":{\"patches\":%zu,\"irregular\":%zu,\"bytes\":%zu},"
                        "\"limn_on\":{\"patches\":%zu,\"single_crease\":%zu,\"irregular\":%zu,\"bytes\":%zu},"
                        "\"osd_off\":{\"regular\":%zu,\"gregory\":%zu,\"bytes\":%zu},"
                        "\"osd_on\":{\"regular\":%zu,\"single_crease\":%zu,\"gregory\":%zu,\"bytes\":%zu}}\n",
                        name.c_str(), depth, limn[0].patches, limn[0].irregular, limn[0].bytes,
                        limn[1].patches, limn[1].single, limn[1].irregular, limn[1].bytes,
                        off.regular, off.gregory, off.bytes, on.regular, on.singleCrease, on.gregory,
                        on.bytes);
            std::fprintf(stderr, "%-26s %2d | %5zu+%-5zu %10zu | %5zu+%-5zu (%4zu) %10zu | %5zu %10zu | %5zu (%4zu) %10zu\n",
                         name.c_str(), depth, limn[0].patches, limn[0].irregular, limn[0].bytes,
                         limn[1].patches, limn[1].irregular, limn[1].single, limn[1].bytes,
                         off.total(), off.bytes, on.total(), on.singleCrease, on.bytes);
        }
    }
    return 0;
}
