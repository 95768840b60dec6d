#include "effects/plan.h"

#include "effects/added_mass.h"
#include "effects/basset.h"
#include "effects/buoyancy.h"
#include "effects/drag.h"
#include "effects/gravity.h"
#include "effects/lift.h"
#include "effects/magnus.h"

namespace lrigid {

namespace {

Vec6 gravity_term(const EffectContext& c) { return gravity_wrench(*c.type, c.g_body); }

Vec6 buoyancy_term(const EffectContext& c) {
  return buoyancy_wrench(*c.type, c.model->fluid_density, c.g_body);
}

Vec6 added_mass_term(const EffectContext& c) {
  if (c.impulse_form) {
    // the rest of the Kirchhoff terms live in the impulse (integrate/dynamics.h)
    Vec6 xi_r;
    xi_r << c.v_rel, c.w;
    const Vec3 P_f = (c.type->K_fluid * xi_r).head<3>();
    return make_wrench(Vec3::Zero(), -c.v_rel.cross(P_f));
  }
  return added_mass_wrench(*c.type, c.v_rel, c.w, c.fluid_acc);
}

Vec6 drag_term(const EffectContext& c) {
  return drag_wrench(*c.type, c.v_rel, c.w, c.model->fluid_density, c.model->nu, c.stiffness);
}

Vec6 plate_drag_term(const EffectContext& c) {
  return plate_drag_wrench(*c.type, c.v_rel, c.w, c.model->fluid_density, c.model->nu,
                           c.stiffness);
}

Vec6 lift_term(const EffectContext& c) {
  return lift_wrench(*c.type, c.v_rel, c.w, c.model->fluid_density, c.model->nu);
}

Vec6 magnus_term(const EffectContext& c) {
  return magnus_wrench(*c.type, c.v_rel, c.w, c.model->fluid_density);
}

Vec6 basset_term(const EffectContext& c) { return basset_wrench(*c.type, c.Rt, c.history); }

}  // namespace

WrenchTerm wrench_term(const BodyType& type, Effect effect) {
  switch (effect) {
    case Effect::Gravity: return gravity_term;
    case Effect::Buoyancy: return buoyancy_term;
    case Effect::AddedMass: return added_mass_term;
    case Effect::Drag: return type.flat ? plate_drag_term : drag_term;
    case Effect::Lift: return type.flat ? lift_term : nullptr;
    case Effect::Magnus: return magnus_term;
    case Effect::Basset: return basset_term;
    case Effect::MeanFlow:
    case Effect::Turbulence: return nullptr;
  }
  return nullptr;
}

void build_effect_plan(BodyType* type, TurbulenceModel turbulence_model) {
  EffectPlan p;
  const EffectSet e = type->effects;
  for (const EffectInfo& info : all_effects()) {
    if (!e.has(info.effect)) continue;
    if (WrenchTerm t = wrench_term(*type, info.effect)) {
      p.terms.push_back(t);
      p.term_effect.push_back(info.effect);
    }
  }
  p.mean_flow = e.has(Effect::MeanFlow);
  p.sample_field = needs_field_sample(e);
  p.gradients = e.has(Effect::AddedMass) && e.has(Effect::MeanFlow);
  p.basset = e.has(Effect::Basset);
  p.seen = e.has(Effect::Turbulence) && turbulence_model == TurbulenceModel::Seen;
  type->plan = std::move(p);
}

}  // namespace lrigid
