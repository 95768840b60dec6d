// Langevin turbulence from the local k and epsilon (docs/physics/langevin.md; physics-notes §2).
// Ornstein-Uhlenbeck process du = -alpha u dt + beta dW with alpha, beta from
// fluid/turbulence_coefficients.h. Two models:
//   body: the body's velocity relative to the mean flow follows the OU process directly (the seed
//         method); its angular velocity follows one with the same alpha and beta / r_eq
//         (r_eq: radius of the sphere of equal volume), so <w_i^2> = sigma2 / r_eq^2.
//   seen: the fluctuating fluid velocity u' seen by the body follows the OU process and acts on
//         the body through drag and added mass: heavy bodies filter it, light ones follow it.
//         In inhomogeneous turbulence it carries Thomson's (1987) well-mixed drift
//         a_i = 1/2 d_i sigma2 + u'_i v . grad sigma2 / (2 sigma2), which keeps a uniform
//         cloud of tracers uniform (without it tracers gather where k is low). v is the velocity
//         of the path along which u' is sampled, the body's own: for a tracer v = U + u'
//         (Thomson's form); for a body that lags the fluid the term keeps u' / sigma stationary
//         along its path, where U + u' would feed u' back into itself (d u'/dt ~ u'^2, a
//         blow-up in finite time in steep gradients: docs/physics/langevin.md).
#pragma once
#include <cmath>

#include "fluid/field.h"
#include "util/types.h"

namespace lrigid {

// exact OU update over h: u <- decay u + noise_std xi
struct OUStep {
  double decay = 1;      // exp(-alpha h)
  double noise_std = 0;  // beta sqrt((1 - exp(-2 alpha h)) / (2 alpha)), m/s
};

inline OUStep ou_exact(double alpha, double beta, double h) {
  OUStep s;
  const double ah = alpha * h;
  s.decay = std::exp(-ah);
  // -expm1(-2 a h) / (2 a) keeps its precision for small a h; the a -> 0 limit is h
  s.noise_std = ah > 1e-12 ? beta * std::sqrt(-std::expm1(-2.0 * ah) / (2.0 * alpha))
                           : beta * std::sqrt(h);
  return s;
}

// Thomson's well-mixed drift correction for the seen fluctuation u' (world frame), m/s^2, for u'
// sampled along a path moving at path_velocity (world frame, m/s).
Vec3 well_mixed_drift(const Vec3& u_seen, const Vec3& path_velocity, const FluidSample& s);

}  // namespace lrigid
