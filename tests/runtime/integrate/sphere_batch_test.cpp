// Uniform spheres on the batched step (integrate/rigid_batch.h: its loops for an isotropic M)
// against the scalar step: the same scene run with model.batched on and off gives the same
// statuses, stop times and reasons, and states that differ by rounding only (double), or by what
// single precision costs (float).
#include "compile/compile_model.h"
#include "integrate/rigid_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "integrate/simulation.h"
#include "support/batch_compare.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using batch_test::Both;
using batch_test::count;
using batch_test::Diff;
using batch_test::farthest_apart;
using batch_test::run;
using batch_test::scalar_and_batched;
using batch_test::wind_grid;

// The body type takes the batched step, on its loops for an isotropic M
bool sphere_batch_eligible(const Model& model, const BodyType& type, std::string* why = nullptr) {
  if (!rigid_batch_eligible(model, type, why)) return false;
  if (batch_mass(type) == BatchMass::Isotropic) return true;
  if (why) *why = batch_mass_name(batch_mass(type));
  return false;
}

Scene bead_scene(double radius, double density, int count) {
  Scene s = test::sphere_scene(radius, density, 1.2, 1.5e-5, count);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow, Effect::Turbulence});
  batch_test::release_in_wind_grid(&s, 7);
  return s;
}

TEST(SphereBatch, BeadsInAGridMatchTheScalarStep) {
  // 300 bodies: 9 full blocks and one of 12
  const Scene s = bead_scene(2.5e-4, 2500, 300);
  const FluidField field = wind_grid(1.5e-5);
  ASSERT_TRUE(sphere_batch_eligible(test::compile(s, field), test::compile(s, field).types[0]));
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
  EXPECT_LT(d.x, 1e-9);
  EXPECT_LT(d.v, 1e-9);
  EXPECT_LT(d.w, 1e-9);
  EXPECT_LT(d.q, 1e-12);
  EXPECT_LT(d.u, 1e-9);
  // the scene exercises what it should: bodies moved by turbulence, some landed, some hit the
  // block or left the grid, some still moving
  EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u);
  EXPECT_GT(count(batched.state, BodyStatus::Landed) + count(batched.state, BodyStatus::Exited),
            0u);
  EXPECT_GT((batched.state.u_seen[0] - batched.state.u_seen[1]).norm(), 0.0);
}

// A sphere lane does not depend on how many lanes its block steps either
// (batch_test::expect_lanes_ignore_width).
TEST(SphereBatch, ALaneEndsTheSameWhateverHowManyLanesItsBlockSteps) {
  const FluidField field = wind_grid(1.5e-5);
  for (const Integrator scheme : {Integrator::Splitting, Integrator::Strang}) {
    for (const Precision p : {Precision::Double, Precision::Float}) {
      Scene s = bead_scene(2.5e-4, 2500, 32);
      s.integrator = scheme;
      batch_test::expect_lanes_ignore_width(s, field, p);
    }
  }
}

TEST(SphereBatch, BeadsInAGustingSeriesMatchTheScalarStep) {
  // a time-dependent field (four frames, batch_compare.h): blended samples and dU/dt
  const Scene s = bead_scene(2.5e-4, 2500, 100);
  const FluidField field = batch_test::gusty_wind_grid(1.5e-5);
  const Model m = test::compile(s, field);
  std::string why;
  ASSERT_TRUE(sphere_batch_eligible(m, m.types[0], &why)) << why;
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
  EXPECT_LT(d.x, 1e-9);
  EXPECT_LT(d.v, 1e-9);
  EXPECT_LT(d.u, 1e-9);
  // and with the strang scheme (its samples within the step take the same frames)
  Scene st = s;
  st.integrator = Integrator::Strang;
  const auto [scalar_s, batched_s, ds] = scalar_and_batched(st, field);
  EXPECT_EQ(scalar_s.stats.body_steps, batched_s.stats.body_steps);
  EXPECT_LT(ds.x, 1e-9);
  EXPECT_LT(ds.v, 1e-9);
  EXPECT_GT((scalar_s.state.x[0] - scalar.state.x[0]).norm(), 0.0);
}

