#include "effects/basset.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lrigid {

BassetKernel make_basset_kernel(double coef, double h, int window, double s_max) {
  BassetKernel k;
  k.coef = coef;
  k.window = window;
  for (int m = 1; m <= window; ++m)
    k.window_w.push_back(2.0 * (std::sqrt((m + 1) * h) - std::sqrt(m * h)));
  const double s_min = (window + 1) * h;
  s_max = std::max(s_max, 10.0 * s_min);
  // modes from exp(u_min) = tol sqrt(pi)/2 / sqrt(s_max) to where exp(-s_min e^{2u}) < e^-40
  const double du = kBassetModeStep;
  const double u_min = std::log(kBassetTailTolerance * std::sqrt(M_PI) / 2.0 / std::sqrt(s_max));
  const double u_max = 0.5 * std::log(40.0 / s_min);
  auto add_mode = [&](double lambda, double c) {
    k.lambda.push_back(lambda);
    k.weight.push_back(c);
    k.decay.push_back(std::exp(-lambda * h));
    // an interval of age W+1 (lags [(W+1) h, (W+2) h]) enters the tail
    k.inject.push_back(c * std::exp(-lambda * (window + 1) * h) * -std::expm1(-lambda * h) /
                       lambda);
  };
  // the slowest modes (lambda s_max < kBassetMergeSlow) hardly decay within s_max: they are
  // merged into one with their total weight and mean rate (the error, of order
  // (lambda s_max)^(5/2) / 9 of the kernel at s_max, stays below the truncation's)
  double c_slow = 0, c_lambda_slow = 0;
  for (double u = u_max; u >= u_min; u -= du) {
    const double lambda = std::exp(2.0 * u);
    const double c = 2.0 / std::sqrt(M_PI) * du * std::exp(u);
    if (lambda * s_max < kBassetMergeSlow) {
      c_slow += c;
      c_lambda_slow += c * lambda;
    } else {
      add_mode(lambda, c);
    }
  }
  if (c_slow > 0) add_mode(c_lambda_slow / c_slow, c_slow);
  // padded with modes of weight 0 to a multiple of 4 (the push sums them four at a time)
  while (k.decay.size() % 4 != 0) {
    k.lambda.push_back(1.0);
    k.weight.push_back(0.0);
    k.decay.push_back(0.0);
    k.inject.push_back(0.0);
  }
  k.implicit_mass = 2.0 * coef * std::sqrt(h);
  return k;
}

double basset_tail_kernel(const BassetKernel& k, double s) {
  double sum = 0;
  for (size_t i = 0; i < k.lambda.size(); ++i) sum += k.weight[i] * std::exp(-k.lambda[i] * s);
  return sum;
}

void basset_reset(const BassetKernel& k, const Vec3& g0, double* history) {
  const size_t n = k.stride();
  for (size_t i = 0; i < n; ++i) history[i] = 0;
  for (int a = 0; a < 3; ++a) history[a] = g0[a];
}

namespace {

// Four doubles in one vector register (GCC and Clang vector extension): the push works on
// whole (x, y, z, pad) vectors. Such vectors never cross a function boundary (the helpers are
// always inlined), so the ABI GCC warns about without AVX (-Wpsabi) never applies.
typedef double V4 __attribute__((vector_size(32)));

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
inline __attribute__((always_inline)) V4 load4(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline __attribute__((always_inline)) void store4(double* p, V4 v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace

// GCC builds the push for AVX-512, AVX2 and the baseline and picks the best at load time, as the
// batched steps do (integrate/batch_lanes.h).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void basset_push(const BassetKernel& k, const Vec3& g, double h, double* history) {
  const int W = k.window;
  const int M = static_cast<int>(k.decay.size());  // even (make_basset_kernel)
  double* hist = history;         // g_n, cache
  double* win = history + 8;      // [W] vectors, newest first
  double* modes = win + 4 * W;    // [M] vectors
  const double* decay = k.decay.data();
  const double* inject = k.inject.data();
  const double* ww = k.window_w.data();
  // the oldest windowed interval moves to the tail (zero until the window has filled)
  const V4 leave = load4(win + 4 * (W - 1));
  // the window moves on by one interval; its part of the next step's history integral
  V4 sw = {0, 0, 0, 0};
  for (int m = W - 1; m > 0; --m) {
    const V4 x = load4(win + 4 * (m - 1));
    store4(win + 4 * m, x);
    sw += ww[m] * x;
  }
  const V4 gn = {g[0], g[1], g[2], 0.0};
  const V4 newest = (gn - load4(hist)) * (1.0 / h);
  store4(win, newest);
  store4(hist, gn);
  sw += ww[0] * newest;
  // the tail modes, with two partial sums (independent dependency chains)
  V4 s0 = {0, 0, 0, 0}, s1 = {0, 0, 0, 0};
  for (int i = 0; i < M; i += 2) {
    const V4 m0 = decay[i] * load4(modes + 4 * i) + inject[i] * leave;
    const V4 m1 = decay[i + 1] * load4(modes + 4 * i + 4) + inject[i + 1] * leave;
    store4(modes + 4 * i, m0);
    store4(modes + 4 * i + 4, m1);
    s0 += m0;
    s1 += m1;
  }
  // cache: the history integral at the end of the next step, per unit coefficient
  store4(hist + 4, (s0 + s1) + sw);
  double& count = modes[4 * M];  // intervals in the window
  count = count < W ? count + 1.0 : count;
}
#pragma GCC diagnostic pop

}  // namespace lrigid
