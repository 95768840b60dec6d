// SmallLU (util/small_lu.h) against Eigen's full-pivoting LU on the systems the step solves.
#include "util/small_lu.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

namespace lrigid {
namespace {

template <int N>
void expect_solves_like_eigen(const Eigen::Matrix<double, N, N>& a,
                              const Eigen::Matrix<double, N, 1>& b) {
  const SmallLU<N> lu(a);
  ASSERT_TRUE(lu.ok());
  const Eigen::Matrix<double, N, 1> x = lu.solve(b);
  const Eigen::Matrix<double, N, 1> ref = a.fullPivLu().solve(b);
  EXPECT_LE((x - ref).norm(), 1e-12 * ref.norm()) << a;
  EXPECT_LE((a * x - b).norm(), 1e-12 * (a.norm() * x.norm() + b.norm()));
}

TEST(SmallLU, SolvesRandomSystemsOfBothSizes) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix<double, 6, 6> a6;
    Eigen::Matrix<double, 6, 1> b6;
    for (int i = 0; i < 36; ++i) a6.data()[i] = u(gen);
    for (int i = 0; i < 6; ++i) b6[i] = u(gen);
    expect_solves_like_eigen<6>(a6, b6);
    Eigen::Matrix3d a3;
    Eigen::Vector3d b3;
    for (int i = 0; i < 9; ++i) a3.data()[i] = u(gen);
    for (int i = 0; i < 3; ++i) b3[i] = u(gen);
    expect_solves_like_eigen<3>(a3, b3);
  }
}

TEST(SmallLU, PivotsWhenTheLeadingEntryIsZero) {
  // without row exchanges the first pivot is 0: only partial pivoting solves this
  Eigen::Matrix3d a;
  a << 0, 2, 1, 1, 1, 0, 3, 0, 1;
  expect_solves_like_eigen<3>(a, Eigen::Vector3d(1, 2, 3));
}

TEST(SmallLU, SolvesBadlyScaledMassMatrices) {
  // a paper sheet's generalized mass: kg and kg m^2 entries ten orders of magnitude apart
  Eigen::Matrix<double, 6, 1> d;
  d << 1.2e-3, 1.2e-3, 2.3e-3, 1.6e-6, 3.4e-6, 3.4e-6;
  Eigen::Matrix<double, 6, 6> a = d.asDiagonal();
  a(0, 4) = a(4, 0) = 1e-7;
  expect_solves_like_eigen<6>(a, Eigen::Matrix<double, 6, 1>::Ones());
}

TEST(SmallLU, ReportsSingularAndNonFiniteMatrices) {
  Eigen::Matrix3d singular;
  singular << 1, 2, 3, 2, 4, 6, 0, 1, 1;
  EXPECT_FALSE(SmallLU<3>(singular).ok());
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(SmallLU<3>(nan).ok());
}

}  // namespace
}  // namespace lrigid