TEST(SphereBatch, LightSpheresInAGustingSeriesFeelDUDt) {
  // bubbles-like light spheres with added mass: the fluid's acceleration dU/dt enters their
  // force (Kirchhoff's added-mass term); the batched step must carry it like the scalar step
  Scene s = test::sphere_scene(2e-3, 50, 1.2, 1.5e-5, 64);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow});
  batch_test::release_in_wind_grid(&s, 5);
  const FluidField field = batch_test::gusty_wind_grid(1.5e-5);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_LT(d.x, 1e-9);
  EXPECT_LT(d.v, 1e-9);
}

TEST(SphereBatch, WithoutTurbulenceBodiesExitWhereTheScalarStepExitsThem) {
  // a step that ends in the block or outside the grid exits the body at the step's start on
  // both steps (before, the scalar step without turbulence kept the end position: 4 of 64
  // bodies ended up to 5 mm apart)
  Scene s = test::sphere_scene(2e-3, 50, 1.2, 1.5e-5, 64);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow});
  batch_test::release_in_wind_grid(&s, 5);
  const FluidField field = wind_grid(1.5e-5);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_GE(count(batched.state, BodyStatus::Exited), 4u);
  EXPECT_LT(d.x, 1e-9);
  EXPECT_LT(d.v, 1e-9);
}

TEST(SphereBatch, StiffDragTakesTheNewtonPathLikeTheScalarStep) {
  // 20 um droplets, response time ~1 ms, dt 20 ms: the implicit drag iterates
  Scene s = bead_scene(2e-5, 1000, 100);
  s.dt = 0.02;
  s.duration = 2.0;
  const FluidField field = wind_grid(1.5e-5);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_LT(d.x, 1e-9);
  EXPECT_LT(d.v, 1e-9);
  EXPECT_LT(d.u, 1e-9);
  EXPECT_GT(batched.stats.newton_steps, batched.stats.body_steps / 2);  // the loops' Newton
  // stiff and stable: the droplets move with the air (|v| of order the wind, not blown up)
  for (size_t i = 0; i < batched.state.size(); ++i) {
    if (batched.state.status[i] == BodyStatus::Moving) {
      EXPECT_LT(batched.state.v[i].norm(), 10.0);
    }
  }
}

TEST(SphereBatch, LightSpheresInWaterWithAddedMassMatchTheScalarStep) {
  // bubbles-like light spheres in a uniform water flow: added mass dominates the inertia
  Scene s = test::sphere_scene(1e-3, 50, 1000, 1e-6, 64);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass,
                             Effect::MeanFlow, Effect::Turbulence});
  s.uniform_U = Vec3(0.2, 0, 0.05);
  s.uniform_k = 1e-3;
  s.uniform_epsilon = 1e-3;
  s.integrator = Integrator::Splitting;
  s.dt = 1e-3;
  s.duration = 0.5;
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_hi = Vec3(0.1, 0.1, 0.1);
  const FluidField field = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                               s.kinematic_viscosity, s.drift);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_LT(d.x, 1e-10);
  EXPECT_LT(d.v, 1e-10);
  EXPECT_LT(d.u, 1e-10);
  // they rise (buoyancy beats gravity 20 to 1)
  EXPECT_GT(batched.state.v[0].norm(), 0.05);
}

TEST(SphereBatch, BassetHistoryAndMagnusMatchTheScalarStep) {
  // all the sphere's effects: spinning beads in the wind grid (Magnus), and the same with stiff
  // drag (20 um droplets at 20 ms: the Newton iteration with the history's implicit mass)
  for (const bool stiff : {false, true}) {
    Scene s = stiff ? bead_scene(2e-5, 1000, 100) : bead_scene(2.5e-4, 2500, 150);
    if (stiff) s.dt = 0.02;
    s.effects.add(Effect::Basset);
    s.effects.add(Effect::Magnus);
    s.bodies[0].angular_velocity = Vec3(300, -150, 80);
    const FluidField field = wind_grid(1.5e-5);
    const Model m = test::compile(s, field);
    std::string why;
    ASSERT_TRUE(sphere_batch_eligible(m, m.types[0], &why)) << why;
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << stiff;
    EXPECT_LT(d.x, 1e-9) << stiff;
    EXPECT_LT(d.v, 1e-9) << stiff;
    EXPECT_LT(d.w, 1e-9) << stiff;
    EXPECT_LT(d.u, 1e-9) << stiff;
    // the two effects moved the beads: without them they end (or stop) elsewhere
    const double moved =
        batch_test::moved_by(s, field, batched, {Effect::Basset, Effect::Magnus});
    EXPECT_GT(moved, 1e-6) << stiff;
    std::printf("%s: Basset and Magnus move the beads by up to %.3g m\n",
                stiff ? "droplets" : "beads", moved);
  }
}

