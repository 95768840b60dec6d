#include "effects/evaluate.h"

#include "effects/mean_flow.h"

namespace lrigid {

void context_from_sample(const Model& model, const BodyType& type, const Kinematics& k,
                         bool impulse_form, const FluidSample* fluid, EffectContext* c,
                         Vec3* u_fluid) {
  const EffectPlan& p = type.plan;
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
}

bool effect_context(const Model& model, const BodyType& type, const Kinematics& k, double t,
                    bool impulse_form, FluidSample* fluid, EffectContext* c, Vec3* u_fluid) {
  const EffectPlan& p = type.plan;
  // sample the fluid only when an effect needs it; gradients only for the added-mass drag-along
  *fluid = FluidSample();
  if (p.sample_field && !sample_fluid(model, k.x, t, p.gradients, fluid)) return false;
  context_from_sample(model, type, k, impulse_form, fluid, c, u_fluid);
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

}  // namespace lrigid
