#include "integrate/dynamics.h"

#include "effects/added_mass.h"
#include "effects/buoyancy.h"
#include "effects/gravity.h"
#include "effects/mean_flow.h"
#include "effects/wrench.h"

namespace lrigid {

EvalResult effect_wrench(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         Vec6* wrench, FluidSample* fluid, DragStiffness* stiffness) {
  const EffectSet e = type.effects;
  const Mat3 Rt = k.R.transpose();
  Vec6 f = Vec6::Zero();

  // sample the fluid only when an effect needs it; gradients only for the added-mass drag-along
  *fluid = FluidSample();
  if (needs_field(type)) {
    const bool grads = e.has(Effect::AddedMass) && e.has(Effect::MeanFlow);
    if (!model.field.sample(k.x, t, grads, fluid)) return EvalResult::Outside;
  }
  // fluid velocity around the body (world): mean flow plus the seen fluctuation
  Vec3 u_fluid = Vec3::Zero();
  if (e.has(Effect::MeanFlow)) u_fluid += fluid->U;
  if (e.has(Effect::Turbulence) && model.turbulence_model == TurbulenceModel::Seen)
    u_fluid += k.u_seen;
  const Vec3 u_fluid_b = Rt * u_fluid;
  const Vec3 v_rel = k.v - u_fluid_b;

  if (e.has(Effect::Gravity) || e.has(Effect::Buoyancy)) {
    const Vec3 g_b = Rt * model.gravity;
    if (e.has(Effect::Gravity)) f += gravity_wrench(type, g_b);
    if (e.has(Effect::Buoyancy)) f += buoyancy_wrench(type, model.fluid_density, g_b);
  }
  if (e.has(Effect::AddedMass)) {
    Vec3 acc = -k.w.cross(u_fluid_b);
    if (e.has(Effect::MeanFlow)) acc += Rt * mean_flow_acceleration(*fluid);
    f += added_mass_wrench(type, v_rel, k.w, acc);
  }
  if (e.has(Effect::Drag))
    f += drag_wrench(type, v_rel, k.w, model.fluid_density, model.nu, stiffness);
  *wrench = f;
  return EvalResult::Ok;
}

EvalResult impulse_rates(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         ImpulseRates* out, DragStiffness* stiffness) {
  const EffectSet e = type.effects;
  const Mat3 Rt = k.R.transpose();
  FluidSample fluid;
  if (needs_field(type)) {
    const bool grads = e.has(Effect::AddedMass) && e.has(Effect::MeanFlow);
    if (!model.field.sample(k.x, t, grads, &fluid)) return EvalResult::Outside;
  }
  Vec3 u_fluid = Vec3::Zero();
  if (e.has(Effect::MeanFlow)) u_fluid += fluid.U;
  if (e.has(Effect::Turbulence) && model.turbulence_model == TurbulenceModel::Seen)
    u_fluid += k.u_seen;
  const Vec3 u_fluid_b = Rt * u_fluid;
  const Vec3 v_rel = k.v - u_fluid_b;
  Vec6 xi;
  xi << k.v, k.w;
  Vec6 f = Vec6::Zero();
  if (e.has(Effect::Gravity) || e.has(Effect::Buoyancy)) {
    const Vec3 g_b = Rt * model.gravity;
    if (e.has(Effect::Gravity)) f += gravity_wrench(type, g_b);
    if (e.has(Effect::Buoyancy)) f += buoyancy_wrench(type, model.fluid_density, g_b);
  }
  out->fluid_inertia = e.has(Effect::AddedMass);
  out->impulse = type.M * xi;
  out->u_fluid = u_fluid;
  out->a_fluid.setZero();
  if (out->fluid_inertia) {
    Vec6 xi_r;
    xi_r << v_rel, k.w;
    const Vec3 P_f = (type.K_fluid * xi_r).head<3>();
    f.tail<3>() -= v_rel.cross(P_f);  // Munk moment
    Vec6 uf;
    uf << u_fluid_b, Vec3::Zero();
    out->impulse -= type.K_fluid * uf;
    if (e.has(Effect::MeanFlow)) out->a_fluid = mean_flow_acceleration(fluid);
  }
  if (e.has(Effect::Drag))
    f += drag_wrench(type, v_rel, k.w, model.fluid_density, model.nu, stiffness);
  out->rate = f;
  return EvalResult::Ok;
}

Vec6 velocity_from_impulse(const BodyType& type, const Vec6& impulse, const Vec3& u_fluid_body,
                           bool fluid_inertia) {
  if (!fluid_inertia) return type.M_inv * impulse;
  Vec6 uf;
  uf << u_fluid_body, Vec3::Zero();
  return type.M_inv * (impulse + type.K_fluid * uf);
}

EvalResult velocity_derivative(const Model& model, const BodyType& type, const Kinematics& k,
                               double t, Vec6* xi_dot, FluidSample* fluid,
                               DragStiffness* stiffness) {
  Vec6 f;
  if (effect_wrench(model, type, k, t, &f, fluid, stiffness) == EvalResult::Outside)
    return EvalResult::Outside;
  // rigid body's own gyroscopic terms (about the COM, v x m v = 0)
  Vec6 xi;
  xi << k.v, k.w;
  f -= kirchhoff_gyro(k.v, k.w, type.M_body * xi);
  *xi_dot = type.M_inv * f;
  return EvalResult::Ok;
}

}  // namespace lrigid
