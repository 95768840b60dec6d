// Runs a model from its initial state to model.duration, calling `on_output` at t = 0 and every
// `every` seconds. Bodies are independent: each thread advances its share of bodies through a
// whole output interval, and the result is bitwise identical for any thread count.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "model/state.h"

namespace lrigid {

struct RunStats {
  uint64_t body_steps = 0;     // steps taken by moving bodies
  // of them, steps a batched block handed to the scalar step (integrate/rigid_batch.h)
  uint64_t scalar_handoffs = 0;
  // steps on which a batched block ran Newton itself (stiff drag, or the free Kirchhoff flow;
  // counted per iteration kind, so a step can count twice; with contacts between bodies also the
  // speculative steps that were taken again, simulation.cpp ContactStretches)
  uint64_t newton_steps = 0;
  uint64_t steps = 0;          // time steps
  double wall_seconds = 0;     // integration only (no output)
  size_t landed = 0, exited = 0, failed = 0;
  // contacts between bodies (Model::body_contact): touching pairs summed over the steps, and
  // sleeping bodies a contact woke
  uint64_t pair_steps = 0;
  uint64_t pair_wakes = 0;
  // stretches of several steps taken in lockstep from their start, where bodies touch from step
  // to step (simulation.cpp ContactStretches; the others are taken speculatively)
  uint64_t lockstep_stretches = 0;
  // at the end: bodies resting on a surface or asleep there (contact/sleep.h)
  size_t resting = 0;
};

struct RunOptions {
  double every = 0.1;          // s between outputs (rounded to a whole number of steps)
  int threads = 0;             // 0 = OpenMP default
  std::function<void(const State&)> on_output;        // may be empty
  std::function<void(const State&, double fraction)> on_progress;  // may be empty
  // bodies this process advances, [body_begin, min(body_end, size)); the others stay as they
  // are unless on_sync brings them up to date (several MPI ranks, app/ranks.h)
  size_t body_begin = 0;
  size_t body_end = ~size_t(0);
  // called before each output (also where on_output is empty); `last` on the final one
  std::function<void(State&, bool last)> on_sync;  // may be empty
  // a resumed run (app checkpoints): no output at the start (it was written before), and the
  // counts go on from *live_stats; when set, *live_stats is kept up to date before each output
  bool output_at_start = true;
  RunStats* live_stats = nullptr;
  // with contacts between bodies (Model::body_contact): the steps of a speculative stretch (0:
  // the default, simulation.cpp kContactStretchSteps; 1: the lockstep, every body one step at a
  // time with the contact stage after each step). The results do not depend on it (tests).
  uint64_t contact_stretch = 0;
};

RunStats simulate(const Model& model, State* state, const RunOptions& options);

// Which step a body type takes: "batched" (integrate/rigid_batch.h) or "scalar"; for the scalar
// step, why not batched.
enum class StepKind { Batched, Scalar };
StepKind step_kind(const Model& model, const BodyType& type, std::string* why_not_batched);
const char* step_kind_name(StepKind kind);

// Steps between outputs for a given output interval.
uint64_t output_stride(const Model& model, double every);

}  // namespace lrigid
