// Elementary functions for the normal generator (util/rng.h) and the batched steps
// (integrate/batch_lanes.h) as straight-line polynomials:
// no table, no library call, no branch, and only integer operations that AVX2 has (no conversion
// between double and int64, no 64-bit arithmetic shift), so a loop over them vectorizes in every
// version of the batched loops, and the results do not depend on the C library. Accurate to a few
// ulp over the ranges they are used on (tested in tests/runtime/util/rng_test.cpp against
// std::log, std::exp, std::sin, std::cos).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

namespace lrigid {

constexpr double kLn2 = 0.6931471805599453094;

// c[0] x^(N-1) + c[1] x^(N-2) + ... + c[N-1] by Horner's rule (N is a constant: unrolled)
template <int N>
inline double horner(double x, const double (&c)[N]) {
  double p = c[0];
  for (int i = 1; i < N; ++i) p = p * x + c[i];
  return p;
}

// ln x for finite x > 0 (normal numbers): x = 2^e m, m in [sqrt(1/2), sqrt(2)),
// ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| < 0.1716, series to s^21 (error < 1e-17)
inline double log_fast(double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  // shift the mantissa range to [sqrt(1/2), sqrt(2)) by biasing before extracting the exponent
  // (e + 1023 by a logical shift, and e as a double through the bits of 2^52 + e + 1023: integer
  // operations that AVX2 has, where an int64 shift or conversion would keep the loops scalar)
  const uint64_t biased = (bits - 0x3fe6a09e667f3bcdULL + 0x3ff0000000000000ULL) >> 52;
  const uint64_t mbits = bits - ((biased - 1023) << 52);
  double m;
  std::memcpy(&m, &mbits, sizeof m);
  const uint64_t ebits = biased | 0x4330000000000000ULL;  // 2^52 + e + 1023
  double eb;
  std::memcpy(&eb, &ebits, sizeof eb);
  const double e = eb - (0x1p52 + 1023.0);
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  constexpr double kAtanh[] = {1.0 / 21, 1.0 / 19, 1.0 / 17, 1.0 / 15, 1.0 / 13, 1.0 / 11,
                               1.0 / 9,  1.0 / 7,  1.0 / 5,  1.0 / 3};
  const double p = horner(s2, kAtanh) * s2;
  return e * kLn2 + (2.0 * s + 2.0 * s * p);
}

// cos and sin of x + quadrant pi/2 for x in [-pi/4, pi/4]: Taylor polynomials to x^15 (sin) and
// x^16 (cos), errors below 1e-16, then the quarter turns
inline void sincos_quadrant(double x, uint32_t quadrant, double* c, double* s) {
  const double x2 = x * x;
  constexpr double kSin[] = {-1.0 / 1307674368000.0, 1.0 / 6227020800.0, -1.0 / 39916800.0,
                             1.0 / 362880.0,          -1.0 / 5040.0,      1.0 / 120.0,
                             -1.0 / 6.0};  // -1/15! ... -1/3!
  const double sp = horner(x2, kSin);
  const double sn = x + x * x2 * sp;
  constexpr double kCos[] = {1.0 / 20922789888000.0, -1.0 / 87178291200.0, 1.0 / 479001600.0,
                             -1.0 / 3628800.0,       1.0 / 40320.0,        -1.0 / 720.0,
                             1.0 / 24.0,             -0.5};  // 1/16! ... -1/2!
  const double cp = horner(x2, kCos);
  const double cs = 1.0 + x2 * cp;
  // rotate by quadrant * pi/2: (c, s) -> (-s, c) per quarter turn
  const bool odd = quadrant & 1u, neg_c = quadrant == 1 || quadrant == 2, neg_s = quadrant >= 2;
  const double cc = odd ? sn : cs, ss = odd ? cs : sn;
  *c = neg_c ? -cc : cc;
  *s = neg_s ? -ss : ss;
}

// cos and sin of the angle 2 pi b / 2^32 - pi/4, uniform over the circle for uniform b:
// the top 2 bits of b pick the quadrant, the low 30 bits an angle x in [-pi/4, pi/4)
inline void sincos_of_turn(uint32_t b, double* c, double* s) {
  const double x = (static_cast<double>(b & 0x3fffffffu) * 0x1p-30 - 0.5) * (M_PI / 2);
  sincos_quadrant(x, b >> 30, c, s);
}

// cos and sin of x for |x| < 2^20 (rad): x = k pi/2 + r, |r| <= pi/4, reduced with pi/2 in two
// parts (Cody and Waite: the first has 33 significant bits, so k times it is exact)
inline void sincos_fast(double x, double* c, double* s) {
  constexpr double kShift = 0x1.8p52;  // adding it rounds to an integer held in the low bits
  const double kd = (x * 0.63661977236758134308 + kShift) - kShift;
  const double r = (x - kd * 1.57079632673412561417) - kd * 6.07710050650619224932e-11;
  // k mod 4 from the low bits of kd + kShift (= 1.5 2^52 + k), not an int64 conversion
  const double kb = kd + kShift;
  uint64_t kbits;
  std::memcpy(&kbits, &kb, sizeof kbits);
  const uint32_t quadrant = static_cast<uint32_t>(kbits & 3);
  sincos_quadrant(r, quadrant, c, s);
}

// e^x for x in [-700, 700] (clamped outside): x = k ln2 + r, |r| <= ln2/2, e^r by its Taylor
// series to r^13 (error < 1e-17), 2^k put into the exponent bits
inline double exp_fast(double x) {
  x = x < -700.0 ? -700.0 : (x > 700.0 ? 700.0 : x);
  constexpr double kShift = 0x1.8p52;  // adding it rounds to an integer held in the low bits
  const double kd = (x * 1.4426950408889634074 + kShift) - kShift;
  const double r = (x - kd * 0.693147180369123816490) - kd * 1.90821492927058770002e-10;
  constexpr double kExp[] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0,
                             1.0 / 3628800.0,    1.0 / 362880.0,    1.0 / 40320.0,
                             1.0 / 5040.0,       1.0 / 720.0,       1.0 / 120.0,
                             1.0 / 24.0,         1.0 / 6.0,         0.5,
                             1.0,                1.0};  // 1/13! ... 1/1!, 1/0!
  const double p = horner(r, kExp);
  // 2^k: k + 1023 (in [13, 2033]) from the low bits of kd + kShift (= 1.5 2^52 + k) shifted into
  // the exponent field (the bits above it leave the word), not an int64 conversion
  const double kb = kd + kShift;
  uint64_t kbits;
  std::memcpy(&kbits, &kb, sizeof kbits);
  const uint64_t scale_bits = (kbits + 1023) << 52;
  double scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return p * scale;
}

