// The scalar step (integrate/integrators.h): the orientation stays a unit quaternion; noise
// substeps sum the finer steps' increments.
#include "integrate/integrators.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// Every orientation update multiplies by a unit quaternion and renormalizes (integrators.h):
// after a million steps of a tumbling body |q| - 1 and R^T R - I stay at round-off.
TEST(Kinematics, QuaternionStaysUnitOverAMillionSteps) {
  for (Integrator scheme : {Integrator::Euler, Integrator::RK4, Integrator::Splitting}) {
    Scene s = test::sphere_scene(1, 800, 1000, 1e-6);
    s.bodies[0].shape = Shape::ellipsoid(0.03, 0.02, 0.01);
    s.effects = EffectSet{};
    s.integrator = scheme;
    s.dt = 1e-3;
    s.duration = scheme == Integrator::RK4 ? 1000 : 300;  // 1e6 steps for rk4
    s.bodies[0].angular_velocity = Vec3(3, -2, 5);
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    EXPECT_LT(std::abs(st.q[0].norm() - 1.0), 1e-12) << integrator_name(scheme);
    const Mat3 R = st.q[0].toRotationMatrix();
    EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-12);
  }
}

// With noise_substeps = r, a step of r h sees the sum of the r increments a run with step h sees:
// the two runs follow the same Brownian path (what the strong-error study needs). For slow
// decay (alpha T << 1) the velocity is ~ beta W(T), so both runs must end close together,
// while a different seed ends far away.
TEST(BrownianPath, CoarseStepsSumTheFineIncrements) {
  for (Integrator scheme : {Integrator::Euler, Integrator::Splitting}) {
    auto final_velocity = [&](double dt, uint32_t r, uint64_t seed) {
      // 50 bodies of the "body" turbulence model at the origin, turbulence only
      Scene s = test::sphere_scene(0.001, 1000, 1000, 1e-6, 50);
      s.effects = test::effects({Effect::Turbulence});
      s.turbulence_model = TurbulenceModel::Body;
      s.drift = Drift::Stationary;
      s.integrator = scheme;
      s.dt = dt;
      s.uniform_k = 1.0;
      s.uniform_epsilon = 1e-3;  // alpha ~ 5e-3 1/s: over 1 s the path is ~ beta W
      s.seed = seed;
      s.duration = 1.0;
      Model m = test::compile(s);
      m.noise_substeps = r;
      State st = initial_state(m, s);
      simulate(m, &st, RunOptions{});
      return st;
    };
    const State coarse = final_velocity(0.04, 4, 9), fine = final_velocity(0.01, 1, 9),
                other = final_velocity(0.01, 1, 10);
    double same = 0, diff = 0;
    for (size_t i = 0; i < coarse.size(); ++i) {
      same = std::max(same, (coarse.u_seen[i] - fine.u_seen[i]).norm());
      diff = std::max(diff, (other.u_seen[i] - fine.u_seen[i]).norm());
    }
    EXPECT_LT(same, 0.02 * diff) << integrator_name(scheme);
  }
}

}  // namespace
}  // namespace lrigid
