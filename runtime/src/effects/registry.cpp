// The registry of effects (effects/registry.h): one row per effect. Adding an effect means a row
// here, a kernel header in src/effects/ and its tests (docs/adding-an-effect.md).
//
// Auto rules: an effect is kept when its force (or inertia) is at least kKeep of the larger of
// the body's net weight and its drag at the characteristic speed (docs/effects.md).
// Costs: additive fits, ns per body-step, one core of the development machine (docs/effects.md):
//  - scalar splitting step: bench/effects_bench, uniform field, idle machine, 2026-12-01 (the
//    fixed part and the sample's cost are in estimated_cost_ns below);
//  - batched steps: lrigid bench on scenes/beads_wind.json with --effects subsets (N = 10^4,
//    one thread, AVX-512 loops, best of 3, 2026-12-01): gravity 9.7 ns, + drag 17.5, + mean flow
//    51.8 (the grid sample), all six effects 67.2; the Basset history about 20 ns (its push),
//    Magnus about 1 ns (leaves and beads scenes with and without them, 2026-12-01).
#include <cmath>
#include <cstdio>
#include <string>

#include "effects/added_mass.h"
#include "effects/basset.h"
#include "effects/buoyancy.h"
#include "effects/drag.h"
#include "effects/gravity.h"
#include "effects/lift.h"
#include "effects/magnus.h"
#include "effects/registry.h"
#include "model/model.h"

