// LU factorization with partial pivoting for the step's small fixed-size systems (3x3, 6x6).
// Eigen's PartialPivLU / LDLT go through its dynamic-size blocked kernels even for a 6x6 matrix
// (about 1,500 instructions to factor, measured with callgrind); these loops have compile-time
// bounds, unroll, and factor a 6x6 in about a fifth of that. The factorization is kept so that
// Newton iterations with an unchanged matrix (simplified Newton) pay only for the solves.
#pragma once
#include <Eigen/Core>
#include <cmath>

namespace lrigid {

template <int N>
class SmallLU {
 public:
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;

  SmallLU() = default;
  explicit SmallLU(const Matrix& a) { factor(a); }

  // false when the matrix is singular (a zero or non-finite pivot)
  bool factor(const Matrix& a) {
    lu_ = a;
    for (int k = 0; k < N; ++k) {
      int p = k;
      double best = std::abs(lu_(k, k));
      for (int i = k + 1; i < N; ++i) {
        const double m = std::abs(lu_(i, k));
        if (m > best) {
          best = m;
          p = i;
        }
      }
      perm_[k] = p;
      if (p != k) lu_.row(k).swap(lu_.row(p));
      if (!(best > 0) || !std::isfinite(best)) return ok_ = false;
      const double inv = 1.0 / lu_(k, k);
      for (int i = k + 1; i < N; ++i) {
        const double l = lu_(i, k) * inv;
        lu_(i, k) = l;
        for (int j = k + 1; j < N; ++j) lu_(i, j) -= l * lu_(k, j);
      }
    }
    return ok_ = true;
  }

  bool ok() const { return ok_; }

  // x with A x = b (A as factored)
  Vector solve(Vector b) const {
    // the row exchanges first (the stored multipliers moved with their rows), then L and U
    for (int k = 0; k < N; ++k)
      if (perm_[k] != k) std::swap(b[k], b[perm_[k]]);
    for (int k = 0; k < N; ++k)
      for (int i = k + 1; i < N; ++i) b[i] -= lu_(i, k) * b[k];
    for (int i = N - 1; i >= 0; --i) {
      double s = b[i];
      for (int j = i + 1; j < N; ++j) s -= lu_(i, j) * b[j];
      b[i] = s / lu_(i, i);
    }
    return b;
  }

 private:
  Matrix lu_ = Matrix::Zero();
  int perm_[N] = {};
  bool ok_ = false;
};

}  // namespace lrigid
