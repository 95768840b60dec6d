// The generalized Kirchhoff equations of one body, body frame, about the centre of mass:
//   M xi' = sum of effect wrenches - (w x P_b; w x L_b)    with xi = (v; w), (P_b; L_b) = M_body xi
// M = M_body (+ K_fluid with added mass) is constant in the body frame and inverted once per body
// type (Model). The effect wrenches are the terms of the body type's plan (effects/plan.h): only
// selected effects are evaluated, by both forms below (sum_effect_wrenches).
#pragma once
#include "effects/context.h"
#include "effects/drag.h"
#include "effects/evaluate.h"
#include "fluid/field.h"
#include "model/kirchhoff.h"
#include "model/model.h"

namespace lrigid {

// The body type's M as the kernels of model/kirchhoff.h take it
inline DiagonalMass diagonal_mass(const BodyType& t) {
  DiagonalMass m;
  for (int a = 0; a < 6; ++a) {
    m.M[a] = t.M(a, a);
    m.Mi[a] = t.M_inv_diagonal[a];
  }
  for (int a = 0; a < 3; ++a) m.S[a] = t.munk_back(a, a);
  return m;
}
inline FullMass full_mass(const BodyType& t) {
  return FullMass{t.M.data(), t.M_inv.data(), t.munk_back.data()};
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

// The free Kirchhoff flow (no forces) of the motion relative to a fluid moving uniformly with
// u_fluid (world, m/s) over h (s): Y' = -(w x P; w x L + v x P) for Y = (P; L) = M xi_r,
// xi_r = (v - R^T u_fluid; w), and R' = R w^. One implicit-midpoint step in the body frame,
// solved by Newton on the 6 components of Y, with the rotation q <- q cay(h w_mid): the
// midpoint rule keeps every quadratic invariant, so the relative kinetic energy 1/2 Y^T M^-1 Y,
// |P|^2 and P.L are conserved to the solver tolerance, and the Cayley rotation makes the
// world-frame impulse R P exactly constant. Substeps (up to kKirchhoffMaxSubsteps) when Newton
// does not converge. Returns the number of Newton iterations (cost accounting). For an isotropic
// M (spheres) the midpoint equation is linear and solved in closed form (no iteration).
constexpr int kKirchhoffMaxSubsteps = 64;
// The solver: the fixed-point iteration Y <- Y0 - h gyro((Y0 + Y)/2) first (cheap), at most
// kKirchhoffMaxFixedPoint times, until the update is below kKirchhoffTol |Y| (energy norm);
// Newton from there when it contracts by less than sqrt(kKirchhoffSlowContraction) per
// iteration, diverges or runs out. The batched step (rigid_batch.h) iterates by the same rule.
constexpr int kKirchhoffMaxFixedPoint = 40;
constexpr double kKirchhoffSlowContraction = 0.25;  // squared: contraction factor above 0.5
constexpr double kKirchhoffTol = 1e-13;             // update / |Y|, energy norm
// Newton (simplified: the Jacobian is kept while each step contracts by kKirchhoffRefactor),
// at most kKirchhoffMaxNewton iterations, before substeps
constexpr int kKirchhoffMaxNewton = 16;
constexpr double kKirchhoffRefactor = 0.25;
int kirchhoff_flow(const BodyType& type, const Vec3& u_fluid, double h, Quat* q, Vec3* v,
                   Vec3* w);

}  // namespace lrigid
