#include "fluid/turbulence_coefficients.h"

#include <algorithm>
#include <cmath>

namespace lrigid {

double taylor_reynolds(double k, double eps, double nu) {
  // Re_L = k^2/(nu eps); R_lambda = sqrt(20/3 Re_L) for isotropic turbulence (Pope 2000 §6)
  return std::sqrt(20.0 / 3.0 * k * k / (nu * eps));
}

double c0_of_reynolds(double r_lambda) {
  if (r_lambda <= 0) return 0;
  return 6.5 / (1.0 + 140.0 * std::pow(r_lambda, -4.0 / 3.0));
}

LangevinCoefficients langevin_coefficients(double k, double eps, double nu, Drift drift,
                                           const TurbulenceLimits& limits) {
  k = std::max(k, limits.k_min);
  eps = std::max(eps, limits.eps_min);
  LangevinCoefficients c;
  c.c0 = std::max(c0_of_reynolds(taylor_reynolds(k, eps, nu)), limits.c0_min);
  c.beta = std::sqrt(c.c0 * eps);
  const double factor = drift == Drift::Original ? 0.5 + 0.75 * c.c0 : 0.75 * c.c0;
  const double alpha = factor * eps / k;
  c.sigma2 = c.beta * c.beta / (2.0 * alpha);  // = C0 k / (2 factor), bounded by k
  // cap the rate at the Kolmogorov frequency and keep the variance: beta follows alpha
  c.alpha = std::min(alpha, std::sqrt(eps / nu));
  if (c.alpha < alpha) c.beta = std::sqrt(2.0 * c.alpha * c.sigma2);
  return c;
}

}  // namespace lrigid
