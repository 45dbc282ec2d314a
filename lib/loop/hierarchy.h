// Adaptive Loop subdivision on the uniform Loop hierarchy of the control mesh ("exact" positions).
//
// The paper (and math.md B.7) re-applies Loop's masks to the adaptive mesh at every level. After
// the first level that mesh mixes vertices of different levels, and Loop's masks applied to such a
// ring no longer describe the control mesh's limit surface: vertices next to transitions drift off
// it (measured in docs/loop.md). Here every vertex of the result is a vertex of the uniform Loop
// hierarchy U_0 = control, U_1, ..., U_L at its exact position, and every decision is taken on an
// edge of that hierarchy with the paper's metric evaluated there (math.md B.4 with U_{l+1}'s even
// and odd positions, which makes the virtual limit exact). Transition (template) triangles are kept
// for the output only; one that later needs refining is first split 1-to-4 itself — math.md B.6's
// red-green guard — so the mesh stays conforming without ever splitting a template diagonal.
#pragma once

#include "loop/adaptive.h"
#include "loop/level.h"

#include <memory>
#include <vector>

namespace limn::loop {

// U_0..U_levels by refine() with every edge split. Its numbering is what the selection relies on:
// vertex v of U_l is vertex v of U_{l+1}; edge e of U_l becomes vertex V_l + e of U_{l+1};
// triangle f of U_l has children 4f..4f+3: the corners at its vertices 0, 1, 2, then the centre
// (m_01, m_12, m_20). UV indices are kept the same way.
class UniformHierarchy {
public:
    explicit UniformHierarchy(const TriMesh& control, int levels = 0);
    // Adds U_{levels()+1} (and the Level of U_levels()).
    void extend();
    int levels() const { return static_cast<int>(meshes_.size()) - 1; }
    const TriMesh& mesh(int l) const { return *meshes_[l]; }
    const Level& level(int l) const { return *levels_[l]; } // l < levels()

private:
    std::vector<std::unique_ptr<TriMesh>> meshes_;
    std::vector<std::unique_ptr<Level>> levels_;
};

// The adaptive result with exact positions (AdaptiveOptions::positions == Positions::Exact).
AdaptiveResult subdivideOnHierarchy(const TriMesh& control, const AdaptiveOptions& options);

} // namespace limn::loop
