// lu_factor / lu_solve (util/small_lu.h) against Eigen's full-pivoting LU on the kinds of system
// the step solves: symmetric positive definite matrices (the implicit force step's M + h J + b P)
// and the free Kirchhoff flow's Newton matrices I + h/2 dG/dY; in double and in float.
#include "util/small_lu.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <limits>
#include <random>

namespace lrigid {
namespace {

template <int N, typename T = double>
Eigen::Matrix<double, N, 1> solve(const Eigen::Matrix<double, N, N>& a,
                                  const Eigen::Matrix<double, N, 1>& b, int* ok) {
  T A[N * N], x[N];
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c < N; ++c) A[r * N + c] = T(a(r, c));
    x[r] = T(b[r]);
  }
  *ok = lu_factor<N>(A);
  lu_solve<N>(A, x);
  Eigen::Matrix<double, N, 1> out;
  for (int r = 0; r < N; ++r) out[r] = double(x[r]);
  return out;
}

template <int N>
void expect_solves_like_eigen(const Eigen::Matrix<double, N, N>& a,
                              const Eigen::Matrix<double, N, 1>& b) {
  int ok = 0;
  const Eigen::Matrix<double, N, 1> x = solve<N>(a, b, &ok);
  ASSERT_TRUE(ok);
  const Eigen::Matrix<double, N, 1> ref = a.fullPivLu().solve(b);
  EXPECT_LE((x - ref).norm(), 1e-12 * ref.norm()) << a;
  EXPECT_LE((a * x - b).norm(), 1e-12 * (a.norm() * x.norm() + b.norm()));
  // float: to float's round-off times the condition number (small for these matrices)
  const Eigen::Matrix<double, N, 1> xf = solve<N, float>(a, b, &ok);
  ASSERT_TRUE(ok);
  EXPECT_LE((xf - ref).norm(), 1e-4 * ref.norm());
}

TEST(SmallLU, SolvesSymmetricPositiveDefiniteSystemsOfBothSizes) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix<double, 6, 6> b6;
    Eigen::Matrix<double, 6, 1> r6;
    for (int i = 0; i < 36; ++i) b6.data()[i] = u(gen);
    for (int i = 0; i < 6; ++i) r6[i] = u(gen);
    expect_solves_like_eigen<6>(b6 * b6.transpose() + 0.1 * Eigen::Matrix<double, 6, 6>::Identity(),
                                r6);
    Eigen::Matrix3d b3;
    Eigen::Vector3d r3;
    for (int i = 0; i < 9; ++i) b3.data()[i] = u(gen);
    for (int i = 0; i < 3; ++i) r3[i] = u(gen);
    expect_solves_like_eigen<3>(b3 * b3.transpose() + 0.1 * Eigen::Matrix3d::Identity(), r3);
  }
}

TEST(SmallLU, SolvesNewtonMatricesOfTheFreeFlow) {
  // I + h/2 D with D of size up to 1 (h |dG/dY| <= 2: where the flow's substeps take it)
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix<double, 6, 6> d;
    for (int i = 0; i < 36; ++i) d.data()[i] = u(gen) / 6.0;
    Eigen::Matrix<double, 6, 1> r;
    for (int i = 0; i < 6; ++i) r[i] = u(gen);
    expect_solves_like_eigen<6>(Eigen::Matrix<double, 6, 6>::Identity() + d, r);
  }
}

TEST(SmallLU, SolvesBadlyScaledMassMatrices) {
  // a paper sheet's generalized mass: kg and kg m^2 entries ten orders of magnitude apart
  Eigen::Matrix<double, 6, 1> d;
  d << 1.2e-3, 1.2e-3, 2.3e-3, 1.6e-6, 3.4e-6, 3.4e-6;
  Eigen::Matrix<double, 6, 6> a = d.asDiagonal();
  a(0, 4) = a(4, 0) = 1e-7;
  expect_solves_like_eigen<6>(a, Eigen::Matrix<double, 6, 1>::Ones());
}

TEST(SmallLU, ReportsZeroAndNonFinitePivots) {
  // a zero leading entry (which partial pivoting would exchange) is reported, not divided by:
  // the step then takes substeps, whose matrices are nearer the identity
  Eigen::Matrix3d zero_lead;
  zero_lead << 0, 2, 1, 1, 1, 0, 3, 0, 1;
  int ok = 1;
  solve<3>(zero_lead, Eigen::Vector3d(1, 2, 3), &ok);
  EXPECT_FALSE(ok);
  Eigen::Matrix3d singular;
  singular << 1, 2, 3, 2, 4, 6, 0, 1, 1;
  solve<3>(singular, Eigen::Vector3d(1, 2, 3), &ok);
  EXPECT_FALSE(ok);
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  solve<3>(nan, Eigen::Vector3d(1, 2, 3), &ok);
  EXPECT_FALSE(ok);
}

}  // namespace
}  // namespace lrigid
