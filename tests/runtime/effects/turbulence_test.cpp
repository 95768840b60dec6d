// The Langevin turbulence (effects/turbulence.h, turbulence.cpp): the exact Ornstein-Uhlenbeck
// update's coefficients and limits, Thomson's well-mixed drift, and the statistics of the seen
// fluctuation the update produces over many samples against the OU process's closed forms: the
// stationary variance 2k/3 per component and the autocorrelation exp(-lag / T_L), T_L = 1 / alpha
// (docs/physics/langevin.md); Euler-Maruyama's update (euler, rk4) against its own, biased,
// closed forms.
#include "effects/turbulence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "fluid/turbulence_coefficients.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

TEST(Turbulence, ExactOUStepLimits) {
  const OUStep small = ou_exact(1e-15, 2.0, 0.01);
  EXPECT_NEAR(small.noise_std, 2.0 * std::sqrt(0.01), 1e-12);
  const OUStep big = ou_exact(1e3, 2.0, 1.0);  // alpha h = 1000: stationary in one step
  EXPECT_NEAR(big.decay, 0.0, 1e-300);
  EXPECT_NEAR(big.noise_std, std::sqrt(4.0 / 2e3), 1e-12);
}

TEST(Turbulence, WellMixedDriftVanishesInHomogeneousTurbulence) {
  FluidSample s;
  s.sigma2 = 0.2;
  EXPECT_EQ(well_mixed_drift(Vec3(0.1, 0.2, 0.3), Vec3(1, 2, 3), s).norm(), 0.0);
  s.grad_sigma2 = Vec3(0.1, 0, 0);
  // mean over u' ~ N(0, sigma2) for a tracer (path velocity U + u', U = 0): <a> = 1/2 grad
  // sigma2 + <u u^T> grad sigma2 / (2 sigma2) = grad sigma2
  EXPECT_NEAR(well_mixed_drift(Vec3::Zero(), Vec3::Zero(), s).x(), 0.05, 1e-15);
  const Vec3 u(0.3, -0.1, 0.2);
  EXPECT_NEAR(well_mixed_drift(u, u, s).x(), 0.05 + 0.3 * 0.3 * 0.1 / 0.4, 1e-15);
}

TEST(Turbulence, WellMixedDriftFollowsThePathNotTheFluctuation) {
  // a body at rest in a gradient: u' is rescaled only as fast as the body moves through sigma,
  // so the drift does not grow with u' (Thomson's u' + U would give u'^2 growth)
  FluidSample s;
  s.sigma2 = 0.2;
  s.grad_sigma2 = Vec3(0, 0, 0.4);
  const Vec3 big(0, 0, 10.0);
  EXPECT_NEAR(well_mixed_drift(big, Vec3::Zero(), s).z(), 0.2, 1e-15);
  const Vec3 v(0, 0, 0.5);
  EXPECT_NEAR(well_mixed_drift(big, v, s).z(), 0.2 + 10.0 * 0.5 * 0.4 / 0.4, 1e-13);
}

TEST(Turbulence, OrnsteinUhlenbeckCoefficientsAreExact) {
  // independent of the kernel: exp and expm1 of the C library
  for (double alpha : {0.0, 1e-14, 1e-3, 0.7, 40.0, 2e3}) {
    for (double h : {1e-4, 1e-2}) {
      const double beta = 0.8;
      double decay, noise;
      ou_exact_kernel(alpha, beta, h, &decay, &noise);
      const double ah = alpha * h;
      const double ref_noise =
          ah > 1e-12 ? beta * std::sqrt(-std::expm1(-2 * ah) / (2 * alpha)) : beta * std::sqrt(h);
      EXPECT_NEAR(decay, std::exp(-ah), 1e-15) << alpha << " " << h;
      EXPECT_NEAR(noise, ref_noise, 1e-14 * ref_noise) << alpha << " " << h;
    }
  }
}

