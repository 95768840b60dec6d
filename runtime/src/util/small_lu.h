// LU factorization of the step's small fixed-size systems (6 x 6 and 3 x 3), written once for
// the scalar step (T = double) and the batched steps' loops across bodies (double or float):
// compile-time bounds that unroll, no branches, no pivoting. Every matrix the step factors has a
// safe diagonal: the free Kirchhoff flow's Newton matrix I + h/2 dG/dY is the identity plus a
// perturbation that the substeps make small (integrate/dynamics.cpp falls back to them when a
// pivot fails), and the implicit force step's M + h J + b P is symmetric positive definite, for
// which elimination without pivoting is stable (Golub & Van Loan, Matrix Computations, 4th ed.,
// section 4.2). Eigen's PartialPivLU goes through its dynamic-size blocked kernels even for a 6 x 6
// (about 1,500 instructions to factor, measured with callgrind), about five times these loops. The
// factorization is kept so that Newton iterations with an unchanged matrix (simplified Newton)
// pay only for the solves.
#pragma once
#include <cmath>

#include "util/lane.h"

namespace lrigid {

// The LU factors of the N x N row-major A, in place (unit lower triangle below the diagonal,
// U above it, and on the diagonal U's reciprocal pivots: the solves multiply, so a factorization
// kept for several right-hand sides pays its N divisions once). 0 when a pivot is zero or not
// finite (the factors are then meaningless).
template <int N, typename T>
LRIGID_LANE int lu_factor(T* A) {
  int ok = 1;
#pragma GCC unroll 6
  for (int p = 0; p < N; ++p) {
    const T piv = A[p * N + p];
    ok &= int(piv != T(0)) & int(std::isfinite(piv));
    const T inv = T(1) / (piv != T(0) ? piv : T(1));
    A[p * N + p] = inv;
#pragma GCC unroll 6
    for (int i = p + 1; i < N; ++i) {
      const T l = A[i * N + p] * inv;
      A[i * N + p] = l;
#pragma GCC unroll 6
      for (int j = p + 1; j < N; ++j) A[i * N + j] -= l * A[p * N + j];
    }
  }
  return ok;
}

// b <- A^-1 b for A factored by lu_factor
template <int N, typename T>
LRIGID_LANE void lu_solve(const T* A, T* b) {
#pragma GCC unroll 6
  for (int p = 0; p < N; ++p)
#pragma GCC unroll 6
    for (int i = p + 1; i < N; ++i) b[i] -= A[i * N + p] * b[p];
#pragma GCC unroll 6
  for (int i = N - 1; i >= 0; --i) {
    T s = b[i];
#pragma GCC unroll 6
    for (int j = i + 1; j < N; ++j) s -= A[i * N + j] * b[j];
    b[i] = s * A[i * N + i];
  }
}

}  // namespace lrigid