TEST(SphereBatch, EveryBatchedEffectOfTheRegistryIsAppliedByEveryScheme) {
  // spinning beads in the wind grid with every effect the registry says the loops implement
  // (lift does not apply to a sphere), in each scheme (batch_compare.h)
  Scene s = bead_scene(2.5e-4, 2500, 32);
  s.bodies[0].angular_velocity = Vec3(300, -150, 80);
  s.dt = 5e-4;
  s.duration = 0.3;
  batch_test::expect_every_batched_effect_applied(s, wind_grid(1.5e-5), 1e-9,
                                                  sphere_batch_eligible);
}

TEST(SphereBatch, StrangMatchesTheScalarStep) {
  // the Strang scheme on the loops and on the scalar step: spinning beads in the wind grid
  // (Magnus, seen turbulence), stiff droplets at 20 ms (ROS2, no Newton), and light spheres in
  // a uniform water flow (added mass)
  for (int c = 0; c < 3; ++c) {
    Scene s = c == 1 ? bead_scene(2e-5, 1000, 100) : bead_scene(2.5e-4, 2500, 150);
    FluidField field = wind_grid(1.5e-5);
    if (c == 1) s.dt = 0.02;
    if (c < 2) {
      s.effects.add(Effect::Magnus);
      s.bodies[0].angular_velocity = Vec3(300, -150, 80);
    } else {
      s = test::sphere_scene(1e-3, 50, 1000, 1e-6, 64);
      s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag,
                                 Effect::AddedMass, Effect::MeanFlow, Effect::Turbulence});
      s.uniform_U = Vec3(0.2, 0, 0.05);
      s.uniform_k = 1e-3;
      s.uniform_epsilon = 1e-3;
      s.dt = 1e-3;
      s.duration = 0.5;
      s.bodies[0].spawn_in_box = true;
      s.bodies[0].box_hi = Vec3(0.1, 0.1, 0.1);
      field = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                  s.kinematic_viscosity, s.drift);
    }
    s.integrator = Integrator::Strang;
    const Model m = test::compile(s, field);
    std::string why;
    ASSERT_TRUE(sphere_batch_eligible(m, m.types[0], &why)) << why;
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << c;
    EXPECT_LT(d.x, 1e-9) << c;
    EXPECT_LT(d.v, 1e-9) << c;
    EXPECT_LT(d.w, 1e-9) << c;
    EXPECT_LT(d.u, 1e-9) << c;
    EXPECT_EQ(batched.stats.scalar_handoffs, 0u) << c;
    // not the splitting scheme: with it the spheres end elsewhere
    Scene split = s;
    split.integrator = Integrator::Splitting;
    const batch_test::Outcome o = batch_test::run(split, field, true, Precision::Double);
    const double apart = farthest_apart(o, batched);
    EXPECT_GT(apart, 1e-9) << c;
    std::printf("strang spheres %d: scalar vs batched |dx| %.2e, strang vs splitting %.2e m\n", c,
                d.x, apart);
  }
}

