// Per-configuration bases for decaying-crease faces, a builder-side prototype
// (lib/subdiv/crease_basis.h; docs/irregular-tables.md, "Decaying-crease configurations"): per mesh and
// depth, how many quadtree faces take a chain, how many configurations and band programs there
// are, whether the chains' sub-patch points are the quadtree's (bitwise), and what they would
// store. One JSON object per line on stdout, a readable line on stderr.
// Usage: bench_crease_bases [-K 6] [-E k0|k|chains] MESH:DEPTH...
//   -E: instead, only build the tables and encode their TBLS chunk, without the irregular
//   faces' levels (k0: --irregular-levels 0), with them (k: K), or with K but the faces that have
//   a decaying-crease chain not refined (chains; TablesOptions::creaseChainsPrototype): its
//   bytes, and the chains' estimated bytes; run under callgrind for the instructions of each.
#include "mesh/import.h"
#include "crease_study.h"
#include "topology/features.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

using namespace limn;

int main(int argc, char** argv) {
    int K = 6, first = 1;
    std::string estimate;
    while (first + 1 < argc && (std::string(argv[first]) == "-K" || std::string(argv[first]) == "-E")) {
        if (std::string(argv[first]) == "-K")
            K = std::atoi(argv[first + 1]);
        else
            estimate = argv[first + 1];
        first += 2;
    }
    if (!estimate.empty() && estimate != "k0" && estimate != "k" && estimate != "chains") first = argc;
    if (first >= argc) {
        std::fprintf(stderr, "usage: bench_crease_bases [-K levels] [-E k0|k|chains] MESH:DEPTH...\n");
        return 2;
    }
    for (int i = first; i < argc; ++i) {
        const std::string arg = argv[i];
        const size_t colon = arg.rfind(':');
        if (colon == std::string::npos) {
            std::fprintf(stderr, "bench_crease_bases: %s: expected MESH:DEPTH\n", arg.c_str());
            return 2;
        }
        try {
            Warnings warnings;
            const Mesh mesh = importMeshFile(arg.substr(0, colon), warnings);
            TablesOptions opts;
            opts.depth = std::atoi(arg.c_str() + colon + 1);
            opts.irregularLevels = K;
            // The study compares the chains with the quadtrees they replace, and the estimate's
            // modes are quadtrees (k0, k) or the prototype (chains): not the tables' chains.
            opts.creaseChains = false;
            std::string name = arg.substr(0, colon);
            name = name.substr(name.find_last_of('/') + 1);
            if (!estimate.empty()) {
                opts.irregularLevels = estimate == "k0" ? 0 : K;
                opts.creaseChainsPrototype = estimate == "chains";
                const CreaseTablesEstimate e =
                    estimateCreaseTables(mesh, resolveSchemeOptions(mesh.tags, {}), opts, warnings);
                std::printf("{\"mesh\":\"%s\",\"depth\":%d,\"mode\":\"%s\",\"K\":%d,\"tables_bytes\":%zu,"
                            "\"chain_faces\":%zu,\"chains\":%zu,\"band_programs\":%zu,\"program_bytes\":%zu,"
                            "\"face_bytes\":%zu,\"total_bytes\":%zu}\n",
                            name.c_str(), opts.depth, estimate.c_str(), opts.irregularLevels, e.tablesBytes, e.faces,
                            e.chains, e.bandPrograms, e.programBytes, e.faceBytes,
                            e.tablesBytes + e.programBytes + e.faceBytes);
                continue;
            }
            const auto t0 = std::chrono::steady_clock::now();
            const CreaseBasisStudy s = studyCreaseBases(mesh, resolveSchemeOptions(mesh.tags, {}), opts, warnings);
            const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::printf("{\"mesh\":\"%s\",\"depth\":%d,\"K\":%d,\"quadtree_faces\":%zu,\"qualifying\":%zu,"
                        "\"configurations\":%zu,\"band_programs\":%zu,\"end_leaf\":%zu,\"end_smooth\":%zu,"
                        "\"end_regular\":%zu,\"bands\":%zu,\"max_bands\":%zu,\"kinds_bspline\":%zu,"
                        "\"kinds_crease\":%zu,\"kinds_boundary\":%zu,\"points\":%zu,\"bitwise\":%zu,"
                        "\"max_difference\":%.3g,\"deduped_bitwise\":%zu,\"deduped_max_difference\":%.3g,"
                        "\"structure_mismatches\":%zu,\"level_n_mismatches\":%zu,\"program_bytes\":%zu,"
                        "\"face_bytes\":%zu,\"support_points\":%zu,\"key_seconds\":%.6f,\"chain_seconds\":%.6f,"
                        "\"study_seconds\":%.3f,\"shared_programs\":%zu,\"shared_mismatches\":%zu,\"repeated_bands\":%zu,"
                        "\"shared_program_bytes\":%zu,\"band_kind_bytes\":%zu,\"shared_max_difference\":%.3g,\"failures\":\"%s\",\"leaf_corners\":%zu,\"leaf_max_difference\":%.3g,"
                        "\"tree_faces\":%zu,\"tree_nodes\":%zu,\"tree_level_nodes\":\"%s\",\"tree_node_keys\":%zu,\"tree_node_classes\":%zu,\"tree_turned_keys\":%zu,\"tree_turned_program_bytes\":%zu,"
                        "\"tree_shared_programs\":%zu,\"tree_program_bytes\":%zu,\"tree_shared_program_bytes\":%zu,"
                        "\"tree_face_bytes\":%zu,\"tree_points\":%zu,\"tree_bitwise\":%zu,"
                        "\"tree_max_difference\":%.3g,\"tree_structure\":%zu,\"tree_seconds\":%.4f}\n",
                        name.c_str(), opts.depth, K, s.quadtreeFaces, s.qualifying, s.configurations, s.bandPrograms,
                        s.endLeaf, s.endSmooth, s.endRegular, s.bands, s.maxBands, s.kindsBSpline, s.kindsCrease,
                        s.kindsBoundary, s.pointsCompared, s.pointsBitwise, s.maxDifference, s.dedupedBitwise,
                        s.dedupedMaxDifference, s.structureMismatches, s.levelNMismatches, s.programBytes,
                        s.faceBytes, s.supportPoints, s.keySeconds, s.chainSeconds, total, s.sharedPrograms,
                        s.sharedMismatches, s.repeatedBands, s.sharedProgramBytes, s.bandKindBytes,
                        s.sharedMaxDifference, s.failures.c_str(), s.leafCorners, s.leafMaxDifference,
                        s.treeFaces, s.treeNodes, s.treeLevelNodes.c_str(), s.treeNodeKeys, s.treeNodeClasses,
                        s.treeTurnedKeys, s.treeTurnedProgramBytes, s.treeSharedPrograms, s.treeProgramBytes, s.treeSharedProgramBytes, s.treeFaceBytes, s.treePoints, s.treeBitwise,
                        s.treeMaxDifference, s.treeStructure, s.treeSeconds);
            std::fprintf(stderr,
                         "%-24s d%d: %zu/%zu quadtree faces with a chain, %zu configurations, %zu band programs "
                         "(%zu B), ends leaf/smooth/regular %zu/%zu/%zu; points %zu, bitwise %zu (deduped %zu), "
                         "max %.3g (deduped %.3g), structure %zu\n",
                         name.c_str(), opts.depth, s.qualifying, s.quadtreeFaces, s.configurations, s.bandPrograms,
                         s.programBytes, s.endLeaf, s.endSmooth, s.endRegular, s.pointsCompared, s.pointsBitwise,
                         s.dedupedBitwise, s.maxDifference, s.dedupedMaxDifference, s.structureMismatches);
            if (s.treeFaces > 0)
                std::fprintf(stderr,
                             "%-24s d%d: %zu of the others as crease trees, nodes %s, %zu node keys (%zu B; %zu turned (%zu B), %zu sharpness classes), %zu shared "
                             "(%zu B), faces %zu B; points %zu, bitwise %zu, max %.3g, structure %zu\n",
                             name.c_str(), opts.depth, s.treeFaces, s.treeLevelNodes.c_str(), s.treeNodeKeys,
                             s.treeProgramBytes, s.treeTurnedKeys, s.treeTurnedProgramBytes, s.treeNodeClasses, s.treeSharedPrograms, s.treeSharedProgramBytes, s.treeFaceBytes,
                             s.treePoints, s.treeBitwise, s.treeMaxDifference, s.treeStructure);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench_crease_bases: %s: %s\n", arg.c_str(), e.what());
            return 1;
        }
    }
    return 0;
}
