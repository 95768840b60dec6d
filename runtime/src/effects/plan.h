// The per-body-type evaluation plan: the list of wrench terms of the selected effects, built
// once by compile_model. integrate/dynamics.cpp sums exactly these terms, in both the
// velocity form (rk4) and the impulse form (euler, splitting); unselected effects are never
// evaluated.
#pragma once
#include "effects/context.h"
#include "model/model.h"

namespace lrigid {

// Fills type->plan from type->effects (and the body's flatness). Needs type->basset when
// Basset is selected.
void build_effect_plan(BodyType* type, TurbulenceModel turbulence_model);

// The wrench term an effect contributes for this body type, or nullptr when the effect is no
// wrench (mean_flow and turbulence move the surrounding fluid instead) or does not apply
// (lift on a body that is not flat).
WrenchTerm wrench_term(const BodyType& type, Effect effect);

}  // namespace lrigid
