// The decaying-crease chains (lib/subdiv/crease_basis.h) measured against the tables' own
// quadtrees, and what tables with chains would hold: study code for bench_crease_bases and the
// CreaseChains tests, kept out of lib/ (the product builds and reads chains, it does not study
// them).
#pragma once

#include "subdiv/crease_basis.h"

#include <string>

namespace limn {

// What studyCreaseBases measured on one mesh (bench/tables/crease_bases.cpp prints it).
struct CreaseBasisStudy {
    size_t quadtreeFaces = 0; // roots of T_N that are neither smooth faces nor bilinear
    size_t qualifying = 0;    // of those, faces with a chain
    size_t configurations = 0, bandPrograms = 0; // distinct band-1 keys; distinct band keys
    size_t endLeaf = 0, endSmooth = 0, endRegular = 0;
    size_t bands = 0, maxBands = 0;
    size_t kindsBSpline = 0, kindsCrease = 0, kindsBoundary = 0; // per distinct band's quadrant
    // The chains' sub-patch control points (and a Smooth end's support) against the tables'
    // quadtree, evaluated by evaluateVertices: each face's own chain, and the chain of the first
    // face of its configuration (what a per-configuration basis stores).
    size_t pointsCompared = 0, pointsBitwise = 0, dedupedBitwise = 0;
    double maxDifference = 0, dedupedMaxDifference = 0; // relative to the box's diagonal
    // The quadtree faces without a chain, as "eEsSbB:count": E corners extraordinary, S of the
    // others sharp (a sharp vertex or edge), B the band where the best corner's chain met an
    // irregular quadrant away from its corner (1: at once).
    std::string failures;
    // A leaf end's corners away from the feature corner, evaluated on the last band's
    // sub-patches that share them, against the quadtree leaf's limit points (evaluateLimitPoints):
    // a format could leave the leaves' limit points out.
    size_t leafCorners = 0;
    double leafMaxDifference = 0; // relative to the box's diagonal
    size_t structureMismatches = 0; // quadrant codes or patch kinds that differ
    size_t levelNMismatches = 0;    // this study's level-N points against the tables' (corners)
    // Band programs by programKey (sharpness from 2 on clamped): how many distinct, whether
    // every band of one such key has the same program (rows, weights, control rows), and how
    // many bands repeat the previous band's program (the refinements a builder could skip).
    size_t sharedPrograms = 0, sharedMismatches = 0, repeatedBands = 0;
    size_t sharedProgramBytes = 0, bandKindBytes = 0;
    double sharedMaxDifference = 0; // between such programs' points, support values of size ~1
    // Bytes a format would add: the distinct band programs (TBLS version 5's program encoding),
    // 9 bytes of kinds per band program, and per qualifying face two bytes plus its support's
    // points (at two bytes each, about what version 5's smooth points take).
    size_t programBytes = 0, faceBytes = 0;
    size_t supportPoints = 0;
    double keySeconds = 0, chainSeconds = 0; // keys of every quadtree face; one chain per configuration
    // The quadtree faces without a chain, as crease trees (crease_tree.h): how many have one,
    // their irregular nodes ("nodes per level below N", summed over faces), each tree's control
    // points and smooth supports against the quadtree (bit for bit; the largest difference
    // relative to the box's diagonal; codes or kinds that differ), and what a format would hold:
    // one program per distinct node key (treeNodeKeys; treeSharedPrograms once the keys'
    // sharpness from 1 on is clamped and the programs give the same points to 1e-12) in TBLS
    // version 5's encoding with 64 control rows and 20 bytes of child codes and kinds, and per
    // face 2 bytes and 2 per support point.
    size_t treeFaces = 0, treeNodes = 0, treeNodeKeys = 0, treeSharedPrograms = 0;
    // Distinct node keys with every sharpness as its class (0, in (0, 1), from 1 on): what a
    // program with weights as functions of the sharpness below 1 would be per.
    size_t treeNodeClasses = 0;
    // Distinct node keys, each the least of its four corners' (a program per such key and a
    // corner per node would share across turns), and their programs' bytes (each key's first
    // node's, from its corner 0: the same rows in another order).
    size_t treeTurnedKeys = 0, treeTurnedProgramBytes = 0;
    size_t treeProgramBytes = 0, treeSharedProgramBytes = 0, treeFaceBytes = 0;
    size_t treePoints = 0, treeBitwise = 0, treeStructure = 0;
    double treeMaxDifference = 0, treeSeconds = 0;
    std::string treeLevelNodes;
};

// Builds `mesh`'s tables as buildTables does, and for every quadtree face of T_N with a chain:
// counts, checks and sizes above. Throws as buildTables does.
CreaseBasisStudy studyCreaseBases(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                                  Warnings& warnings);

// What tables would hold with decaying-crease chains (TablesOptions::creaseChainsPrototype):
// the TBLS chunk of the tables built with opts (payload bytes, as limn-info's), and, where
// opts.creaseChainsPrototype is set, the faces taken, their chains and the bytes a format would
// add for them: the programs once per programKey (sharpness from 2 on clamped) and 15 bytes of
// kinds per band of each chain (CreaseBasisStudy's sharedProgramBytes + bandKindBytes), and
// faceBytes as CreaseBasisStudy's.
struct CreaseTablesEstimate {
    size_t tablesBytes = 0;
    size_t faces = 0, chains = 0, bandPrograms = 0;
    size_t programBytes = 0, faceBytes = 0;
};
CreaseTablesEstimate estimateCreaseTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                                          Warnings& warnings);

} // namespace limn
