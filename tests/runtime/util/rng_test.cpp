// The normal generator (util/rng.h) and its polynomial log and sin/cos (util/fast_math.h):
// accuracy against the C library, and the statistics of the normals (moments, the CDF at fixed
// points against Phi, independence of neighbouring slots, of bodies and of steps).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <vector>

#include "util/fast_math.h"
#include "util/rng.h"

namespace lrigid {
namespace {

TEST(FastMath, LogMatchesLibraryOverTheBoxMullerRange) {
  double worst = 0;
  // all magnitudes the generator uses, (a + 1) 2^-32 for a in [0, 2^32), plus a sweep
  for (uint64_t a = 0; a < (uint64_t(1) << 32); a = a * 3 + 1) {
    const double u = (double(a) + 1.0) * 0x1p-32;
    worst =
        std::max(worst, std::abs(log_fast(u) - std::log(u)) / std::max(1.0, std::abs(std::log(u))));
  }
  for (double x = 1e-12; x < 1e12; x *= 1.0137) {
    worst =
        std::max(worst, std::abs(log_fast(x) - std::log(x)) / std::max(1.0, std::abs(std::log(x))));
  }
  EXPECT_LT(worst, 4e-16);
  EXPECT_EQ(log_fast(1.0), 0.0);
}

TEST(FastMath, LogOverEveryExponentAndAtTheMantissaSplit) {
  // every binary exponent of the normal numbers, each on both sides of the point sqrt(1/2) 2^k
  // where the exponent taken out changes, and at 1 and just below 2
  double worst = 0;
  for (int k = -1022; k <= 1023; ++k) {
    const double split = std::ldexp(M_SQRT1_2, k);
    for (double x : {std::nextafter(split, 0.0), split, std::nextafter(split, HUGE_VAL),
                     std::ldexp(1.0, k), std::ldexp(1.999999, k)}) {
      if (!std::isnormal(x)) continue;
      worst = std::max(worst,
                       std::abs(log_fast(x) - std::log(x)) / std::max(1.0, std::abs(std::log(x))));
    }
  }
  EXPECT_LT(worst, 4e-16);
  EXPECT_DOUBLE_EQ(log_fast(DBL_MIN), std::log(DBL_MIN));
}

TEST(FastMath, ExpAndOneMinusExpMatchLibrary) {
  // relative errors of a few ulp over the ranges the batched step uses them on
  double worst_exp = 0, worst_om = 0;
  for (int i = 0; i <= 200000; ++i) {
    const double x = -700.0 + 1400.0 * i / 200000.0;
    worst_exp = std::max(worst_exp, std::abs(exp_fast(x) - std::exp(x)) / std::exp(x));
  }
  for (int i = 0; i <= 200000; ++i) {
    const double y = std::pow(10.0, -14.0 + 16.0 * i / 200000.0);  // 1e-14 .. 100
    const double ref = -std::expm1(-y);
    worst_om = std::max(worst_om, std::abs(one_minus_exp_neg(y) - ref) / ref);
  }
  std::printf("exp_fast: worst relative error %.3g; one_minus_exp_neg: %.3g\n", worst_exp,
              worst_om);
  EXPECT_LT(worst_exp, 1e-15);
  EXPECT_LT(worst_om, 1e-15);
  EXPECT_EQ(exp_fast(0.0), 1.0);
  EXPECT_EQ(exp_fast(-1000.0), exp_fast(-700.0));  // clamped, finite
}

TEST(FastMath, SinCosOfTurnMatchesLibrary) {
  double worst = 0;
  for (uint64_t b = 0; b < (uint64_t(1) << 32); b += 99991) {
    const double phi = 2.0 * M_PI * double(b) * 0x1p-32 - M_PI / 4;
    double c, s;
    sincos_of_turn(uint32_t(b), &c, &s);
    worst = std::max({worst, std::abs(c - std::cos(phi)), std::abs(s - std::sin(phi))});
  }
  EXPECT_LT(worst, 1e-15);
}

TEST(FastMath, SinCosFastMatchesLibrary) {
  // the angles of the euler and rk4 steps' rotations (util/lane.h exp_rotate): half a step's
  // turn, small mostly, up to fast spins over coarse steps; and far out, negative, and zero
  double worst = 0, worst_rel_small = 0;
  for (double x = -1000.0; x <= 1000.0; x += 0.0123) {
    double c, s;
    sincos_fast(x, &c, &s);
    worst = std::max({worst, std::abs(c - std::cos(x)), std::abs(s - std::sin(x))});
  }
  for (double x = 1e-12; x < 1.0; x *= 1.37) {
    double c, s;
    sincos_fast(x, &c, &s);
    worst_rel_small = std::max(worst_rel_small, std::abs(s - std::sin(x)) / std::sin(x));
  }
  EXPECT_LT(worst, 1e-15);
  EXPECT_LT(worst_rel_small, 1e-15);
  double c, s;
  sincos_fast(0.0, &c, &s);
  EXPECT_EQ(c, 1.0);
  EXPECT_EQ(s, 0.0);
}

// standard normal CDF
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

TEST(Philox, LoopFormIsRandom123BitForBit) {
  r123::Philox4x32 gen;
  uint64_t state = 0x9e3779b97f4a7c15ULL;
  auto next = [&state]() {  // splitmix64: counters and keys that cover the 32-bit range
    state += 0x9e3779b97f4a7c15ULL;
    uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  for (int i = 0; i < 100000; ++i) {
    const uint64_t a = next(), b = next(), key = next();
    uint32_t c[4] = {uint32_t(a), uint32_t(a >> 32), uint32_t(b), uint32_t(b >> 32)};
    const r123::Philox4x32::ctr_type ctr = {{c[0], c[1], c[2], c[3]}};
    const r123::Philox4x32::key_type k = {{uint32_t(key), uint32_t(key >> 32)}};
    const auto ref = gen(ctr, k);
    philox4x32_10(c[0], c[1], c[2], c[3], uint32_t(key), uint32_t(key >> 32));
    for (int w = 0; w < 4; ++w) ASSERT_EQ(c[w], ref[w]) << "draw " << i << " word " << w;
  }
}

TEST(NormalStream, MomentsAndCdfOfAMillionDraws) {
  const int bodies = 1 << 17;  // 8 per stream x 2^17 = 1 048 576 draws
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0, lag = 0;
  const double pts[] = {-3, -2, -1, -0.5, 0, 0.5, 1, 2, 3};
  std::vector<double> below(9, 0);
  for (int b = 0; b < bodies; ++b) {
    double z[8];
    NormalStream(2026, uint32_t(b), 17).normals(z);
    for (int i = 0; i < 8; ++i) {
      m1 += z[i], m2 += z[i] * z[i], m3 += z[i] * z[i] * z[i], m4 += z[i] * z[i] * z[i] * z[i];
      if (i > 0) lag += z[i] * z[i - 1];
      for (int k = 0; k < 9; ++k) below[k] += z[i] < pts[k];
    }
  }
  const double n = 8.0 * bodies;
  // standard errors: mean 1/sqrt(n) ~ 1e-3, var sqrt(2/n), skew sqrt(15/n), kurt sqrt(96/n)
  EXPECT_NEAR(m1 / n, 0.0, 5e-3);
  EXPECT_NEAR(m2 / n, 1.0, 7e-3);
  EXPECT_NEAR(m3 / n, 0.0, 2e-2);
  EXPECT_NEAR(m4 / n, 3.0, 5e-2);
  EXPECT_NEAR(lag / (7.0 * bodies), 0.0, 5e-3);
  for (int k = 0; k < 9; ++k) {
    const double p = phi(pts[k]);
    EXPECT_NEAR(below[k] / n, p, 5.0 * std::sqrt(p * (1 - p) / n) + 1e-6) << "at " << pts[k];
  }
}

TEST(NormalStream, StreamsOfNeighbouringBodiesAndStepsAreUncorrelated) {
  double cb = 0, cs = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    double a[4], b[4], c[4];
    NormalStream(5, uint32_t(i), 3).normals(a);
    NormalStream(5, uint32_t(i + 1), 3).normals(b);
    NormalStream(5, uint32_t(i), 4).normals(c);
    cb += a[0] * b[0];
    cs += a[0] * c[0];
  }
  EXPECT_NEAR(cb / n, 0.0, 1e-2);
  EXPECT_NEAR(cs / n, 0.0, 1e-2);
}

TEST(NormalStream, PureFunctionOfSeedBodyStep) {
  double a[12], b[12], c[12];
  NormalStream(9, 4, 11).normals(a);
  NormalStream(9, 4, 11).normals(b);
  NormalStream(10, 4, 11).normals(c);
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(a[i], b[i]);
    EXPECT_NE(a[i], c[i]);
  }
}

}  // namespace
}  // namespace lrigid
