// The step's shortcuts for structured generalized mass matrices (element-wise M^-1 when M is
// diagonal, two 3x3 solves when it is block diagonal) give the general 6x6 path's result.
#include <gtest/gtest.h>

#include <string>

#include "integrate/integrators.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// a paper-like box in a uniform turbulent wind, every effect the splitting step handles
Scene sheet_scene(Integrator integrator) {
  Scene s = test::sphere_scene(0.01, 800, 1.2, 1.5e-5);
  s.bodies[0].shape = Shape::box(0.148, 0.105, 0.001);
  s.bodies[0].panels = 200;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag,
                             Effect::Lift, Effect::MeanFlow, Effect::Turbulence});
  s.uniform_U = Vec3(2.0, 0.5, 0);
  s.uniform_k = 0.5, s.uniform_epsilon = 0.2;
  s.integrator = integrator;
  s.dt = 0.004;
  return s;
}

BodyState start() {
  BodyState b;
  b.x = Vec3::Zero();
  b.q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  b.v = Vec3(0.3, -0.2, -0.8);
  b.w = Vec3(2.0, -1.0, 4.0);
  b.u_seen = Vec3(0.2, 0.1, -0.3);
  return b;
}

void run(const Model& m, BodyState* b, int steps) {
  for (int k = 0; k < steps; ++k) {
    std::string reason;
    ASSERT_EQ(step_body(m, m.types[0], 0, k, k * m.dt, b, &reason), StepOutcome::Ok) << reason;
  }
}

// 200 steps of the same body with both models from the same start: the same motion up to the
// order of operations (round-off, grown over the steps); tol for x, v, q (m, m/s, 1), 10 tol for w
void expect_same_motion(const Model& fast, const Model& general, double tol) {
  BodyState a = start(), b = start();
  run(fast, &a, 200);
  run(general, &b, 200);
  EXPECT_TRUE(test::near(a.x, b.x, tol));
  EXPECT_TRUE(test::near(a.v, b.v, tol));
  EXPECT_TRUE(test::near(a.w, b.w, 10 * tol));
  EXPECT_TRUE(test::near(a.q.coeffs(), b.q.coeffs(), tol));
}

TEST(MassPaths, DiagonalAndBlockShortcutsMatchTheGeneralPath) {
  for (Integrator integ : {Integrator::Splitting, Integrator::Euler, Integrator::RK4}) {
    SCOPED_TRACE(integrator_name(integ));
    const Model fast = test::compile(sheet_scene(integ));
    ASSERT_TRUE(fast.types[0].M_diagonal);
    ASSERT_TRUE(fast.types[0].M_block_diagonal);
    Model general = fast;
    general.types[0].M_diagonal = false;
    general.types[0].M_block_diagonal = false;
    expect_same_motion(fast, general, 1e-9);
  }
}

TEST(MassPaths, SphereClosedFormKirchhoffFlowMatchesTheIteration) {
  // a light spinning sphere in a turbulent wind: M = diag(m, m, m, J, J, J), the free flow in
  // closed form against the general midpoint iteration
  Scene s = test::sphere_scene(0.01, 50, 1000, 1e-6);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag,
                             Effect::MeanFlow, Effect::Turbulence, Effect::Magnus});
  s.uniform_U = Vec3(0.3, 0.1, 0);
  s.uniform_k = 1e-3, s.uniform_epsilon = 1e-4;
  s.dt = 0.004;
  const Model fast = test::compile(s);
  ASSERT_TRUE(fast.types[0].M_isotropic);
  Model general = fast;
  general.types[0].M_isotropic = false;
  expect_same_motion(fast, general, 1e-10);
  // and not every diagonal M is isotropic
  EXPECT_FALSE(test::compile(sheet_scene(Integrator::Splitting)).types[0].M_isotropic);
}

TEST(MassPaths, ShortcutsApplyTheSameMatrices) {
  const Model m = test::compile(sheet_scene(Integrator::Splitting));
  const BodyType& t = m.types[0];
  const Vec6 y = (Vec6() << 1, -2, 3, 0.5, -0.25, 0.125).finished();
  EXPECT_TRUE(test::near(t.M_inv_times(y), Vec6(t.M_inv * y), 1e-12 * (t.M_inv * y).norm()));
  EXPECT_TRUE(test::near(t.M_times(y), Vec6(t.M * y), 1e-15 * (t.M * y).norm()));
}

}  // namespace
}  // namespace lrigid