TEST(Turbulence, OrnsteinUhlenbeckUpdateHasThomsonsDrift) {
  // the update against decay u + h a + noise z with a from well_mixed_drift (the scalar
  // step's reference form), and in float against double
  FluidSample s;
  s.sigma2 = 0.3;
  s.grad_sigma2 = Vec3(0.02, -0.05, 0.11);
  const Vec3 V(1.0, -0.4, 0.2), u0(0.3, -0.1, 0.25);
  const double z[3] = {0.5, -1.2, 0.8}, h = 5e-3, decay = 0.97, noise = 0.04;
  const Vec3 ref = decay * u0 + h * well_mixed_drift(u0, V, s) + noise * Vec3(z[0], z[1], z[2]);
  Vec3 u = u0;
  ou_update(1.0, decay, noise, s.sigma2, V.data(), s.grad_sigma2.data(), z, h, u.data());
  float uf[3] = {float(u0[0]), float(u0[1]), float(u0[2])};
  const float Vf[3] = {1.0f, -0.4f, 0.2f}, gf[3] = {0.02f, -0.05f, 0.11f};
  const float zf[3] = {0.5f, -1.2f, 0.8f};
  ou_update(1.0f, float(decay), float(noise), 0.3f, Vf, gf, zf, float(h), uf);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(u[a], ref[a], 1e-15);
    EXPECT_NEAR(uf[a], ref[a], 1e-6);
  }
  // without the drift, and where sigma2 = 0 (no drift whatever wm says)
  Vec3 u_off = u0, u_zero = u0;
  ou_update(0.0, decay, noise, s.sigma2, V.data(), s.grad_sigma2.data(), z, h, u_off.data());
  ou_update(1.0, decay, noise, 0.0, V.data(), s.grad_sigma2.data(), z, h, u_zero.data());
  const Vec3 plain = decay * u0 + noise * Vec3(z[0], z[1], z[2]);
  EXPECT_TRUE(test::near(u_off, plain, 1e-15));
  EXPECT_TRUE(test::near(u_zero, plain, 1e-15));
}

// Moments of the seen fluctuation over `chains` independent OU paths of three components each,
// updated by ou_update (homogeneous turbulence: no drift) with the coefficients decay and noise:
// after `burn` updates from u' = 0 (u0), one update later (u1) and `lag` updates later (ul).
struct OuMoments {
  // means over the samples, and the standard errors of those means
  double mean = 0, var = 0, c1 = 0, cl = 0;
  double se_mean = 0, se_var = 0, se_c1 = 0, se_cl = 0;
};

OuMoments ou_moments(double decay, double noise, double h, int chains, int burn, int lag) {
  std::mt19937_64 g(12345);
  std::normal_distribution<double> normal(0, 1);
  const double zero[3] = {0, 0, 0};
  auto update = [&](double* u) {
    const double z[3] = {normal(g), normal(g), normal(g)};
    ou_update(0.0, decay, noise, 0.0, zero, zero, z, h, u);
  };
  // sums of x and x^2 for u0, u0^2, u0 u1, u0 ul
  double s[4] = {0, 0, 0, 0}, s2[4] = {0, 0, 0, 0};
  for (int c = 0; c < chains; ++c) {
    double u[3] = {0, 0, 0};
    for (int k = 0; k < burn; ++k) update(u);
    const double u0[3] = {u[0], u[1], u[2]};
    update(u);
    const double u1[3] = {u[0], u[1], u[2]};
    for (int k = 1; k < lag; ++k) update(u);
    for (int a = 0; a < 3; ++a) {
      const double x[4] = {u0[a], u0[a] * u0[a], u0[a] * u1[a], u0[a] * u[a]};
      for (int m = 0; m < 4; ++m) s[m] += x[m], s2[m] += x[m] * x[m];
    }
  }
  const double n = 3.0 * chains;
  double mean[4], se[4];
  for (int m = 0; m < 4; ++m) {
    mean[m] = s[m] / n;
    se[m] = std::sqrt((s2[m] / n - mean[m] * mean[m]) / n);
  }
  return {mean[0], mean[1], mean[2], mean[3], se[0], se[1], se[2], se[3]};
}

