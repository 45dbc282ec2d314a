// The multi-level procedure of adaptive Loop subdivision (paper 004, section 3.3; math.md B.7):
// at each level compute every even and odd position, measure every edge (metric.h), split the
// edges whose normalized distance is at least ε, and retriangulate (refine.h). `uniform` splits
// every edge: plain Loop subdivision.
#pragma once

#include "loop/metric.h"
#include "loop/refine.h"
#include "loop/trimesh.h"

#include <cstdint>
#include <vector>

namespace limn::loop {

enum class Normalization {
    BoundingBox, // F(d) = d / D, D the bounding-box diagonal of the control mesh (all levels)
    EdgeLength,  // F(d) = d / |e|, |e| the edge's current length
};

// Where the vertices of the result come from.
enum class Positions {
    Exact, // the uniform Loop hierarchy of the control mesh (hierarchy.h)
    Paper, // Loop's masks re-applied to the adaptive mesh at each level (paper 004, math.md B.7)
};

struct AdaptiveOptions {
    int levels = 2;
    double epsilon = 2e-5; // the CLI default for bounding-box normalization (docs/loop.md)
    Normalization normalization = Normalization::BoundingBox;
    Metric metric = Metric::Full;
    EvenUpdate evenUpdate = EvenUpdate::Split;
    Positions positions = Positions::Exact;
    bool uniform = false;
};

struct LevelStats {
    int level = 0;
    uint32_t edges = 0;      // edges of the mesh this level refined
    uint32_t splitEdges = 0; // of those, split
    uint32_t vertices = 0;   // after the level
    uint32_t faces = 0;
};

struct AdaptiveResult {
    TriMesh mesh;
    // One entry per level run. A level that splits nothing ends the refinement (math.md B.7), so
    // there may be fewer entries than levels, the last with splitEdges = 0.
    std::vector<LevelStats> levels;
};

// Whether each edge of `level` should be split: F(d(e)) >= ε (math.md B.4; the paper's
// pseudo-code has the comparison inverted). `diagonal` is the control mesh's D.
std::vector<uint8_t> splitDecisions(const Level& level, const std::vector<glm::dvec3>& even,
                                    const std::vector<glm::dvec3>& odd,
                                    const AdaptiveOptions& options, double diagonal);

AdaptiveResult subdivide(const TriMesh& control, const AdaptiveOptions& options);

} // namespace limn::loop
