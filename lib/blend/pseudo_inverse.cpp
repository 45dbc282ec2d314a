#include "blend/pseudo_inverse.h"

#include "base/error.h"

#include <algorithm>
#include <cmath>

namespace limn::blend {

// One-sided Jacobi (Hestenes): rotate pairs of columns of B = M·V until all columns are mutually
// orthogonal. Then M = U Σ Vᵀ with σ_j = |b_j|, u_j = b_j/σ_j, and M⁺ = Σ_j v_j b_jᵀ / σ_j².
std::vector<double> pseudoInverse(const std::vector<double>& m, size_t rows, size_t cols,
                                  double rcond) {
    if (m.size() != rows * cols) throwBadInput("pseudoInverse: matrix size mismatch");
    std::vector<double> b = m;                 // rows×cols
    std::vector<double> v(cols * cols, 0.0);   // cols×cols
    for (size_t i = 0; i < cols; ++i) v[i * cols + i] = 1.0;
    auto col = [&](std::vector<double>& a, size_t n, size_t r, size_t c) -> double& {
        return a[r * n + c];
    };
    for (int sweep = 0; sweep < 60; ++sweep) {
        bool rotated = false;
        for (size_t p = 0; p + 1 < cols; ++p)
            for (size_t q = p + 1; q < cols; ++q) {
                double alpha = 0, beta = 0, gamma = 0;
                for (size_t r = 0; r < rows; ++r) {
                    double bp = col(b, cols, r, p), bq = col(b, cols, r, q);
                    alpha += bp * bp;
                    beta += bq * bq;
                    gamma += bp * bq;
                }
                if (gamma == 0 || std::abs(gamma) <= 1e-15 * std::sqrt(alpha * beta)) continue;
                rotated = true;
                double zeta = (beta - alpha) / (2 * gamma);
                double t = std::copysign(1.0, zeta) / (std::abs(zeta) + std::sqrt(1 + zeta * zeta));
                double c = 1 / std::sqrt(1 + t * t), s = c * t;
                for (size_t r = 0; r < rows; ++r) {
                    double bp = col(b, cols, r, p), bq = col(b, cols, r, q);
                    col(b, cols, r, p) = c * bp - s * bq;
                    col(b, cols, r, q) = s * bp + c * bq;
                }
                for (size_t r = 0; r < cols; ++r) {
                    double vp = col(v, cols, r, p), vq = col(v, cols, r, q);
                    col(v, cols, r, p) = c * vp - s * vq;
                    col(v, cols, r, q) = s * vp + c * vq;
                }
            }
        if (!rotated) break;
    }
    std::vector<double> sigma2(cols, 0.0);
    double maxSigma2 = 0;
    for (size_t j = 0; j < cols; ++j) {
        for (size_t r = 0; r < rows; ++r) sigma2[j] += col(b, cols, r, j) * col(b, cols, r, j);
        maxSigma2 = std::max(maxSigma2, sigma2[j]);
    }
    std::vector<double> out(cols * rows, 0.0); // cols×rows
    double cutoff2 = rcond * rcond * maxSigma2;
    for (size_t j = 0; j < cols; ++j) {
        if (sigma2[j] == 0 || sigma2[j] <= cutoff2) continue;
        for (size_t i = 0; i < cols; ++i) {
            double vij = col(v, cols, i, j) / sigma2[j];
            if (vij == 0) continue;
            for (size_t r = 0; r < rows; ++r) out[i * rows + r] += vij * col(b, cols, r, j);
        }
    }
    return out;
}

} // namespace limn::blend
