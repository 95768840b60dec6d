// Magnus force on a spinning body: F = C_M rho V w x u (u: velocity of the centroid relative to
// the fluid, w: angular velocity; MuJoCo's fluid model uses the same form with C_M = 1). With
// C_M = 0.5 a sphere's lift coefficient is C_L = F / (1/2 rho pi a^2 u^2) = (8/3) C_M S = 1.33 S
// at spin ratio S = a w / u, inside the spread of sports-ball data for S < 0.3 (Rubinow & Keller's
// low-Re result is C_M = 3/4). No torque about the centroid; spin decays through the angular drag.
#pragma once
#include "effects/wrench.h"
#include "model/model.h"

namespace lrigid {

constexpr double kMagnus = 0.5;  // C_M

inline Wrench magnus_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho) {
  const Vec3 u = u_rel + w.cross(type.r_cob);
  const Vec3 f = kMagnus * rho * type.volume * w.cross(u);
  return make_wrench(f, type.r_cob.cross(f));
}

}  // namespace lrigid
