#include "effects/plan.h"

#include "effects/magnus.h"
#include "effects/registry.h"

namespace lrigid {

Vec6 magnus_term(const EffectContext& c) {
  return magnus_wrench(*c.type, c.type->plan.params->magnus, c.v_rel, c.w);
}

WrenchTerm wrench_term(const BodyType& type, Effect effect) {
  const TermFor term = effect_info(effect).term;
  return term ? term(type) : nullptr;
}

void build_effect_plan(BodyType* type, TurbulenceModel turbulence_model, double rho, double nu) {
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
  auto params = std::make_shared<EffectParams>();
  params->drag = drag_params(*type, rho, nu);
  if (type->flat) {
    params->plate_drag = plate_params(*type, rho, nu, true, false);
    params->plate_lift = plate_params(*type, rho, nu, false, true);
    params->plate_both =
        plate_params(*type, rho, nu, e.has(Effect::Drag), e.has(Effect::Lift));
  }
  params->magnus = magnus_factor(*type, rho);
  p.params = std::move(params);
  type->plan = std::move(p);
}

}  // namespace lrigid