// The exact update from u' = 0, in homogeneous turbulence of k = 0.06 m^2/s^2 and eps =
// 0.05 m^2/s^3 (the coefficients of the "stationary" drift), over 20 000 paths: after 12 T_L its
// variance per component is 2k/3 = 0.04 m^2/s^2, its mean 0, and its autocorrelation over a step
// of h = 0.3 T_L and over 4 steps exp(-0.3) and exp(-1.2), each within 3 standard errors of the
// samples; the update is exact at any step, so a step of 2 T_L keeps the variance as well
TEST(Turbulence, ExactUpdateHasTheStationaryVarianceAndTheAutocorrelationOfTheOuProcess) {
  const double k = 0.06, eps = 0.05, nu = 1.5e-5;
  const LangevinCoefficients lc = langevin_coefficients(k, eps, nu, Drift::Stationary);
  ASSERT_LT(lc.alpha, std::sqrt(eps / nu));  // the Kolmogorov cap does not act
  const double T_L = 1.0 / lc.alpha, sigma2 = 2.0 * k / 3.0;
  for (const double step : {0.3, 2.0}) {
    const double h = step * T_L;
    const OUStep ou = ou_exact(lc.alpha, lc.beta, h);
    const int lag = 4, burn = int(std::ceil(12.0 / step));
    const OuMoments m = ou_moments(ou.decay, ou.noise_std, h, 20000, burn, lag);
    std::printf(
        "exact update, h = %.1f T_L: <u'^2> = %.5f (2k/3 = %.5f), rho(h) = %.4f (%.4f), "
        "rho(%d h) = %.4f (%.4f)\n",
        step, m.var, sigma2, m.c1 / sigma2, std::exp(-step), lag, m.cl / sigma2,
        std::exp(-lag * step));
    EXPECT_NEAR(m.mean, 0.0, 3 * m.se_mean) << step;
    EXPECT_NEAR(m.var, sigma2, 3 * m.se_var) << step;
    EXPECT_NEAR(m.c1, sigma2 * std::exp(-h / T_L), 3 * m.se_c1) << step;
    EXPECT_NEAR(m.cl, sigma2 * std::exp(-lag * h / T_L), 3 * m.se_cl) << step;
    // the test can tell: 3 standard errors are a few per cent of what is compared
    EXPECT_LT(3 * m.se_var, 0.03 * sigma2);
    EXPECT_LT(3 * m.se_c1, 0.03 * sigma2);
  }
}

// Euler-Maruyama's update u <- (1 - alpha h) u + beta sqrt(h) z (the euler and rk4 steps) is an
// AR(1) process too, but not the OU process's: its stationary variance is
// beta^2 h / (1 - (1 - alpha h)^2) = 2k/3 / (1 - alpha h / 2), its correlation over a step
// 1 - alpha h. At h = T_L / 2: 4/3 of 2k/3 and 0.5 (the exact update: 2k/3 and exp(-0.5))
TEST(Turbulence, EulerMaruyamaUpdateHasItsOwnBiasedVariance) {
  const double k = 0.06, eps = 0.05, nu = 1.5e-5;
  const LangevinCoefficients lc = langevin_coefficients(k, eps, nu, Drift::Stationary);
  const double h = 0.5 / lc.alpha, sigma2 = 2.0 * k / 3.0;
  double decay, noise;
  ou_euler_kernel(lc.alpha, lc.beta, h, &decay, &noise);
  EXPECT_NEAR(decay, 0.5, 1e-15);
  const OuMoments m = ou_moments(decay, noise, h, 20000, 60, 2);
  const double var = sigma2 / (1 - 0.25);
  std::printf("Euler-Maruyama, h = 0.5 T_L: <u'^2> = %.5f (%.5f), rho(h) = %.4f (0.5)\n", m.var,
              var, m.c1 / var);
  EXPECT_NEAR(m.mean, 0.0, 3 * m.se_mean);
  EXPECT_NEAR(m.var, var, 3 * m.se_var);
  EXPECT_NEAR(m.c1, var * 0.5, 3 * m.se_c1);
  EXPECT_NEAR(m.cl, var * 0.25, 3 * m.se_cl);
  EXPECT_GT(m.var - sigma2, 10 * m.se_var);  // distinguishable from the exact update's
}

