#include "effects/basset.h"

#include <cmath>

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
  for (double u = u_max; u >= u_min; u -= du) {
    const double lambda = std::exp(2.0 * u);
    const double c = 2.0 / std::sqrt(M_PI) * du * std::exp(u);
    k.lambda.push_back(lambda);
    k.weight.push_back(c);
    k.decay.push_back(std::exp(-lambda * h));
    // an interval of age W+1 (lags [(W+1) h, (W+2) h]) enters the tail
    k.inject.push_back(c * std::exp(-lambda * (window + 1) * h) * -std::expm1(-lambda * h) /
                       lambda);
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

void basset_push(const BassetKernel& k, const Vec3& g, double h, double* history) {
  const int W = k.window;
  const size_t M = k.decay.size();
  double* win = history + 6;
  double* modes = win + 3 * W;
  double& count = modes[3 * M];
  // the oldest windowed interval moves to the tail
  double leaving[3] = {0, 0, 0};
  if (count >= W)
    for (int a = 0; a < 3; ++a) leaving[a] = win[3 * (W - 1) + a];
  for (size_t i = 0; i < M; ++i)
    for (int a = 0; a < 3; ++a)
      modes[3 * i + a] = k.decay[i] * modes[3 * i + a] + k.inject[i] * leaving[a];
  for (int m = W - 1; m > 0; --m)
    for (int a = 0; a < 3; ++a) win[3 * m + a] = win[3 * (m - 1) + a];
  for (int a = 0; a < 3; ++a) {
    win[a] = (g[a] - history[a]) / h;
    history[a] = g[a];
  }
  if (count < W) count += 1;
  // cache: history integral at the end of the next step, per unit coefficient
  for (int a = 0; a < 3; ++a) {
    double s = 0;
    for (int m = 0; m < W; ++m) s += k.window_w[m] * win[3 * m + a];
    for (size_t i = 0; i < M; ++i) s += modes[3 * i + a];
    history[3 + a] = s;
  }
}

}  // namespace lrigid
