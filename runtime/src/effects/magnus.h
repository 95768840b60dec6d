// Magnus force on a spinning body: F = C_M rho V w x u (u: velocity of the centroid relative to
// the fluid, w: angular velocity; MuJoCo's fluid model uses the same form with C_M = 1). With
// C_M = 0.5 a sphere's lift coefficient is C_L = F / (1/2 rho pi a^2 u^2) = (8/3) C_M S = 1.33 S
// at spin ratio S = a w / u, inside the spread of sports-ball data for S < 0.3 (Rubinow & Keller's
// low-Re result is C_M = 3/4). No torque about the centroid; spin decays through the angular drag.
#pragma once
#include "effects/context.h"
#include "effects/wrench.h"
#include "model/model.h"
#include "util/lane.h"

namespace lrigid {

constexpr double kMagnus = 0.5;  // C_M

// The kernel, written once (the scalar step's magnus_wrench and the batched loops call it):
// f = c w x u for spin w and relative velocity u in one frame, c = magnus_factor(), N.
template <typename T>
LRIGID_LANE void magnus_kernel(T c, const T* w, const T* u, T* f) {
  T wxu[3];
  cross3(w, u, wxu);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) f[a] = c * wxu[a];
}

// C_M rho V, kg
inline double magnus_factor(const BodyType& type, double rho) {
  return kMagnus * rho * type.volume;
}

// c: magnus_factor (EffectParams::magnus)
inline Wrench magnus_wrench(const BodyType& type, double c, const Vec3& u_rel, const Vec3& w) {
  const Vec3 u = centroid_velocity(type.r_cob, u_rel, w);
  Vec3 f;
  magnus_kernel(c, w.data(), u.data(), f.data());
  return wrench_at_centroid(type.r_cob, f);
}

inline Wrench magnus_wrench(const BodyType& type, const Vec3& u_rel, const Vec3& w, double rho) {
  return magnus_wrench(type, magnus_factor(type, rho), u_rel, w);
}

// the scalar step's term (the registry's row; effects/plan.cpp has the factor)
Vec6 magnus_term(const EffectContext& c);

}  // namespace lrigid
