// The registry of effects: one table (all_effects(), effects/registry.cpp) says for each effect
// its name, what it needs of the fluid field, the rule by which "auto" keeps or skips it, its
// estimated cost per body-step on the scalar and on the batched step, and whether the batched
// steps' loops implement it. "auto", `lrigid explain`, the cost estimates, the plan
// (effects/plan.cpp) and the batched steps' eligibility all read it. Each effect's force is a
// kernel in src/effects/. docs/adding-an-effect.md says how to add one.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "model/model.h"

namespace lrigid {

// What an effect needs of the fluid field at a body's position.
enum class FieldNeed : uint8_t {
  None,    // nothing: the fluid at rest will do
  Sample,  // U, k, eps (Langevin coefficients) at the position: one grid sample per step
};

// What the "auto" rules weigh, per body type, from analyze_effects (compile/compile_model.cpp):
// forces in N, speeds in m/s (docs/effects.md states the thresholds).
struct AutoInputs {
  double weight = 0, buoyancy = 0;  // W = m g, B = rho_f V g
  double F_ref = 0;                 // max(|W - B|, drag at the characteristic speed)
  double drag_per_speed = 0;        // c: drag / speed at the characteristic speed, kg/s
  double speed = 0;                 // characteristic speed relative to the fluid
  double mass = 0, added_mass_max = 0;  // kg: the body's, its largest linear added mass
  double flow_U = 0, flow_k = 0;    // the scene's representative |U| and k (m^2/s^2)
  double u_turb = 0;                // sqrt(2 k / 3)
  double stokes_k_eps = 0;          // tau_p eps / k
  double spin = 0;                  // initial spin, rad/s
  double rho = 0, nu = 0, volume = 0, r_eq = 0, tau_p = 0, reynolds = 0;
  bool flat = false;
  double plate_area = 0, thickness_ratio = 0;  // m^2; thickness / width
};

// An "auto" rule's verdict: the effect's size relative to its reference, keep or not, and why
// not (empty when kept).
struct AutoDecision {
  double size = 0;
  bool keep = false;
  std::string why_not;
};
using AutoRule = AutoDecision (*)(const AutoInputs&);

// The scalar step's wrench term of an effect for a body type (nullptr: the effect is no wrench,
// like mean_flow and turbulence, which move the surrounding fluid, or does not apply, like lift
// on a body that is not flat). The term functions live next to their kernels in src/effects/.
using TermFor = WrenchTerm (*)(const BodyType&);

struct EffectInfo {
  Effect effect;
  const char* name;
  const char* summary;
  FieldNeed field;         // what it needs of the field
  AutoRule rule;           // whether "auto" keeps it
  TermFor term;            // its wrench term on the scalar step
  double cost_ns;          // added cost per body-step, scalar splitting step (estimated_cost_ns)
  double batched_cost_ns;  // the same on the batched steps (estimated_batched_cost_ns)
  bool batched;            // the batched steps' loops implement it; otherwise a body type that
                           // selects it takes the scalar step (explain and summary.json say so)
};

// All effects, in evaluation order.
const std::vector<EffectInfo>& all_effects();
const EffectInfo& effect_info(Effect e);
// Name to effect; returns false for an unknown name.
bool effect_from_name(const std::string& name, Effect* out);
std::vector<std::string> effect_names(EffectSet set);
// Whether any selected effect needs the field sampled.
bool needs_field_sample(EffectSet set);
// The first selected effect the batched steps do not implement (nullptr: none).
const EffectInfo* first_unbatched(EffectSet set);


// Estimated cost of one body-step for an effect set and integrator, ns: an additive fit to the
// table in docs/effects.md (uniform field; grid sampling is extra). A guide, not a promise.
double estimated_cost_ns(EffectSet set, Integrator integrator, bool grid, bool isotropic_mass);
// The same for a body type that takes the batched step (integrate/rigid_batch.h): uniform spheres
// (the loops of an isotropic M) or, with `rigid`, plates, ellipsoids and meshes; a fit to
// docs/batched-step.md's measurements (AVX-512 loops, steady grid, one core).
double estimated_batched_cost_ns(EffectSet set, Precision precision, bool rigid = false,
                                 Integrator integrator = Integrator::Splitting);

}  // namespace lrigid