TEST(SphereBatch, EulerAndRk4MatchTheScalarStep) {
  // the explicit schemes (integrators.h euler, rk4; rigid_batch_explicit.h) on the loops and on
  // the scalar step: beads in the wind grid with seen turbulence, then spinning with the Basset
  // history and Magnus too, and light spheres in a uniform water flow (added mass, velocity form
  // in rk4's stages)
  for (const Integrator scheme : {Integrator::Euler, Integrator::RK4}) {
    for (int c = 0; c < 3; ++c) {
      Scene s = bead_scene(2.5e-4, 2500, 150);
      FluidField field = wind_grid(1.5e-5);
      if (c == 1) {
        s.effects.add(Effect::Basset);
        s.effects.add(Effect::Magnus);
        s.bodies[0].angular_velocity = Vec3(300, -150, 80);
      } else if (c == 2) {
        s = test::sphere_scene(1e-3, 50, 1000, 1e-6, 64);
        s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag,
                                   Effect::AddedMass, Effect::MeanFlow, Effect::Turbulence});
        s.uniform_U = Vec3(0.2, 0, 0.05);
        s.uniform_k = 1e-3;
        s.uniform_epsilon = 1e-3;
        s.dt = 1e-3;
        s.duration = 0.5;
        s.bodies[0].spawn_in_box = true;
        s.bodies[0].box_hi = Vec3(0.1, 0.1, 0.1);
        s.bodies[0].angular_velocity = Vec3(3, -1, 2);
        field = FluidField::uniform(s.uniform_U, s.uniform_k, s.uniform_epsilon,
                                    s.kinematic_viscosity, s.drift);
      }
      s.integrator = scheme;
      const Model m = test::compile(s, field);
      std::string why;
      ASSERT_TRUE(sphere_batch_eligible(m, m.types[0], &why)) << why;
      const auto [scalar, batched, d] = scalar_and_batched(s, field);
      const char* name = scheme == Integrator::Euler ? "euler" : "rk4";
      EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << name << " " << c;
      EXPECT_LT(d.x, 1e-9) << name << " " << c;
      EXPECT_LT(d.u, 1e-9) << name << " " << c;
      // the world velocity to 1e-9 m/s; the spin, the orientation and the body-frame velocity
      // (the world one turned by q) carry the scalar step's spin of rounding noise: for a
      // sphere the moments v x m v and v_r x m_a v_r (rk4's gyroscopic and added-mass terms,
      // euler's -v_r x P_f) vanish only to round-off there, and a 0.25 mm bead's
      // J = 4e-15 kg m^2 turns that into ~5e-10 rad/s after 1 s (beads released without spin;
      // the loops leave these moments out for an isotropic M, rigid_batch_explicit.h)
      double dV = 0;
      for (size_t i = 0; i < scalar.state.size(); ++i)
        dV = std::max(dV, (scalar.state.q[i] * scalar.state.v[i] -
                           batched.state.q[i] * batched.state.v[i]).norm());
      EXPECT_LT(dV, 1e-9) << name << " " << c;
      EXPECT_LT(d.w, 1e-8) << name << " " << c;
      if (c == 0) {
        // without those moments a sphere released without spin keeps none
        double spin = 0;
        for (const Vec3& w : batched.state.w) spin = std::max(spin, w.norm());
        EXPECT_EQ(spin, 0.0) << name;
      }
      EXPECT_LT(d.q, 1e-9) << name << " " << c;
      EXPECT_LT(d.v, 1e-8) << name << " " << c;
      // the loops take the steps themselves (rk4 hands over a lane whose stage left the fluid)
      EXPECT_LE(batched.stats.scalar_handoffs, batched.stats.body_steps / 1000)
          << name << " " << c;
      EXPECT_GT(batched.stats.body_steps, 100u * s.bodies[0].count) << name << " " << c;
      EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u) << name << " " << c;
      // and it is the scheme asked for: splitting ends elsewhere
      Scene split = s;
      split.integrator = Integrator::Splitting;
      const batch_test::Outcome o = run(split, field, true, Precision::Double);
      const double apart = farthest_apart(o, batched);
      EXPECT_GT(apart, 1e-6) << name << " " << c;
      std::printf("%s spheres %d: scalar vs batched |dx| %.2e |dV| %.2e |dw| %.2e, vs "
                  "splitting %.2e m, %llu of %llu steps handed to the scalar step\n",
                  name, c, d.x, dV, d.w, apart,
                  static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                  static_cast<unsigned long long>(batched.stats.body_steps));
    }
  }
}