namespace lrigid {

namespace {

constexpr double kKeep = 1e-2;        // force (or inertia) / reference below which an effect goes
constexpr double kKeepBasset = 0.1;   // history force / quasi-steady drag
constexpr double kBassetMaxRe = 100;  // the t^-1/2 kernel is a low-Re result (Mei & Adrian 1992)
constexpr double kTurbulenceMaxStokes = 1e4;

std::string fmt(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}

const std::string kRef = " of max(|W - B|, drag)";

// size >= kKeep, else "what = size of max(|W - B|, drag) < kKeep"
AutoDecision relative(double size, const char* what) {
  AutoDecision d;
  d.size = size;
  d.keep = size >= kKeep;
  if (!d.keep) d.why_not = std::string(what) + " = " + fmt(size) + kRef + " < " + fmt(kKeep);
  return d;
}

AutoDecision gravity_rule(const AutoInputs& a) { return relative(a.weight / a.F_ref, "weight"); }

AutoDecision buoyancy_rule(const AutoInputs& a) {
  return relative(a.buoyancy / a.F_ref, "buoyancy");
}

AutoDecision added_mass_rule(const AutoInputs& a) {
  AutoDecision d;
  d.size = a.added_mass_max / a.mass;
  d.keep = d.size >= kKeep;
  if (!d.keep) d.why_not = "largest added mass / mass = " + fmt(d.size) + " < " + fmt(kKeep);
  return d;
}

AutoDecision drag_rule(const AutoInputs& a) {
  return relative(a.drag_per_speed * a.speed / a.F_ref, "drag");
}

AutoDecision mean_flow_rule(const AutoInputs& a) {
  AutoDecision d = relative(a.drag_per_speed * a.flow_U / a.F_ref, "drag of the mean flow");
  if (!(a.flow_U > 0)) {
    d.keep = false;
    d.why_not = "the field's U is zero";
  }
  return d;
}

AutoDecision turbulence_rule(const AutoInputs& a) {
  // the part of the turbulent velocity the body does not filter out
  const double u_seen = a.u_turb / std::sqrt(1.0 + a.stokes_k_eps);
  AutoDecision d = relative(a.drag_per_speed * u_seen / a.F_ref, "turbulent drag");
  if (!(a.flow_k > 0)) {
    d.keep = false;
    d.why_not = "the field's k is zero";
  } else if (a.stokes_k_eps > kTurbulenceMaxStokes) {
    d.keep = false;
    d.why_not = "St = tau_p eps/k = " + fmt(a.stokes_k_eps) + " > " + fmt(kTurbulenceMaxStokes);
  }
  return d;
}

AutoDecision lift_rule(const AutoInputs& a) {
  const double F =
      a.flat ? 0.5 * a.rho * kLiftTranslational * a.plate_area * a.speed * a.speed : 0.0;
  AutoDecision d = relative(F / a.F_ref, "lift");
  if (!a.flat) {
    d.keep = false;
    d.why_not = "not flat: thickness/width = " + fmt(a.thickness_ratio) + " > " + fmt(kFlatRatio);
  }
  return d;
}

AutoDecision magnus_rule(const AutoInputs& a) {
  AutoDecision d =
      relative(kMagnus * a.rho * a.volume * a.spin * a.speed / a.F_ref, "Magnus force");
  if (!d.keep && !(a.spin > 0)) d.why_not = "no initial spin";
  return d;
}

AutoDecision basset_rule(const AutoInputs& a) {
  // the history force at the response time scale, relative to the quasi-steady drag
  const double coef = 6.0 * a.r_eq * a.r_eq * a.rho * std::sqrt(M_PI * a.nu);
  const double c = a.drag_per_speed;
  AutoDecision d;
  d.size = (a.tau_p > 0 && c > 0) ? coef / (std::sqrt(a.tau_p) * c) : 0;
  d.keep = d.size >= kKeepBasset && a.reynolds <= kBassetMaxRe;
  if (!d.keep)
    d.why_not = a.reynolds > kBassetMaxRe
                    ? "Re = " + fmt(a.reynolds) + " > " + fmt(kBassetMaxRe) +
                          " (the memory decays faster than t^-1/2)"
                    : "history force / drag = " + fmt(d.size) + " < " + fmt(kKeepBasset);
  return d;
}

// the rows' term selectors (the term functions live next to their kernels)
template <WrenchTerm Term>
WrenchTerm always(const BodyType&) {
  return Term;
}
WrenchTerm drag_for(const BodyType& t) { return t.flat ? plate_drag_term : drag_term; }
WrenchTerm lift_for(const BodyType& t) { return t.flat ? lift_term : nullptr; }

}  // namespace

const std::vector<EffectInfo>& all_effects() {
  using F = FieldNeed;
  // effect, name, summary, field, auto rule, scalar term, cost scalar ns, batched ns, batched
  static const std::vector<EffectInfo> list = {
      {Effect::Gravity, "gravity", "weight m g at the centre of mass", F::None, gravity_rule,
       always<gravity_term>, 5, 0, true},
      {Effect::Buoyancy, "buoyancy", "-rho_f V g at the centre of buoyancy", F::None,
       buoyancy_rule, always<buoyancy_term>, 5, 0, true},
      {Effect::AddedMass, "added_mass", "Kirchhoff tensor of the displaced fluid", F::None,
       added_mass_rule, always<added_mass_term>, 15, 0, true},
      {Effect::Drag, "drag", "quasi-steady drag on the velocity relative to the fluid", F::None,
       drag_rule, drag_for, 100, 8, true},
      {Effect::MeanFlow, "mean_flow", "the fluid moves with the field's mean velocity U", F::Sample,
       mean_flow_rule, nullptr, 0, 0, true},
      {Effect::Turbulence, "turbulence", "Langevin model from k and epsilon", F::Sample,
       turbulence_rule, nullptr, 100, 15, true},
      {Effect::Lift, "lift", "circulation lift of flat bodies (Andersen, Pesavento & Wang 2005)",
       F::None, lift_rule, lift_for, 80, 0, true},
      {Effect::Magnus, "magnus", "lift of a spinning body, C_M rho V w x v_r", F::None,
       magnus_rule, always<magnus_term>, 10, 1, true},
      {Effect::Basset, "basset", "history force, window plus exponential-sum tail", F::None,
       basset_rule, always<basset_term>, 90, 20, true},
  };
  return list;
}

const EffectInfo& effect_info(Effect e) {
  for (const EffectInfo& info : all_effects())
    if (info.effect == e) return info;
  return all_effects().front();  // unreachable: every Effect has a row (registry test)
}

bool effect_from_name(const std::string& name, Effect* out) {
  for (const auto& e : all_effects())
    if (name == e.name) {
      *out = e.effect;
      return true;
    }
  return false;
}

std::vector<std::string> effect_names(EffectSet set) {
  std::vector<std::string> names;
  for (const auto& e : all_effects())
    if (set.has(e.effect)) names.push_back(e.name);
  return names;
}

bool needs_field_sample(EffectSet set) {
  for (const auto& e : all_effects())
    if (set.has(e.effect) && e.field == FieldNeed::Sample) return true;
  return false;
}

const EffectInfo* first_unbatched(EffectSet set) {
  for (const auto& e : all_effects())
    if (set.has(e.effect) && !e.batched) return &e;
  return nullptr;
}

// ---- the cost fits (model/model.h), from the rows' parts
// -----------------------------------------

double estimated_cost_ns(EffectSet set, Integrator integrator, bool grid, bool isotropic_mass) {
  // additive fit to bench/effects_bench (docs/effects.md: splitting, uniform field, one core,
  // idle machine, 2026-12-01), each effect's part in its registry row (effects/registry.cpp);
  // sampling a grid costs more than the uniform field and is not included. A mass matrix that is
  // not a multiple of the identity per block (anything but a uniform sphere) needs the iterated
  // Kirchhoff flow instead of its closed form.
  (void)grid;
  double ns = 305;
  if (!isotropic_mass) ns += 240;
  if (needs_field_sample(set)) ns += 40;
  for (const EffectInfo& info : all_effects())
    if (set.has(info.effect)) ns += info.cost_ns;
  if (integrator == Integrator::Euler) ns *= 0.55;
  if (integrator == Integrator::RK4) ns *= 1.65;
  return ns;
}

double estimated_batched_cost_ns(EffectSet set, Precision precision, bool rigid,
                                 Integrator integrator) {
  // additive fit (effects/registry.cpp says to what), each effect's part in its registry row:
  // gravity, buoyancy and added mass cost next to nothing; the baseline x86-64 loops take about
  // 4 times longer. Plates and ellipsoids (rigid): scenes/leaves_wind.json (N = 10^4, one
  // thread, after 250 steps, best of 2, 2026-12-01): gravity and drag 23.5 ns, the scene's own
  // effects 85.5 ns, about 6 ns and 19 ns above the sphere fit. Lanes handed to the scalar step
  // (about 1.5 us each) are not in it: none on those scenes, where the loops solve stiff drag and
  // slow free flows by Newton themselves.
  double ns = 10;
  const bool sampled = needs_field_sample(set);
  if (sampled) ns += 34;
  for (const EffectInfo& info : all_effects())
    if (set.has(info.effect)) ns += info.batched_cost_ns;
  if (rigid) ns += sampled ? 19 : 6;
  // plates and ellipsoids on euler and rk4 (rigid_batch_explicit.h), against splitting on the
  // leaves scene (lrigid bench, N = 10^4, one thread, per CPU second, 2026-12-02,
  // docs/physics/integrators.md): 18.0 and 5.86 against 10.9 M body-steps/s
  if (rigid && integrator == Integrator::Euler) ns *= 0.61;
  if (rigid && integrator == Integrator::RK4) ns *= 1.86;
  // uniform spheres on euler and rk4 (the isotropic M's loops, rigid_batch_explicit.h), against
  // splitting on the beads scene
  // (lrigid bench scenes/beads_wind.json, N = 10^4, one thread, per CPU second, best of 2,
  // 2026-12-02, docs/physics/integrators.md): 17.3 and 6.37 against 14.7 M body-steps/s
  if (!rigid && integrator == Integrator::Euler) ns *= 0.85;
  if (!rigid && integrator == Integrator::RK4) ns *= 2.30;
  if (precision == Precision::Float) ns *= 0.78;
  return ns;
}

}  // namespace lrigid