// Csanady's factors (effects/turbulence.h crossing_factors): b = sqrt(1 + beta^2 vd^2 / sigma2)
// along the drift, b' = sqrt(1 + 4 beta^2 vd^2 / sigma2) across it, beta = 0.8; exactly 1 for a
// tracer and where there is no turbulence
TEST(CrossingTrajectories, FactorsAreCsanadys) {
  double along, across;
  crossing_factors(0.0, 0.04, &along, &across);
  EXPECT_EQ(along, 1.0);
  EXPECT_EQ(across, 1.0);
  crossing_factors(0.09, 0.0, &along, &across);
  EXPECT_EQ(along, 1.0);
  EXPECT_EQ(across, 1.0);
  crossing_factors(0.09, 0.04, &along, &across);  // vd / u' = 1.5
  EXPECT_NEAR(along, std::sqrt(1 + 0.64 * 2.25), 1e-15);
  EXPECT_NEAR(across, std::sqrt(1 + 4 * 0.64 * 2.25), 1e-15);
  // the exact coefficients are the OU process's on alpha b and beta sqrt(b): the variance
  // beta^2 / (2 alpha) is the same on both axes
  const double alpha = 3.0, beta = 0.6, h = 0.01;
  double d, n, da, na;
  ou_crossing_exact_kernel<ScalarMath>(alpha, beta, 0.04, 0.09, h, &d, &n, &da, &na);
  EXPECT_NEAR(d, std::exp(-alpha * across * h), 1e-15);
  EXPECT_NEAR(da, std::exp(-alpha * along * h), 1e-15);
  EXPECT_NEAR(n * n / (1 - d * d), beta * beta / (2 * alpha), 1e-12);
  EXPECT_NEAR(na * na / (1 - da * da), beta * beta / (2 * alpha), 1e-12);
  // without a drift: ou_exact's pair on both axes, to the bit
  ou_crossing_exact_kernel<ScalarMath>(alpha, beta, 0.04, 0.0, h, &d, &n, &da, &na);
  const OUStep ou = ou_exact(alpha, beta, h);
  EXPECT_EQ(d, ou.decay);
  EXPECT_EQ(n, ou.noise_std);
  EXPECT_EQ(da, ou.decay);
  EXPECT_EQ(na, ou.noise_std);
}

// Euler-Maruyama's pair with the factors: 1 - alpha b h and beta sqrt(b h), each factor capped
// so the decay stays >= 0 where the tracer's is (alpha h <= 1), and never below the tracer's
TEST(CrossingTrajectories, EulerFactorsKeepTheDecayNonNegative) {
  const double alpha = 2.0, beta = 0.5, sigma2 = 0.01, vd2 = 1.0;  // vd / u' = 10
  double along, across;
  crossing_factors(vd2, sigma2, &along, &across);
  for (const double h : {1e-3, 0.05, 0.4, 0.5}) {  // alpha h <= 1
    double d, n, da, na;
    ou_crossing_euler_kernel(alpha, beta, sigma2, vd2, h, &d, &n, &da, &na);
    const double cap = 1 / (alpha * h);
    const double b = std::min(across, cap), ba = std::min(along, cap);
    EXPECT_NEAR(d, 1 - alpha * b * h, 1e-15) << h;
    EXPECT_NEAR(da, 1 - alpha * ba * h, 1e-15) << h;
    EXPECT_NEAR(n, beta * std::sqrt(b * h), 1e-15) << h;
    EXPECT_NEAR(na, beta * std::sqrt(ba * h), 1e-15) << h;
    EXPECT_GE(d, 0.0);
    EXPECT_GE(da, 0.0);
  }
  // alpha h > 1: the tracer's own pair (the step is already coarser than T_L)
  double d, n, da, na, dt, nt;
  ou_crossing_euler_kernel(alpha, beta, sigma2, vd2, 0.75, &d, &n, &da, &na);
  ou_euler_kernel(alpha, beta, 0.75, &dt, &nt);
  EXPECT_EQ(d, dt);
  EXPECT_EQ(da, dt);
  EXPECT_EQ(n, nt);
}

// ou_update_crossing without a drift is ou_update to the bit (a tracer's path does not change);
// with one, the component along the drift takes the along pair and the others the across pair
TEST(CrossingTrajectories, UpdateActsOnTheAxesOfTheDrift) {
  std::mt19937_64 g(7);
  std::normal_distribution<double> normal(0, 1);
  const double V[3] = {0.3, -0.2, 0.1}, gs[3] = {0.01, 0.02, -0.03}, h = 1e-3;
  const double zero[3] = {0, 0, 0};
  for (int trial = 0; trial < 200; ++trial) {
    const double z[3] = {normal(g), normal(g), normal(g)};
    const double u0[3] = {normal(g), normal(g), normal(g)};
    double a[3] = {u0[0], u0[1], u0[2]}, b[3] = {u0[0], u0[1], u0[2]};
    ou_update(1.0, 0.97, 0.05, 0.2, V, gs, z, h, a);
    ou_update_crossing(1.0, 0.97, 0.05, 0.97, 0.05, zero, 0.2, V, gs, z, h, b);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]);
    // a drift along (0, 0.6, 0.8): that component decays by 0.9 with noise 0.07, the rest as
    // ou_update (no well-mixed drift here, to compare with the closed form)
    const Vec3 d(0, 0.6, 0.8), u(u0[0], u0[1], u0[2]), zv(z[0], z[1], z[2]);
    double w[3] = {u0[0], u0[1], u0[2]};
    ou_update_crossing(0.0, 0.97, 0.05, 0.9, 0.07, d.data(), 0.2, V, gs, z, h, w);
    const Vec3 ref = 0.97 * (u - u.dot(d) * d) + 0.05 * (zv - zv.dot(d) * d) +
                     (0.9 * u.dot(d) + 0.07 * zv.dot(d)) * d;
    EXPECT_TRUE(test::near(Vec3(w[0], w[1], w[2]), ref, 1e-14));
  }
}