TEST(SphereBatch, Rk4InAGustingSeriesMatchesTheScalarStep) {
  // rk4's stages sample a time-dependent field at their own times (t + h/2, t + h), as the
  // scalar step does; euler samples at the start only. Beads with seen turbulence, and light
  // spheres whose added mass feels dU/dt (rk4's drag-along K (R^T Du/Dt - w x u_f))
  for (const Integrator scheme : {Integrator::Euler, Integrator::RK4}) {
    for (const bool light : {false, true}) {
      Scene s = bead_scene(2.5e-4, 2500, 100);
      if (light) {
        s = test::sphere_scene(2e-3, 50, 1.2, 1.5e-5, 64);
        s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag,
                                   Effect::AddedMass, Effect::MeanFlow});
        batch_test::release_in_wind_grid(&s, 5);
      }
      s.integrator = scheme;
      s.dt = 1e-3;
      s.duration = 0.5;
      const FluidField field = batch_test::gusty_wind_grid(1.5e-5);
      ASSERT_EQ(field.frame_count(), 4u);
      const Model m = test::compile(s, field);
      std::string why;
      ASSERT_TRUE(sphere_batch_eligible(m, m.types[0], &why)) << why;
      const auto [scalar, batched, d] = scalar_and_batched(s, field);
      const char* name = scheme == Integrator::Euler ? "euler" : "rk4";
      EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << name << " " << light;
      EXPECT_LT(d.x, 1e-9) << name << " " << light;
      EXPECT_LT(d.v, 1e-9) << name << " " << light;
      EXPECT_LT(d.u, 1e-9) << name << " " << light;
      EXPECT_LE(batched.stats.scalar_handoffs, batched.stats.body_steps / 1000) << name;
      std::printf("%s %s in the gusting series: scalar vs batched |dx| %.2e |v| %.2e\n", name,
                  light ? "light spheres" : "beads", d.x, d.v);
    }
  }
}

TEST(SphereBatch, SpheresInFluidAtRestMatchTheScalarStep) {
  // no effect samples the field (gravity and drag, or nothing at all): the fluid is at rest
  for (const EffectSet& e : {test::effects({Effect::Gravity, Effect::Drag}), test::effects({})}) {
    Scene s = test::sphere_scene(0.01, 500, 1000, 1e-6, 40);
    s.effects = e;
    s.integrator = Integrator::Splitting;
    s.dt = 0.01;
    s.duration = 1.0;
    s.bodies[0].velocity = Vec3(0.3, 0.0, -0.2);
    s.bodies[0].angular_velocity = Vec3(1.0, 2.0, 0.5);
    const FluidField field =
        FluidField::uniform(Vec3::Zero(), 0, 0, s.kinematic_viscosity, s.drift);
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_LT(d.x, 1e-12);
    EXPECT_LT(d.v, 1e-12);
    EXPECT_LT(d.q, 1e-12);
    for (size_t i = 0; i < batched.state.size(); ++i) {
      EXPECT_EQ(batched.state.status[i], BodyStatus::Moving) << "body " << i;
      // the spin turned the sphere (about 2.3 rad in 1 s)
      EXPECT_GT(batched.state.q[i].angularDistance(Quat::Identity()), 1.0) << "body " << i;
    }
  }
}

TEST(SphereBatch, IdenticalForAnyThreadCount) {
  const Scene s = bead_scene(2.5e-4, 2500, 200);
  const FluidField field = wind_grid(1.5e-5);
  const batch_test::Outcome one = run(s, field, true, Precision::Double, 1);
  const batch_test::Outcome two = run(s, field, true, Precision::Double, 2);
  const Diff d = compare(one, two);
  EXPECT_EQ(d.x, 0.0);
  EXPECT_EQ(d.t, 0.0);
  EXPECT_EQ(d.v, 0.0);
  EXPECT_EQ(d.q, 0.0);
  EXPECT_EQ(d.u, 0.0);
}

TEST(SphereBatch, NonFiniteStateFailsWithTheScalarStepsReason) {
  const Scene s = bead_scene(2.5e-4, 2500, 40);
  const FluidField field = wind_grid(1.5e-5);
  batch_test::Outcome r[2];
  for (int b = 0; b < 2; ++b) {
    Model m = test::compile(s, field);
    m.batched = b == 1;
    r[b].state = initial_state(m, s);
    // a non-finite spin leaves the position (and the sample) finite: the orientation fails
    r[b].state.w[3] = Vec3(std::nan(""), 0, 0);
    r[b].stats = simulate(m, &r[b].state, RunOptions{});
  }
  // both fail the body at the same step with the same reason: the scalar step (body-frame
  // velocity, rotated with the orientation) and the batched one (whose Magnus term, zero for
  // beads, multiplies the non-finite spin) both reach a non-finite position, which fails the
  // body before it could count as outside the grid
  for (int b = 0; b < 2; ++b) {
    EXPECT_EQ(r[b].state.status[3], BodyStatus::Failed);
    EXPECT_EQ(r[b].state.t_stop[3], 0.0);
    EXPECT_EQ(r[b].state.reason[3], "non-finite position") << (b ? "batched" : "scalar");
  }
  // the other bodies of the block went on
  for (size_t i = 0; i < r[0].state.size(); ++i) {
    if (i == 3) continue;
    EXPECT_EQ(r[0].state.status[i], r[1].state.status[i]) << "body " << i;
    EXPECT_LT((r[0].state.x[i] - r[1].state.x[i]).norm(), 1e-9) << "body " << i;
  }
}

