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

// GCC builds the push for AVX-512, AVX2 and the baseline and picks the best at load time, as the
// batched steps do (integrate/batch_lanes.h): with all effects it is a large part of a batched
// body-step.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void basset_push(const BassetKernel& k, const Vec3& g, double h, double* history) {
  const int W = k.window;
  const int M = static_cast<int>(k.decay.size());  // a multiple of 4 (make_basset_kernel)
  double* win = history + 6;    // [W][3], newest first
  double* modes = win + 3 * W;  // [3][M]
  const double* decay = k.decay.data();
  const double* inject = k.inject.data();
  // the oldest windowed interval moves to the tail (zero until the window has filled)
  double leaving[3];
  for (int a = 0; a < 3; ++a) leaving[a] = win[3 * (W - 1) + a];
  std::memmove(win + 3, win, sizeof(double) * 3 * (W - 1));
  for (int a = 0; a < 3; ++a) {
    win[a] = (g[a] - history[a]) / h;
    history[a] = g[a];
  }
  // window part of the next step's history integral: three sums, one per component
  double sw[3] = {0, 0, 0};
  for (int m = 0; m < W; ++m)
    for (int a = 0; a < 3; ++a) sw[a] += k.window_w[m] * win[3 * m + a];
  for (int a = 0; a < 3; ++a) {
    double* ma = modes + a * M;
    const double la = leaving[a];
    // four partial sums: independent chains the compiler can put in one vector
    double s[4] = {0, 0, 0, 0};
    for (int i = 0; i < M; i += 4)
      for (int r = 0; r < 4; ++r) {
        ma[i + r] = decay[i + r] * ma[i + r] + inject[i + r] * la;
        s[r] += ma[i + r];
      }
    // cache: the history integral at the end of the next step, per unit coefficient
    history[3 + a] = ((s[0] + s[1]) + (s[2] + s[3])) + sw[a];
  }
  modes[3 * M] = std::min(modes[3 * M] + 1.0, double(W));  // intervals in the window
}

}  // namespace lrigid
