// A guard against silent de-vectorization: the leaves scene's body types (scenes/leaves_wind.json:
// leaves, paper, seed pods) with the scene's effects, and the beads scene's spheres on euler and
// rk4, in the wind grid of the batched-step tests, stepped on the batched step and on the scalar
// step in one run. The batched step must do at least 4 times the body-steps per CPU-second of
// the scalar step. If a change made the loops stop vectorizing, or sent the body types to the
// scalar step (a missing kernel, an eligibility rule), the ratio falls towards 1 and this fails.
//
// Robust to a noisy machine: CPU time of this thread (time other jobs take is not counted), the
// two steps measured alternately three times each, the best of each kept. Not a timing assertion
// in seconds: a ratio of two measurements made side by side (docs/batched-step.md).
#include <gtest/gtest.h>
#include <time.h>

#include <algorithm>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "compile/compile_model.h"
#include "integrate/rigid_batch.h"
#include "integrate/simulation.h"
#include "io/scene_json.h"
#include "support/batch_compare.h"

namespace lrigid {
namespace {

constexpr double kMinRatio = 4.0;

double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// body-steps per CPU-second of `steps` steps from `initial`, one thread
double rate(Model m, const State& initial, int steps) {
  State st = initial;
  RunOptions opt;
  opt.threads = 1;
  opt.every = 1e9;
  m.duration = double(steps) * m.dt;
  const double t0 = thread_cpu_seconds();
  const RunStats r = simulate(m, &st, opt);
  const double cpu = thread_cpu_seconds() - t0;
  EXPECT_GT(r.body_steps, uint64_t(steps) * st.size() / 2) << "most bodies must keep moving";
  return double(r.body_steps) / cpu;
}

// The leaves scene's body types in the test wind grid, 1024 of each, with the effects "auto"
// keeps for leaves in the wind, compiled for `scheme`
Model leaves_model(Integrator scheme, Scene* scene) {
  // the scene's own file, with its fluid made uniform before parsing: its grid comes from
  // OpenFOAM (./Allrun) and need not exist when the unit tests run
  const std::string path = std::string(LRIGID_SOURCE_DIR) + "/scenes/leaves_wind.json";
  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  j["fluid"].erase("field");
  j["fluid"]["uniform"] = {{"U", {0, 0, 0}}, {"k", 0}, {"epsilon", 0}};
  Scene s = parse_scene(j.dump(), path);
  // the scene's bodies in the test wind grid (the shipped grid comes from OpenFOAM), 1024 of each
  // type, with the effects "auto" keeps for leaves in the wind
  batch_test::release_in_wind_grid(&s, 3);
  s.effects_auto = false;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Lift,
                             Effect::AddedMass, Effect::MeanFlow, Effect::Turbulence});
  for (BodySpec& b : s.bodies) {
    b.count = 1024;
    b.spawn_in_box = true;
    b.box_lo = Vec3(-5, -3, 2.5);
    b.box_hi = Vec3(-1.5, 3, 3);
  }
  s.integrator = scheme;
  // the step alone: with contacts between bodies every body is stepped one step at a time
  s.body_contact = false;
  *scene = s;
  return test::compile(s, batch_test::wind_grid(s.kinematic_viscosity));
}

TEST(VectorizationGuard, BatchedStepIsAtLeastFourTimesTheScalarStepOnTheLeavesScene) {
  Scene s;
  Model batched = leaves_model(Integrator::Splitting, &s);
  for (const BodyType& t : batched.types) {
    std::string why;
    EXPECT_NE(step_kind(batched, t, &why), StepKind::Scalar) << t.name << ": " << why;
  }
  Model scalar = batched;
  scalar.batched = false;
  const State initial = initial_state(batched, s);
  double best_batched = 0, best_scalar = 0;
  rate(batched, initial, 2);  // warm the caches
  for (int round = 0; round < 3; ++round) {
    best_scalar = std::max(best_scalar, rate(scalar, initial, 10));
    best_batched = std::max(best_batched, rate(batched, initial, 40));
  }
  const double ratio = best_batched / best_scalar;
  std::printf("batched %.3g, scalar %.3g body-steps per CPU-second: ratio %.2f (%s loops)\n",
              best_batched, best_scalar, ratio, batch_isa());
  EXPECT_GE(ratio, kMinRatio);
}