TEST(SphereBatch, FloatCostsLittleAccuracy) {
  // every scheme's loops in single precision (euler and rk4: rigid_batch_explicit.h)
  for (const Integrator scheme :
       {Integrator::Splitting, Integrator::Strang, Integrator::Euler, Integrator::RK4}) {
    Scene s = bead_scene(2.5e-4, 2500, 300);
    s.integrator = scheme;
    const FluidField field = wind_grid(1.5e-5);
    const batch_test::Outcome dbl = run(s, field, true, Precision::Double);
    const batch_test::Outcome flt = run(s, field, true, Precision::Float);
    // the same bodies keep moving; positions after 1 s (of up to ~5 m travel) agree to well
    // below a millimetre where both still move
    const auto [same, dx] = batch_test::float_vs_double(dbl, flt, true);
    EXPECT_GE(same, dbl.state.size() - 3) << int(scheme);
    EXPECT_LT(dx, 1e-4) << int(scheme);
    std::printf("scheme %d: float vs double |dx| %.3g m, %zu of %zu alike\n", int(scheme), dx,
                same, dbl.state.size());
    EXPECT_GT(dx, 0.0) << int(scheme);  // single precision really ran
  }
}

TEST(SphereBatch, EligibilitySaysWhatExcludesABodyType) {
  const Scene s = bead_scene(2.5e-4, 2500, 1);
  const FluidField field = wind_grid(1.5e-5);
  std::string why;
  const Model ok = test::compile(s, field);
  EXPECT_TRUE(sphere_batch_eligible(ok, ok.types[0], &why));
  // lift has no term for a body that is not flat: listing it leaves the sphere on the batched
  // step (the effects registry, effects/registry.cpp, says every effect has a batched kernel)
  Scene with_lift = s;
  with_lift.effects.add(Effect::Lift);
  const Model lifted = test::compile(with_lift, field);
  EXPECT_TRUE(sphere_batch_eligible(lifted, lifted.types[0], &why)) << why;
  // every scheme runs on it (euler and rk4: rigid_batch_explicit.h)
  for (const Integrator scheme :
       {Integrator::Euler, Integrator::RK4, Integrator::Splitting, Integrator::Strang}) {
    Scene e = s;
    e.integrator = scheme;
    const Model me = test::compile(e, field);
    EXPECT_TRUE(sphere_batch_eligible(me, me.types[0], &why)) << why;
  }
  batch_test::expect_exclusions(
      s, field, sphere_batch_eligible,
      {
          // batched, on the loops of a diagonal M
          {[](Scene& e) { e.bodies[0].shape = Shape::ellipsoid(3e-4, 2.5e-4, 2e-4); },
           "diagonal M"},
          {[](Scene& e) { e.turbulence_model = TurbulenceModel::Body; },
           "the body turbulence model"},
          {[](Scene& e) { e.batched = false; }, "the scene turns the batched step off"},
      });
  // a sphere whose centre of mass is off its centroid is batched, not on the isotropic loops
  // (its fluid forces act at the centroid, rigid_batch_test.cpp)
  Scene offset = s;
  offset.bodies[0].mass_offset = Vec3(0, 0, -5e-5);
  const Model mo = test::compile(offset, field);
  EXPECT_TRUE(rigid_batch_eligible(mo, mo.types[0], &why)) << why;
  EXPECT_NE(batch_mass(mo.types[0]), BatchMass::Isotropic);
}

}  // namespace
}  // namespace lrigid
