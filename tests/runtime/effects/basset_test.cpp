// The Basset kernel: exponential-sum tail against s^-1/2, and the window + tail history
// integral against a direct full-history quadrature of the same piecewise-constant derivative.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "effects/basset.h"

namespace lrigid {
namespace {

TEST(Basset, ExponentialSumMatchesInverseSquareRootOverTheTail) {
  const double h = 1e-3, s_max = 20;
  const BassetKernel k = make_basset_kernel(1.0, h, kBassetWindow, s_max);
  double worst = 0;
  for (double s = (kBassetWindow + 1) * h; s <= s_max; s *= 1.01)
    worst = std::max(worst, std::abs(basset_tail_kernel(k, s) * std::sqrt(s) - 1.0));
  EXPECT_LT(worst, 2e-3) << k.lambda.size() << " modes";
  EXPECT_LT(k.lambda.size(), 40u);
  RecordProperty("modes", int(k.lambda.size()));
  RecordProperty("max_relative_error", std::to_string(worst));
}

// direct O(n^2) history integral at t_{n+1} with g' piecewise constant, intervals before the
// current one (what the cache holds)
double direct_history(const std::vector<double>& gd, double h) {
  const size_t n = gd.size();  // intervals 0..n-1 completed; evaluate at t_{n+1}
  double s = 0;
  for (size_t j = 0; j < n; ++j) {
    const double lag_lo = double(n - j) * h, lag_hi = double(n + 1 - j) * h;
    s += gd[j] * 2.0 * (std::sqrt(lag_hi) - std::sqrt(lag_lo));
  }
  return s;
}

TEST(Basset, WindowPlusTailMatchesFullHistoryQuadrature) {
  const double h = 2e-3;
  const int steps = 3000;
  const BassetKernel k = make_basset_kernel(1.0, h, kBassetWindow, steps * h);
  std::vector<double> hist(k.stride());
  basset_reset(k, Vec3::Zero(), hist.data());
  std::vector<double> gd;
  double worst = 0, scale = 0;
  for (int n = 1; n <= steps; ++n) {
    const double t = n * h;
    const double g = std::sin(3 * t) + 0.5 * (1 - std::exp(-t));  // smooth, with memory
    gd.push_back((g - (n == 1 ? 0.0 : std::sin(3 * (t - h)) + 0.5 * (1 - std::exp(-(t - h))))) / h);
    basset_push(k, Vec3(g, 0, 0), h, hist.data());
    const double exact = direct_history(gd, h);
    // the history force per unit coefficient (k.coef = 1)
    worst = std::max(worst, std::abs(basset_history_force(k, hist.data()).x() - exact));
    scale = std::max(scale, std::abs(exact));
  }
  EXPECT_LT(worst / scale, 1e-3);
  RecordProperty("relative_error", std::to_string(worst / scale));
}

}  // namespace
}  // namespace lrigid
