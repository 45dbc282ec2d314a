// OpenSubdiv's face-varying evaluation as the reference for smooth UVs: an adaptive
// patch table with face-varying patches for the mesh's one UV channel (not the legacy linear
// ones), the channel considered in the isolation, Gregory end caps and infinitely sharp
// patches; the UV at (ptex, u, v) is EvaluateBasisFaceVarying over the patch's refined and local
// face-varying values, in double precision.
#pragma once

#include "mesh/mesh.h"
#include "topology/features.h"

#include <glm/vec2.hpp>

#include <memory>

namespace limn::test {

class OsdFaceVarying {
public:
    // `options.fvar` is the face-varying rule.
    OsdFaceVarying(const Mesh& mesh, const SchemeOptions& options, int isolationLevel);
    ~OsdFaceVarying();

    // The UV at (u, v) of ptex face `ptex`, from the patch containing (insideU, insideV).
    // Returns false on holes.
    bool evaluate(int ptex, double u, double v, double insideU, double insideV, glm::dvec2& uv) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace limn::test
