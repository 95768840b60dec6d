#include "fluid/turbulence_coefficients.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lrigid {
namespace {

// worked values of physics-notes §1 (nu = 1.5e-5 m^2/s)
TEST(TurbulenceCoefficients, TaylorReynoldsAndC0MatchWorkedValues) {
  const double nu = 1.5e-5;
  EXPECT_NEAR(taylor_reynolds(1, 1, nu), 667, 1);
  EXPECT_NEAR(c0_of_reynolds(taylor_reynolds(1, 1, nu)), 6.35, 1e-2);
  EXPECT_NEAR(taylor_reynolds(0.01, 0.01, nu), 66.7, 0.1);
  EXPECT_NEAR(c0_of_reynolds(taylor_reynolds(0.01, 0.01, nu)), 4.28, 1e-2);
  EXPECT_NEAR(c0_of_reynolds(taylor_reynolds(1e-4, 1e-2, nu)), 0.03, 5e-3);
}

TEST(TurbulenceCoefficients, StationaryDriftReproducesTwoThirdsK) {
  const double k = 0.3, eps = 0.05, nu = 1e-6;
  const LangevinCoefficients c = langevin_coefficients(k, eps, nu, Drift::Stationary);
  EXPECT_NEAR(c.sigma2, 2.0 * k / 3.0, 1e-12);
  EXPECT_NEAR(c.alpha, 0.75 * c.c0 * eps / k, 1e-12);
  EXPECT_NEAR(c.beta, std::sqrt(c.c0 * eps), 1e-12);
}

TEST(TurbulenceCoefficients, OriginalDriftGivesPopeSLMVariance) {
  // <u_i^2> = C0 k / (1 + 3/2 C0), below 2k/3 (decaying-turbulence model in a frozen field)
  const double k = 0.3, eps = 0.05, nu = 1e-6;
  const LangevinCoefficients c = langevin_coefficients(k, eps, nu, Drift::Original);
  EXPECT_NEAR(c.sigma2, c.c0 * k / (1 + 1.5 * c.c0), 1e-12);
  EXPECT_LT(c.sigma2, 2.0 * k / 3.0);
}

TEST(TurbulenceCoefficients, FiniteWhereKVanishes) {
  for (double k : {0.0, 1e-30, 1e-12}) {
    for (double eps : {0.0, 1e-30, 1.0}) {
      const LangevinCoefficients c = langevin_coefficients(k, eps, 1e-6, Drift::Stationary);
      EXPECT_TRUE(std::isfinite(c.alpha) && std::isfinite(c.beta) && std::isfinite(c.sigma2));
      EXPECT_GE(c.c0, 1.0);  // clamped
      // the rate never exceeds the Kolmogorov frequency sqrt(eps/nu)
      EXPECT_LE(c.alpha, std::sqrt(std::max(eps, 1e-12) / 1e-6) * (1 + 1e-12));
    }
  }
}

TEST(TurbulenceCoefficients, CapKeepsVarianceBoundedByK) {
  // tiny k, large eps: alpha is capped, sigma2 keeps its uncapped value C0 k/(2 factor)
  const double k = 1e-6, eps = 1.0, nu = 1e-6;
  const LangevinCoefficients c = langevin_coefficients(k, eps, nu, Drift::Stationary);
  EXPECT_NEAR(c.alpha, std::sqrt(eps / nu), 1e-9);
  EXPECT_NEAR(c.sigma2, 2.0 * k / 3.0, 1e-15);
  EXPECT_NEAR(c.beta * c.beta / (2 * c.alpha), c.sigma2, 1e-15);
}

}  // namespace
}  // namespace lrigid
