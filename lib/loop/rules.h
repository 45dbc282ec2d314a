// Loop's refinement rules and limit masks (math.md B.1–B.3; paper 004 eq. (1) and the ω(k)
// limit; Hoppe et al. 1994). Every function computes one value per vertex or per edge of a level.
#pragma once

#include "loop/level.h"

#include <glm/vec3.hpp>

#include <vector>

namespace limn::loop {

// α(k) = 5/8 − (3 + 2cos(2π/k))²/64: the total weight of the k neighbours in the even rule
// (math.md B.1; the paper's a(k) = k(1−α)/α gives the same mask).
double loopAlpha(int k);
// ω(k) = 3k / (8 α(k)): the centre weight of the limit mask (ω v + Σ v_i)/(ω + k) (math.md B.2).
double limitOmega(int k);

// Even (vertex) positions of every vertex: smooth (1−α)v + α/k Σ v_i, crease (a + 6v + b)/8,
// corner v (math.md B.1, B.3).
std::vector<glm::dvec3> evenPositions(const Level& level);

// Odd (edge) positions of every edge, by topology edge index: smooth 3/8 (a+b) + 1/8 (c+d),
// sharp (boundary or crease) (a+b)/2 (math.md B.1, B.3).
std::vector<glm::dvec3> oddPositions(const Level& level);

// Limit positions of every vertex: smooth (ω v + Σ v_i)/(ω + k) (E5), crease (a + 4v + b)/6,
// corner v (math.md B.2, B.3). A dart (one sharp edge) uses the smooth mask, as OpenSubdiv does.
std::vector<glm::dvec3> limitPositions(const Level& level);

} // namespace limn::loop
