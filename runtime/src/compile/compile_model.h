// Compiling a scene into the constant model and its initial state: each body type's mass
// properties, generalized mass, the effects "auto" keeps (the registry's rules, weighed on the
// scene's representative flow), its Basset kernel, its plan of wrench terms and its contact
// points. It needs the effects (effects/: the registry, the effects' parameters) and the contact
// points (contact/), so it lives above both, beside the steps that run the model (layers:
// model/ <- effects/ <- contact/ <- compile/, integrate/; tests/runtime/layers_test.py).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "model/model.h"
#include "model/state.h"

namespace lrigid {

// Representative flow of a scene for the dimensionless numbers of "auto" and `lrigid explain`.
// Uniform field: its U, k, eps. Grid: medians over valid grid points (up to ~32^3 sampled) of
// |U|, and of k and eps recovered from the Langevin coefficients (first frame).
struct FlowScales {
  double U = 0;        // |U|, m/s
  double k = 0;        // m^2/s^2
  double eps = 0;      // m^2/s^3
  std::string source;  // how they were obtained
};
FlowScales flow_scales(const Scene& scene, const FluidField& field);

// Why "auto" keeps or skips each effect of a body type (docs/effects.md states the thresholds).
struct EffectAnalysis {
  double density_ratio = 0;    // rho_f / rho_b
  double aspect_ratio = 1;     // smallest / largest semi-axis of the equivalent ellipsoid
  double size = 0;             // d: diameter of the equal-volume sphere (chord for flat), m
  double speed = 0;            // characteristic speed relative to the fluid, m/s
  double terminal_speed = 0;   // settling speed in still fluid, m/s
  double reynolds = 0;         // speed d / nu
  double tau_p = 0;            // response time m_eff / drag coefficient, s
  double stokes_k_eps = 0;     // tau_p / (k / eps)
  double stokes_kolmogorov = 0;  // tau_p / sqrt(nu / eps)
  double spin_ratio = 0;       // r_eq |w0| / speed
  std::vector<std::pair<Effect, double>> size_rel;  // force (or inertia) / driving force
  EffectSet chosen;
  std::vector<std::pair<Effect, std::string>> skipped;
};
EffectAnalysis analyze_effects(const Scene& scene, const BodyType& type, const FlowScales& flow,
                               const BodySpec& spec);

// Effects chosen for "effects": "auto" (analyze_effects().chosen).
EffectSet auto_effects(const Scene& scene, const BodyType& type, const FlowScales& flow,
                       const BodySpec& spec);

// The fluid Kirchhoff tensor a body type of `shape` takes in a run, about the shape's volume
// centroid in the shape axes (a mass offset then moves it to the centre of mass): a flat body
// whose surfaces are planes (a box, an ellipsoid, or a mesh whose extent along its normal is at
// most 1.5 times its mean thickness, volume / planform area) takes its planform's, w times the
// rectangle's (panel method) plus 1 - w times the ellipse's (Lamb), turned with the planform's
// axes e1, e2; any other body its own (Lamb's, or the panel solution of its surface).
// docs/physics/added-mass.md, "Flat bodies: the planform's tensor". Throws as `added_mass` does.
struct TypeAddedMass {
  AddedMass added_mass;        // tensor (kg, kg m, kg m^2 for fluid_density), method, panels
  bool from_planform = false;  // the planform's blend (flat and planar), else the shape's own
  bool flat = false;           // the body counts as flat (BodyType::flat)
  int normal_axis = 2;         // its plate normal, when flat
  Planform planform;           // its planform (R, w, e1, e2), when flat
};
TypeAddedMass type_added_mass(const Shape& shape, double fluid_density, int panels,
                              const AddedMassProvider& added_mass);

// Throws lrigid::Error naming the scene file and key for physically impossible input.
Model compile_model(const Scene& scene, FluidField field, const AddedMassProvider& added_mass);

// Places the bodies as the scene says; random draws are keyed by (seed, body), so the state
// does not depend on threads. The seen turbulence starts from its stationary distribution, the
// Basset history from the relative velocity at t = 0.
State initial_state(const Model& model, const Scene& scene);

// Where body `id` of the entry `spec` (scene.bodies[entry]) starts (its position, its draw in
// the spawn box or on the solids' surface), as initial_state places it.
Vec3 initial_position(const Model& model, const BodySpec& spec, size_t entry, uint32_t id);

}  // namespace lrigid
