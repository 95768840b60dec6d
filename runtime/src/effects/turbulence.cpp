#include "effects/turbulence.h"

namespace lrigid {

Vec3 well_mixed_drift(const Vec3& u_seen, const Vec3& path_velocity, const FluidSample& s) {
  if (s.sigma2 <= 0) return Vec3::Zero();
  // stationary Fokker-Planck solution p ~ sigma^-3 exp(-|u|^2 / (2 sigma^2)) at uniform
  // concentration for tracers, x' = U + u' = path_velocity; for other paths u' stays
  // N(0, sigma^2(x)) along the path (derivation in docs/physics/langevin.md)
  return 0.5 * s.grad_sigma2 +
         u_seen * (path_velocity.dot(s.grad_sigma2) / (2.0 * s.sigma2));
}

}  // namespace lrigid
