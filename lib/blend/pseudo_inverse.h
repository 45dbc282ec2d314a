// Moore–Penrose pseudo-inverse of a small dense matrix (math.md A.5: the local-surface fit solves
// its least-squares / minimum-norm problems with the pseudo-inverse, tolerance about 1e-10 as in
// YZ04's code). Matrices here are at most (2k+1)×8, so a one-sided Jacobi SVD is simple and exact
// enough.
#pragma once

#include <cstddef>
#include <vector>

namespace limn::blend {

// `m` is rows×cols, row-major. Returns the cols×rows pseudo-inverse, row-major. Singular values
// below rcond·σ_max are treated as zero (numpy.linalg.pinv's convention).
std::vector<double> pseudoInverse(const std::vector<double>& m, size_t rows, size_t cols,
                                  double rcond = 1e-10);

} // namespace limn::blend
