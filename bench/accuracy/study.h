// The error-versus-cost study (docs/accuracy.md): runs a scene with one integrator,
// time step, Brownian-path resolution, effect set and field, and compares two runs' body
// positions with the metrics of the study. Shared by bench/accuracy/accuracy_study.cpp and the
// reduced study in tests/accuracy/.
#pragma once
#include <cstdint>
#include <cstddef>
#include <string>
#include <vector>

#include "integrate/simulation.h"
#include "model/model.h"
#include "model/scene.h"
#include "model/state.h"

namespace lrigid::accuracy {

enum class EffectMode { Scene, Full, Auto, Minimal };
const char* effect_mode_name(EffectMode m);

struct RunSpec {
  Integrator integrator = Integrator::Splitting;
  double dt = 1e-3;              // s
  uint32_t substeps = 1;         // Brownian increments summed per step
  EffectMode effects = EffectMode::Scene;
  bool turbulence = true;        // false: the Turbulence effect is removed from every body type
  int threads = 1;
  // the batched step's arithmetic (integrate/rigid_batch.h; splitting only)
  Precision precision = Precision::Double;
};

// Body positions at the output times (t = 0 first) and the run's cost.
struct RunResult {
  std::vector<double> times;               // s
  std::vector<std::vector<Vec3>> x;        // [output][body], world, m
  std::vector<BodyStatus> status;          // at the end
  RunStats stats;
  double wall_total = 0;                   // compile + initial state + integration, s
  double cpu_seconds = 0;                  // process CPU time of the integration, s
};

// Runs `scene` (its body counts, duration and seed as given) on `field` with the overrides of
// `spec`; `every` is the output interval (s, a multiple of spec.dt).
RunResult run(const Scene& scene, const FluidField& field, const RunSpec& spec, double every);

// One number with its Monte Carlo standard error (0 when the metric is not statistical).
struct Metric {
  double value = 0;
  double se = 0;
  bool valid = false;      // false: a body failed/exited in one run only, or too few bodies
  std::string note;
};

// Relative pathwise error: max over output times t > 0 of RMS_i |x_a - x_r| / L(t), with L(t)
// the RMS displacement of the reference bodies from their start. Used for deterministic runs
// (trajectory error) and for runs on the same Brownian path (strong error).
// With `last` given: only the output times 1..last (last = 1: the first compared time, before
// the chaos of tumbling plates amplifies a step's error).
Metric pathwise_error(const RunResult& a, const RunResult& ref, size_t last = SIZE_MAX);
// Weak error in the mean position at the last output, |mean x_a - mean x_r| / L(T), and its
// standard error from the paired differences (common random numbers).
Metric weak_mean_error(const RunResult& a, const RunResult& ref);
// Weak error in the total position variance at the last output, |V_a - V_r| / V_r.
Metric weak_variance_error(const RunResult& a, const RunResult& ref);
// Landing points (bodies landed in both runs; horizontal position): mean error / L(T) and the
// relative variance error. invalid when fewer than 30 bodies landed in both.
Metric landing_mean_error(const RunResult& a, const RunResult& ref);
Metric landing_variance_error(const RunResult& a, const RunResult& ref);


Integrator integrator_from_name(const std::string& name);  // throws on an unknown name
// Scales the scene's body counts so they sum to about n (each type keeps at least one body).
void scale_bodies(Scene* scene, int n);

}  // namespace lrigid::accuracy