TEST(VectorizationGuard, EulerAndRk4OnTheBatchedStep) {
  // the explicit schemes on the batched step (rigid_batch_explicit.h), in one run beside the
  // splitting scheme's batched step and their own scalar steps: each at least four times its
  // scalar step, and euler (one force evaluation, no iteration) at least as fast as a third of
  // splitting
  const Integrator schemes[3] = {Integrator::Splitting, Integrator::Euler, Integrator::RK4};
  const char* names[3] = {"splitting", "euler", "rk4"};
  double best_batched[3] = {0, 0, 0}, best_scalar[3] = {0, 0, 0};
  Scene s;
  for (int k = 0; k < 3; ++k) {
    Model batched = leaves_model(schemes[k], &s);
    for (const BodyType& t : batched.types) {
      std::string why;
      EXPECT_NE(step_kind(batched, t, &why), StepKind::Scalar) << t.name << ": " << why;
    }
    Model scalar = batched;
    scalar.batched = false;
    const State initial = initial_state(batched, s);
    rate(batched, initial, 2);  // warm the caches
    for (int round = 0; round < 3; ++round) {
      best_scalar[k] = std::max(best_scalar[k], rate(scalar, initial, 10));
      best_batched[k] = std::max(best_batched[k], rate(batched, initial, 40));
    }
    std::printf("%s: batched %.3g, scalar %.3g body-steps per CPU-second: ratio %.2f (%s loops)\n",
                names[k], best_batched[k], best_scalar[k], best_batched[k] / best_scalar[k],
                batch_isa());
  }
  for (int k = 1; k < 3; ++k) EXPECT_GE(best_batched[k] / best_scalar[k], kMinRatio) << names[k];
  EXPECT_GE(best_batched[1], best_batched[0] / 3) << "euler against splitting, batched";
}

// The beads scene's spheres (scenes/beads_wind.json: 0.5 mm glass beads with gravity, buoyancy,
// drag, added mass, mean flow and seen turbulence) in the test wind grid, 2048 of them,
// compiled for `scheme`
Model beads_model(Integrator scheme, Scene* scene) {
  Scene s = test::sphere_scene(2.5e-4, 2500, 1.204, 1.5e-5, 2048);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow, Effect::Turbulence});
  batch_test::release_in_wind_grid(&s, 3);
  s.bodies[0].box_lo = Vec3(-5, -3, 2.5);
  s.bodies[0].box_hi = Vec3(-1.5, 3, 3);
  s.integrator = scheme;
  *scene = s;
  return test::compile(s, batch_test::wind_grid(s.kinematic_viscosity));
}

TEST(VectorizationGuard, EulerAndRk4OnTheBatchedSphereStep) {
  // the explicit schemes on the batched step's loops for an isotropic M (rigid_batch_explicit.h),
  // each against its own scalar step in one run: at least four times it
  const Integrator schemes[2] = {Integrator::Euler, Integrator::RK4};
  const char* names[2] = {"euler", "rk4"};
  for (int k = 0; k < 2; ++k) {
    Scene s;
    Model batched = beads_model(schemes[k], &s);
    std::string why;
    EXPECT_EQ(step_kind(batched, batched.types[0], &why), StepKind::Batched) << why;
    EXPECT_EQ(batch_mass(batched.types[0]), BatchMass::Isotropic);
    Model scalar = batched;
    scalar.batched = false;
    const State initial = initial_state(batched, s);
    double best_batched = 0, best_scalar = 0;
    rate(batched, initial, 2);  // warm the caches
    for (int round = 0; round < 3; ++round) {
      best_scalar = std::max(best_scalar, rate(scalar, initial, 10));
      best_batched = std::max(best_batched, rate(batched, initial, 40));
    }
    std::printf("%s spheres: batched %.3g, scalar %.3g body-steps per CPU-second: ratio %.2f "
                "(%s loops)\n",
                names[k], best_batched, best_scalar, best_batched / best_scalar,
                batch_isa());
    EXPECT_GE(best_batched / best_scalar, kMinRatio) << names[k];
  }
}

}  // namespace
}  // namespace lrigid
