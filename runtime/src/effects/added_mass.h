// Added mass (fluid Kirchhoff tensor K). Its acceleration part sits on the left-hand side, in the
// generalized mass M = M_body + K that the step inverts (never a force from a lagged acceleration:
// that is the classic added-mass instability). What remains as a force is:
//   - the gyroscopic (Munk) terms of the fluid momentum K xi_r, with xi_r = (v - u_f; w) the
//     motion relative to the fluid: -(w x P_f; w x L_f + v_r x P_f). The v_r x P_f moment turns a
//     prolate body broadside.
//   - the fluid's own acceleration, which drags the added mass along: +K (a~; 0), with
//     a~ = d/dt (R^T u_f) = R^T Du/Dt - w x u_f (Auton et al. 1988 use the fluid's material
//     derivative Du/Dt = dU/dt + (U . grad) U).
#pragma once
#include "effects/context.h"
#include "effects/wrench.h"
#include "model/kirchhoff.h"
#include "model/model.h"

namespace lrigid {

// The kernel, written once (the scalar step's added_mass_wrench and added_mass_term, and the
// batched loops call it): the wrench f (body frame) for the fluid tensor K (model/kirchhoff.h
// mass_times: a DiagonalMass or FullMass holding K), v_rel the velocity of the centre of mass
// relative to the fluid, w the angular velocity, fluid_acc a~ above (body frame, m/s^2). The
// velocity form (rk4): K (a~; 0) - (w x P_f; w x L_f + v_r x P_f), (P_f; L_f) = K (v_r; w); the
// impulse form (euler, splitting; the rest lives in the impulse, integrate/dynamics.h):
// (0; -v_r x P_f). Both take back the Munk share K.S of a flat body with drag (BodyType::
// munk_back, model/kirchhoff.h): + v_r x (S v_r) on the moment.
template <bool ImpulseForm, typename T, class Tensor>
LRIGID_LANE void added_mass_kernel(const Tensor& K, const T* v_rel, const T* w, const T* fluid_acc,
                                   T* f) {
  const T xi_r[6] = {v_rel[0], v_rel[1], v_rel[2], w[0], w[1], w[2]};
  T mom[6], sv[3], back[3];
  mass_times(K, xi_r, mom);
  munk_back_momentum(K, v_rel, sv);
  cross3(v_rel, sv, back);
  if constexpr (ImpulseForm) {
    T m[3];
    cross3(v_rel, mom, m);
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) {
      f[a] = T(0);
      f[3 + a] = back[a] - m[a];
    }
  } else {
    const T acc[6] = {fluid_acc[0], fluid_acc[1], fluid_acc[2], T(0), T(0), T(0)};
    T ka[6], g[6];
    mass_times(K, acc, ka);
    kirchhoff_gyro_kernel(v_rel, w, mom, mom + 3, g);
#pragma GCC unroll 6
    for (int a = 0; a < 6; ++a) f[a] = ka[a] - g[a];
#pragma GCC unroll 3
    for (int a = 0; a < 3; ++a) f[3 + a] += back[a];
  }
}

// The body type's K for the kernel (symmetric: row or column major alike)
inline FullMass fluid_tensor(const BodyType& type) {
  return FullMass{type.K_fluid.data(), nullptr, type.munk_back.data()};
}

// v_rel: velocity of the centre of mass relative to the fluid, body frame; w: angular velocity;
// fluid_acc: a~ above, body frame, m/s^2.
inline Wrench added_mass_wrench(const BodyType& type, const Vec3& v_rel, const Vec3& w,
                                const Vec3& fluid_acc) {
  Wrench f;
  added_mass_kernel<false>(fluid_tensor(type), v_rel.data(), w.data(), fluid_acc.data(), f.data());
  return f;
}

// the scalar step's term (the registry's row). In the impulse form (euler, splitting) the rest
// of the Kirchhoff terms live in the impulse (integrate/dynamics.h): only -v_r x P_f remains.
inline Vec6 added_mass_term(const EffectContext& c) {
  if (c.impulse_form) {
    Wrench f;
    added_mass_kernel<true>(fluid_tensor(*c.type), c.v_rel.data(), c.w.data(), c.v_rel.data(),
                            f.data());
    return f;
  }
  return added_mass_wrench(*c.type, c.v_rel, c.w, c.fluid_acc);
}

}  // namespace lrigid
