// The per-body-type evaluation plan: the list of wrench terms of the selected effects (each the
// registry's TermFor of its row) and the kernels' parameters, built once by compile_model.
// effects/evaluate.h sums exactly these terms, in both the velocity form (rk4) and the
// impulse form (euler, splitting); the batched loops read the same parameters; unselected
// effects are never evaluated.
#pragma once
#include "effects/context.h"
#include "effects/drag.h"
#include "effects/plate.h"
#include "model/model.h"

namespace lrigid {

// Each kernel's Params (a plain struct of numbers) for one body type, in the fluid of the scene.
struct EffectParams {
  DragParams drag;          // effects/drag.h: bodies that are not flat
  PlateParams plate_drag;   // effects/plate.h: the plate's drag and torque (flat bodies)
  PlateParams plate_lift;   // the plate's lift alone
  PlateParams plate_both;   // drag (if selected) and lift (if selected) together: the batched loops
  double magnus = 0;        // effects/magnus.h: C_M rho V, kg/m
};

// Fills type->plan from type->effects (and the body's flatness) for fluid density rho (kg/m^3)
// and kinematic viscosity nu (m^2/s). Needs type->basset when Basset is selected.
void build_effect_plan(BodyType* type, TurbulenceModel turbulence_model, double rho, double nu);

// The wrench term an effect contributes for this body type (its registry row's TermFor), or
// nullptr.
WrenchTerm wrench_term(const BodyType& type, Effect effect);

}  // namespace lrigid
