// Distance of a mesh to the limit surface of a control mesh (math.md B.8), relative to the
// control mesh's bounding-box diagonal D:
//  1. Reference: the control mesh refined uniformly to level R with every vertex pushed to its
//     limit position (B.2/B.3). Its vertices are exact limit points; its triangles lie within
//     O(h_R²) of the limit surface.
//  2. Test → limit: every test vertex plus one random point per test triangle, exact distance to
//     the reference triangles.
//  3. Limit → test: every reference vertex (an exact limit point), exact distance to the test
//     triangles. This catches coarse triangles that cut through or stand off the surface.
//  4. Max and RMS of each direction and of both together.
// Samples are capped per direction by a deterministic pseudo-random selection (fixed seed), so
// the same inputs always give the same numbers.
#pragma once

#include "loop/bvh.h"
#include "loop/trimesh.h"

#include <cstdint>

namespace limn::loop {

struct MeasureOptions {
    int referenceLevel = 4;
    uint64_t maxSamples = 200000; // per direction
};

struct OneSided {
    double max = 0, rms = 0; // relative to the diagonal
    uint64_t samples = 0;
};

struct Measurement {
    int referenceLevel = 0;
    uint64_t referenceFaces = 0;
    double diagonal = 0;
    OneSided toLimit, fromLimit;
    double max = 0, rms = 0; // both directions together
};

class LimitReference {
public:
    LimitReference(const TriMesh& control, const MeasureOptions& options);
    Measurement measure(const TriMesh& test) const;
    const TriMesh& mesh() const { return mesh_; }

private:
    MeasureOptions options_;
    double diagonal_;
    TriMesh mesh_; // level R, vertices at their limit positions
    TriangleBvh bvh_;
};

// R = levels + 2 (the errors being measured then dominate the reference's by about 4^2), lowered
// while the reference would have more than `faceBudget` triangles; at least 1.
int defaultReferenceLevel(const TriMesh& control, int levels, uint64_t faceBudget = 5000000);

} // namespace limn::loop
