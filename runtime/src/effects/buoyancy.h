// Buoyancy: the displaced fluid's weight, -rho_f V g, acts at the centre of buoyancy (the volume
// centroid). About the centre of mass it gives the torque r_cob x F, which rights a bottom-heavy
// body (centre of mass below the centre of buoyancy). Together with gravity this is the
// "buoyancy-corrected gravity" R^T (m - rho_f V) g of the seed method (physics-notes §3).
#pragma once
#include "effects/context.h"
#include "effects/wrench.h"
#include "model/model.h"

namespace lrigid {

inline Wrench buoyancy_wrench(const BodyType& type, double fluid_density, const Vec3& g_body) {
  return wrench_at_centroid(type.r_cob, Vec3(-fluid_density * type.volume * g_body));
}

// the scalar step's term (the registry's row)
inline Vec6 buoyancy_term(const EffectContext& c) {
  return buoyancy_wrench(*c.type, c.model->fluid_density, c.g_body);
}

}  // namespace lrigid