// 1 - e^-y for y >= 0 without the cancellation of the difference at small y: its Taylor series
// to y^16 below y = 0.5 (error < 1e-19 y), 1 - exp_fast(-y) above
inline double one_minus_exp_neg(double y) {
  // the series y - y^2/2! + y^3/3! - ... to -y^16/16!, divided by y
  constexpr double kSeries[] = {-1.0 / 20922789888000.0, 1.0 / 1307674368000.0,
                                -1.0 / 87178291200.0,    1.0 / 6227020800.0,
                                -1.0 / 479001600.0,      1.0 / 39916800.0,
                                -1.0 / 3628800.0,        1.0 / 362880.0,
                                -1.0 / 40320.0,          1.0 / 5040.0,
                                -1.0 / 720.0,            1.0 / 120.0,
                                -1.0 / 24.0,             1.0 / 6.0,
                                -0.5,                    1.0};
  const double p = horner(y, kSeries);
  const double series = p * y;
  const double direct = 1.0 - exp_fast(-y);
  return y < 0.5 ? series : direct;
}

// The elementary functions a kernel written once (effects/*.h) calls, chosen by its caller. The
// batched lanes take LaneMath, the straight-line polynomials above: a loop over them vectorizes.
// The scalar step takes ScalarMath, the C library's: on one number at a time a 14-term Horner
// chain is a long run of dependent multiplies and adds, slower than libm's table-driven
// functions (on beads_wind the scalar step spends 7-10 % of its CPU time in them). The two agree to
// a few ulp (tests/runtime/util/rng_test.cpp).
struct LaneMath {
  static double exp(double x) { return exp_fast(x); }
  static double pow(double x, double y) { return exp_fast(y * log_fast(x)); }
  static double one_minus_exp_neg(double y) { return lrigid::one_minus_exp_neg(y); }
  static void sincos(double x, double* c, double* s) { sincos_fast(x, c, s); }
};
struct ScalarMath {
  static double exp(double x) { return std::exp(x); }
  static double pow(double x, double y) { return std::pow(x, y); }
  static double one_minus_exp_neg(double y) { return -std::expm1(-y); }
  static void sincos(double x, double* c, double* s) {
    *c = std::cos(x);
    *s = std::sin(x);
  }
};

}  // namespace lrigid
