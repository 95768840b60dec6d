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
#include "model/model.h"

namespace lrigid {

// v_rel: velocity of the centre of mass relative to the fluid, body frame; w: angular velocity;
// fluid_acc: a~ above, body frame, m/s^2.
inline Wrench added_mass_wrench(const BodyType& type, const Vec3& v_rel, const Vec3& w,
                                const Vec3& fluid_acc) {
  Vec6 xi_r;
  xi_r << v_rel, w;
  const Vec6 momentum = type.K_fluid * xi_r;
  Vec6 a;
  a << fluid_acc, Vec3::Zero();
  return type.K_fluid * a - kirchhoff_gyro(v_rel, w, momentum);
}

// the scalar step's term (the registry's row). In the impulse form (euler, splitting) the rest
// of the Kirchhoff terms live in the impulse (integrate/dynamics.h): only -v_r x P_f remains.
inline Vec6 added_mass_term(const EffectContext& c) {
  if (c.impulse_form) {
    Vec6 xi_r;
    xi_r << c.v_rel, c.w;
    const Vec3 P_f = (c.type->K_fluid * xi_r).head<3>();
    return make_wrench(Vec3::Zero(), -c.v_rel.cross(P_f));
  }
  return added_mass_wrench(*c.type, c.v_rel, c.w, c.fluid_acc);
}

}  // namespace lrigid
