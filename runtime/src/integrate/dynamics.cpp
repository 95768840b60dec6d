#include "integrate/dynamics.h"

#include "effects/mean_flow.h"
#include "effects/wrench.h"

namespace lrigid {

bool effect_context(const Model& model, const BodyType& type, const Kinematics& k, double t,
                    bool impulse_form, FluidSample* fluid, EffectContext* c, Vec3* u_fluid) {
  const EffectPlan& p = type.plan;
  // sample the fluid only when an effect needs it; gradients only for the added-mass drag-along
  *fluid = FluidSample();
  if (p.sample_field && !sample_fluid(model, k.x, t, p.gradients, fluid)) return false;
  // fluid velocity around the body (world): mean flow plus the seen fluctuation
  Vec3 uf = Vec3::Zero();
  if (p.mean_flow) uf += fluid->U;
  if (p.seen) uf += k.u_seen;
  c->model = &model;
  c->type = &type;
  c->Rt = k.R.transpose();
  const Vec3 uf_b = c->Rt * uf;
  c->v_rel = k.v - uf_b;
  c->w = k.w;
  c->g_body = c->Rt * model.gravity;
  c->fluid = fluid;
  c->history = k.history;
  c->impulse_form = impulse_form;
  c->fluid_acc.setZero();
  if (!impulse_form && type.effects.has(Effect::AddedMass)) {
    c->fluid_acc = -k.w.cross(uf_b);
    if (p.gradients) c->fluid_acc += c->Rt * mean_flow_acceleration(*fluid);
  }
  *u_fluid = uf;
  return true;
}

EvalResult effect_wrench(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         Vec6* wrench, FluidSample* fluid, DragStiffness* stiffness) {
  EffectContext c;
  Vec3 uf;
  if (!effect_context(model, type, k, t, false, fluid, &c, &uf)) return EvalResult::Outside;
  c.stiffness = stiffness;
  *wrench = sum_effect_wrenches(c);
  return EvalResult::Ok;
}

EvalResult impulse_rates(const Model& model, const BodyType& type, const Kinematics& k, double t,
                         ImpulseRates* out, DragStiffness* stiffness) {
  FluidSample fluid;
  EffectContext c;
  Vec3 uf;
  if (!effect_context(model, type, k, t, true, &fluid, &c, &uf)) return EvalResult::Outside;
  c.stiffness = stiffness;
  Vec6 xi;
  xi << k.v, k.w;
  out->fluid_inertia = type.effects.has(Effect::AddedMass);
  out->impulse = type.M * xi;
  out->u_fluid = uf;
  out->a_fluid.setZero();
  if (out->fluid_inertia) {
    Vec6 ufb;
    ufb << c.Rt * uf, Vec3::Zero();
    out->impulse -= type.K_fluid * ufb;
    if (type.plan.mean_flow) out->a_fluid = mean_flow_acceleration(fluid);
  }
  out->rate = sum_effect_wrenches(c);
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
