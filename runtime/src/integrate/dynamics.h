// The generalized Kirchhoff equations of one body, body frame, about the centre of mass:
//   M xi' = sum of effect wrenches - (w x P_b; w x L_b)    with xi = (v; w), (P_b; L_b) = M_body xi
// M = M_body (+ K_fluid with added mass) is constant in the body frame and inverted once per body
// type (Model). Only selected effects are evaluated.
#pragma once
#include "effects/drag.h"
#include "fluid/field.h"
#include "model/model.h"

namespace lrigid {

struct Kinematics {
  Vec3 x;       // world, m
  Mat3 R;       // body -> world
  Vec3 v;       // body frame, m/s
  Vec3 w;       // body frame, rad/s
  Vec3 u_seen;  // seen fluctuation, world frame, m/s
};

enum class EvalResult { Ok, Outside };

// Does the body need the fluid field sampled at all?
inline bool needs_field(const BodyType& t) {
  return t.effects.has(Effect::MeanFlow) || t.effects.has(Effect::Turbulence);
}

// Acceleration xi' (body frame) and, when asked, the drag stiffness for implicit steps.
// `fluid` receives the sample used (zero flow when the field is not needed).
EvalResult velocity_derivative(const Model& model, const BodyType& type, const Kinematics& k,
                               double t, Vec6* xi_dot, FluidSample* fluid,
                               DragStiffness* stiffness = nullptr);

// World-frame impulse form (used by euler and splitting): with the body's generalized impulse
// Pi = M xi - K (u_f; 0) (u_f the fluid velocity in the body frame), its world-frame components
// change only through forces: d(R P)/dt = R F, d(R L)/dt = R (T - v_r x P_f). The frame-rotation
// terms w x P, w x L disappear, so fast spin cannot destabilize the step.
struct ImpulseRates {
  Vec6 impulse;              // Pi at the current state, body frame
  Vec6 rate;                 // (F; T - v_r x P_f), body frame components
  Vec3 u_fluid = Vec3::Zero();   // fluid velocity around the body, world frame, m/s
  Vec3 a_fluid = Vec3::Zero();   // its material derivative (mean flow), world frame, m/s^2
  bool fluid_inertia = false;    // K enters Pi (added mass selected)
};

EvalResult impulse_rates(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         ImpulseRates* out, DragStiffness* stiffness);

// xi = M^-1 (Pi + K (u_f_body; 0))
Vec6 velocity_from_impulse(const BodyType& type, const Vec6& impulse, const Vec3& u_fluid_body,
                           bool fluid_inertia);

// Sum of the effect wrenches alone (no rigid gyroscopic term): used by tests to check each
// effect's exact contribution.
EvalResult effect_wrench(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         Vec6* wrench, FluidSample* fluid, DragStiffness* stiffness = nullptr);

}  // namespace lrigid
