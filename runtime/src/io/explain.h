// What `lrigid explain SCENE.json` reports, as data (docs/effects.md): per body type the
// dimensionless numbers that decide which effects matter, the effects chosen and skipped (with
// the reason), the step taken and the estimated cost per body-step. The command prints it; the
// Python module returns it as a dict.
#pragma once
#include <nlohmann/json.hpp>

#include "model/scene.h"

namespace lrigid {

// Keys (SI units): scene, fluid {density, kinematic_viscosity, gravity}, flow {source, U, k,
// epsilon[, k_over_epsilon, tau_eta]}, art {mean_flow_scale, turbulence_scale}, integrator, dt,
// effects_auto, warnings [{check, key, message, error}] (io/sanity.h), body_types [{index, name, shape, count, mass, volume, density, density_ratio,
// aspect_ratio, flat, normal_axis, size, terminal_speed, relative_speed, reynolds, tau_p,
// stokes_k_eps, stokes_kolmogorov, spin_ratio, crossing_trajectories {on, reason, drift_speed,
// drift_over_u_turb, factor_along, factor_across}, plain_words (io/explain_words.h), effects [{name, size, keep, reason}],
// auto_chooses, scene_lists (effects listed by the scene, or null with "auto"), simulated,
// step {batched, kind, block, isa, precision, reason}, cost_ns}], total {body_steps,
// seconds_one_core}. Reads the grid when the scene has one; throws lrigid::Error on bad input.
nlohmann::json explain_scene(const Scene& scene);

}  // namespace lrigid