// The update's statistics with a drift along an oblique axis d, over 20 000 paths: the variance
// along and across d stays sigma2 = beta^2 / (2 alpha), and the autocorrelation over 4 steps is
// exp(-4 alpha b h) along d and exp(-4 alpha b' h) across it, within 3 standard errors
TEST(CrossingTrajectories, EachAxisIsAnOuProcessOfItsOwnTimeScaleAndTheSameVariance) {
  const double alpha = 2.0, beta = 0.4, sigma2 = beta * beta / (2 * alpha), h = 0.05;
  const double vd2 = 2.25 * sigma2;  // vd / u' = 1.5
  double bl, bc;
  crossing_factors(vd2, sigma2, &bl, &bc);
  double dc, nc, da, na;
  ou_crossing_exact_kernel<ScalarMath>(alpha, beta, sigma2, vd2, h, &dc, &nc, &da, &na);
  const Vec3 d = Vec3(1, 2, 2) / 3.0, e = Vec3(2, -1, 0) / std::sqrt(5.0);  // e across d
  std::mt19937_64 g(99);
  std::normal_distribution<double> normal(0, 1);
  const double zero[3] = {0, 0, 0};
  const int chains = 20000, burn = 60, lag = 4;
  // per axis (0 along d, 1 across): sums of u0^2, u0 ul and of their squares
  double s[2][2] = {{0, 0}, {0, 0}}, s2[2][2] = {{0, 0}, {0, 0}};
  for (int c = 0; c < chains; ++c) {
    double u[3] = {0, 0, 0};
    auto step = [&] {
      const double z[3] = {normal(g), normal(g), normal(g)};
      ou_update_crossing(0.0, dc, nc, da, na, d.data(), sigma2, zero, zero, z, h, u);
    };
    for (int k = 0; k < burn; ++k) step();
    const Vec3 u0(u[0], u[1], u[2]);
    for (int k = 0; k < lag; ++k) step();
    const Vec3 ul(u[0], u[1], u[2]);
    const Vec3 ax[2] = {d, e};
    for (int a = 0; a < 2; ++a) {
      const double x0 = u0.dot(ax[a]), xl = ul.dot(ax[a]);
      const double x[2] = {x0 * x0, x0 * xl};
      for (int m = 0; m < 2; ++m) s[a][m] += x[m], s2[a][m] += x[m] * x[m];
    }
  }
  const double rho[2] = {std::exp(-lag * alpha * bl * h), std::exp(-lag * alpha * bc * h)};
  for (int a = 0; a < 2; ++a) {
    double mean[2], se[2];
    for (int m = 0; m < 2; ++m) {
      mean[m] = s[a][m] / chains;
      se[m] = std::sqrt((s2[a][m] / chains - mean[m] * mean[m]) / chains);
    }
    std::printf("%s the drift: <u'^2> = %.5f (%.5f), rho(4 h) = %.4f (%.4f)\n",
                a == 0 ? "along" : "across", mean[0], sigma2, mean[1] / sigma2, rho[a]);
    EXPECT_NEAR(mean[0], sigma2, 3 * se[0]) << a;
    EXPECT_NEAR(mean[1], sigma2 * rho[a], 3 * se[1]) << a;
  }
  // the test tells the axes apart (and from a tracer's exp(-4 alpha h) = 0.67)
  EXPECT_GT(rho[0] - rho[1], 0.1);
  EXPECT_GT(std::exp(-lag * alpha * h) - rho[0], 0.1);
}

}  // namespace
}  // namespace lrigid
