// The decaying-crease chains (lib/subdiv/crease_basis.h, a builder-side prototype) against the
// quadtrees the tables hold for the same faces: the chains are made from each face's own copy of
// its level-N neighbourhood, the quadtrees by refining the whole level K more times, and both
// are evaluated from the same level-N points (evaluateVertices for the quadtrees).
#include "mesh/import.h"
#include "crease_study.h"
#include "test_support.h"
#include "topology/features.h"

#include <gtest/gtest.h>

using namespace limn;

namespace {

CreaseBasisStudy study(const std::string& model, int depth) {
    Warnings w;
    const Mesh m = importMeshFile(test::modelPath("osd/catmark/" + model).string(), w);
    TablesOptions opts;
    opts.depth = depth;
    opts.creaseChains = false; // the study compares the chains with the quadtrees they replace
    return studyCreaseBases(m, resolveSchemeOptions(m.tags, {}), opts, w);
}

} // namespace

// Every sub-patch point of every band, and the support where the crease has decayed into a
// smooth face, is the quadtree's to the bit; the kinds (single-crease bits and sharpness,
// boundary bits) and the quadtree's shape agree; a configuration's chain made from another face
// of the same key gives the same points up to rounding (its sums in that face's order).
TEST(CreaseChains, GiveTheQuadtreesSubPatchesBitForBit) {
    struct Case {
        const char* model;
        int depth;
        bool all; // every quadtree face has a chain
    };
    for (const Case& c : {Case{"catmark_car.obj", 3, true}, Case{"catmark_chaikin0.obj", 2, true},
                          Case{"catmark_chaikin1.obj", 2, false}, Case{"catmark_cubes_semisharp.obj", 2, true}}) {
        SCOPED_TRACE(std::string(c.model) + " depth " + std::to_string(c.depth));
        const CreaseBasisStudy s = study(c.model, c.depth);
        EXPECT_EQ(s.levelNMismatches, 0u);
        EXPECT_GT(s.qualifying, 0u);
        if (c.all) {
            EXPECT_EQ(s.qualifying, s.quadtreeFaces);
        }
        EXPECT_EQ(s.structureMismatches, 0u);
        EXPECT_GT(s.pointsCompared, 16 * s.qualifying);
        EXPECT_EQ(s.pointsBitwise, s.pointsCompared);
        EXPECT_LT(s.dedupedMaxDifference, 1e-14);
        EXPECT_LT(s.sharedMaxDifference, 1e-14);
        EXPECT_LE(s.configurations, s.qualifying);
    }
}

// The faces a chain cannot take along Chaikin creases of varying sharpness (every child edge a
// sharpness of its own, so every node along the crease stays irregular: chaikin1 d2 has
// 108/228/324 irregular nodes at levels 2-4) as crease trees (tests/support/crease_tree.h),
// every node's program over its own support made from the face's copy: every sub-patch point
// and smooth support of the quadtree to the bit, the same shape and kinds.
TEST(CreaseChains, TreesGiveTheChaikinQuadtreesBitForBit) {
    for (const char* model : {"catmark_chaikin1.obj", "catmark_chaikin2.obj"}) {
        SCOPED_TRACE(model);
        const CreaseBasisStudy s = study(model, 2);
        EXPECT_GT(s.treeFaces, 0u);
        EXPECT_EQ(s.qualifying + s.treeFaces, s.quadtreeFaces);
        EXPECT_EQ(s.treeStructure, 0u);
        EXPECT_GT(s.treePoints, 16 * s.treeNodes);
        EXPECT_EQ(s.treeBitwise, s.treePoints);
        EXPECT_LE(s.treeSharedPrograms, s.treeNodeKeys);
    }
    EXPECT_EQ(study("catmark_chaikin1.obj", 2).treeLevelNodes, "108/228/324");
}

// The car's faces around its sharpness-6 creases at depth 3: 312 faces, 20 configurations; 304
// chains end in a smooth face of the per-valence basis at level 6 (three crease bands), 8 (the
// darts' ends) in a regular patch. (Its 4 faces around boundary vertices, which kept an irregular
// corner child to level N + K, take boundary bases instead.)
TEST(CreaseChains, CarConfigurations) {
    const CreaseBasisStudy s = study("catmark_car.obj", 3);
    EXPECT_EQ(s.quadtreeFaces, 312u);
    EXPECT_EQ(s.configurations, 20u);
    EXPECT_EQ(s.endSmooth, 304u);
    EXPECT_EQ(s.endRegular, 8u);
    EXPECT_EQ(s.endLeaf, 0u);
}
