// The batched step for plates and ellipsoids (integrate/rigid_batch.h) against the scalar step it
// replaces: the same scene run with model.batched on and off gives the same statuses, stop times
// and reasons, and states that differ by rounding only (double), or by what single precision
// costs (float). Lanes the loops hand to the scalar step (slow Kirchhoff iteration, stiff drag)
// are part of it.
#include "integrate/rigid_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "integrate/simulation.h"
#include "support/batch_compare.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using batch_test::count;
using batch_test::Diff;
using batch_test::farthest_apart;
using batch_test::run;
using batch_test::scalar_and_batched;
using batch_test::wind_grid;

// count bodies of `shape` released in the wind grid with the leaves scene's effects
Scene rigid_scene(const Shape& shape, double density, int count) {
  Scene s = test::sphere_scene(0.01, density, 1.2, 1.5e-5, count);
  s.bodies[0].shape = shape;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Lift,
                             Effect::AddedMass, Effect::MeanFlow, Effect::Turbulence});
  batch_test::release_in_wind_grid(&s, 11);
  return s;
}

void expect_close(const Diff& d, double tol) {
  EXPECT_LT(d.x, tol);
  EXPECT_LT(d.v, tol);
  EXPECT_LT(d.w, tol);
  EXPECT_LT(d.q, tol);
  EXPECT_LT(d.u, tol);
}

void expect_eligible(const Scene& s, const FluidField& field) {
  const Model m = test::compile(s, field);
  std::string why;
  EXPECT_TRUE(rigid_batch_eligible(m, m.types[0], &why)) << why;
  EXPECT_NE(batch_mass(m.types[0]), BatchMass::Isotropic);  // the diagonal or the full loops
}

TEST(RigidBatch, LeavesInAGridMatchTheScalarStep) {
  // leaf-sized rectangles (plate drag, APW torque, lift, added mass): 7 full blocks and one of 20
  const Scene s = rigid_scene(Shape::box(0.06, 0.04, 4e-4), 600, 244);
  const FluidField field = wind_grid(1.5e-5);
  expect_eligible(s, field);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
  // rounding grows in the leaves' tumbling (up to tens of rad/s) to about 1e-9
  expect_close(d, 1e-8);
  // the scene exercises what it should: the leaves turn, some landed or hit the block, some
  // still move
  EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u);
  EXPECT_GT(count(batched.state, BodyStatus::Landed) + count(batched.state, BodyStatus::Exited),
            0u);
  double turned = 0;
  for (size_t i = 0; i < batched.state.size(); ++i)
    turned = std::max(turned, batched.state.w[i].norm());
  EXPECT_GT(turned, 1.0);  // rad/s
  // the loops advance the leaves themselves (the hard lanes of the next test aside)
  EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / 100);
  std::printf("leaves: %llu of %llu steps handed to the scalar step\n",
              static_cast<unsigned long long>(batched.stats.scalar_handoffs),
              static_cast<unsigned long long>(batched.stats.body_steps));
}

TEST(RigidBatch, LeavesInAGustingSeriesMatchTheScalarStep) {
  // a time-dependent field (four frames): the lanes blend two frames at each sample's time and
  // add dU/dt to the mean flow's acceleration, as FluidField::sample does
  const Scene s = rigid_scene(Shape::box(0.06, 0.04, 4e-4), 600, 100);
  const FluidField field = batch_test::gusty_wind_grid(1.5e-5);
  ASSERT_EQ(field.frame_count(), 4u);
  expect_eligible(s, field);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
  expect_close(d, 1e-8);
  EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / 100);
  // the gusts matter: the same leaves in the first frame alone end elsewhere
  const FluidField steady = wind_grid(1.5e-5);
  const batch_test::Outcome first = run(s, steady, true, Precision::Double, 1);
  const double apart = farthest_apart(first, batched);
  EXPECT_GT(apart, 0.05);  // m
}

TEST(RigidBatch, EllipsoidsAndDisksMatchTheScalarStep) {
  // a seed pod (prolate, not flat: ellipsoid drag) and a disk (flat: the ellipse's chord)
  for (const Shape& shape :
       {Shape::ellipsoid(0.004, 0.002, 0.002), Shape::ellipsoid(0.015, 0.01, 6e-4)}) {
    const Scene s = rigid_scene(shape, 500, 100);
    const FluidField field = wind_grid(1.5e-5);
    expect_eligible(s, field);
    const Model m = test::compile(s, field);
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
    // the disks tumble (their pitch-rate terms take the finite span, effects/plate.h), which
    // grows the rounding as in the leaves' test above (measured 1.2e-8 rad/s in w);
    // the pods stay below 1e-9
    expect_close(d, m.types[0].flat ? 1e-7 : 1e-9);
    // they flew for a while (50 steps on average) and some landed
    EXPECT_GT(batched.stats.body_steps, 50u * s.bodies[0].count) << m.types[0].flat;
    EXPECT_GT(count(batched.state, BodyStatus::Landed), 0u) << m.types[0].flat;
  }
}

TEST(RigidBatch, AllNineEffectsMatchTheScalarStep) {
  // with the Basset history and the Magnus force too: leaves (plates) and seed pods (ellipsoids)
  for (const Shape& shape : {Shape::box(0.06, 0.04, 4e-4), Shape::ellipsoid(0.004, 0.002, 0.002)}) {
    Scene s = rigid_scene(shape, 600, 100);
    s.effects.add(Effect::Basset);
    s.effects.add(Effect::Magnus);
    s.bodies[0].angular_velocity = Vec3(5, 20, -10);
    const FluidField field = wind_grid(1.5e-5);
    expect_eligible(s, field);
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
    expect_close(d, 1e-8);
    // the loops take every step themselves: the pods' free Kirchhoff flow needs Newton on some
    // (the fixed point does not contract: 473 of these steps went to the scalar step before the
    // loops had their own Newton)
    EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / 1000);
    if (shape.type == ShapeType::Ellipsoid) {
      EXPECT_GT(batched.stats.newton_steps, 0u);
    }
    // the two effects change the motion: without them the bodies end (or stop) elsewhere
    const double moved =
        batch_test::moved_by(s, field, batched, {Effect::Basset, Effect::Magnus});
    EXPECT_GT(moved, 1e-6);
    std::printf("all nine effects: %llu Newton steps, %llu of %llu steps handed to the scalar "
                "step; Basset and Magnus move the bodies by up to %.3g m\n",
                static_cast<unsigned long long>(batched.stats.newton_steps),
                static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                static_cast<unsigned long long>(batched.stats.body_steps), moved);
  }
}

TEST(RigidBatch, EveryBatchedEffectOfTheRegistryIsAppliedByEveryScheme) {
  // spinning disks (flat: the plate's force stage) and seed pods (the ellipsoid's) in the wind
  // grid with every effect the registry says the loops implement, in each scheme
  // (batch_compare.h)
  for (const Shape& shape :
       {Shape::ellipsoid(0.015, 0.01, 6e-4), Shape::ellipsoid(0.004, 0.002, 0.002)}) {
    Scene s = rigid_scene(shape, 600, 32);
    s.bodies[0].angular_velocity = Vec3(5, 20, -10);
    s.dt = 5e-4;  // (euler's limit for the light disks)
    s.duration = 0.3;
    batch_test::expect_every_batched_effect_applied(s, wind_grid(1.5e-5), 1e-8,
                                                    rigid_batch_eligible);
  }
}

TEST(RigidBatch, StrangMatchesTheScalarStep) {
  // the Strang scheme (integrator "strang": force half steps around the free flow) on the loops
  // and on the scalar step: leaves (plate drag and lift) with Magnus, and seed pods, in the wind
  // grid with seen turbulence, a short flight; then light cards at a coarse step (stiff drag:
  // ROS2 takes it without Newton)
  for (const Shape& shape : {Shape::box(0.06, 0.04, 4e-4), Shape::ellipsoid(0.004, 0.002, 0.002)}) {
    for (const double dt : {2e-3, 2e-2}) {
      Scene s = rigid_scene(shape, dt > 1e-2 ? 500 : 600, 100);
      s.integrator = Integrator::Strang;
      s.dt = dt;
      s.duration = 0.3;
      s.effects.add(Effect::Magnus);
      s.bodies[0].angular_velocity = Vec3(5, 20, -10);
      const FluidField field = wind_grid(1.5e-5);
      expect_eligible(s, field);
      const auto [scalar, batched, d] = scalar_and_batched(s, field);
      EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
      expect_close(d, 1e-9);
      // at 20 ms the free flow of some fast-spinning lanes needs the scalar step's substeps
      // (as with splitting: HardLanesGoToTheScalarStepAndStillMatch)
      EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / (dt > 1e-2 ? 20 : 100));
      EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u);
      // and it is not the splitting scheme: the same scene with splitting ends elsewhere
      Scene split = s;
      split.integrator = Integrator::Splitting;
      const batch_test::Outcome o = run(split, field, true, Precision::Double);
      Diff ds;
      ds.x = farthest_apart(o, batched);
      EXPECT_GT(ds.x, 1e-6);
      std::printf("strang dt %g: scalar vs batched |dx| %.2e, strang vs splitting |dx| %.2e, "
                  "%llu of %llu steps handed to the scalar step\n",
                  dt, d.x, ds.x, static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                  static_cast<unsigned long long>(batched.stats.body_steps));
    }
  }
}

TEST(RigidBatch, EulerAndRk4MatchTheScalarStep) {
  // the explicit schemes (integrators.h euler, rk4; rigid_batch_explicit.h) on the loops and on
  // the scalar step: leaves (plate drag, torque and lift, added mass) and seed pods (ellipsoid
  // drag) in the wind grid with seen turbulence, then with the Basset history and Magnus too
  for (const Integrator scheme : {Integrator::Euler, Integrator::RK4}) {
    for (const Shape& shape :
         {Shape::box(0.06, 0.04, 4e-4), Shape::ellipsoid(0.004, 0.002, 0.002)}) {
      for (const bool extra : {false, true}) {
        Scene s = rigid_scene(shape, 600, 64);
        s.integrator = scheme;
        s.dt = 5e-4;
        s.duration = 0.3;
        if (extra) {
          s.effects.add(Effect::Basset);
          s.effects.add(Effect::Magnus);
          s.bodies[0].angular_velocity = Vec3(5, 20, -10);
        }
        const FluidField field = wind_grid(1.5e-5);
        expect_eligible(s, field);
        const auto [scalar, batched, d] = scalar_and_batched(s, field);
        const char* name = scheme == Integrator::Euler ? "euler" : "rk4";
        EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << name;
        expect_close(d, 1e-9);
        // the loops take the steps themselves (rk4 hands over a lane whose stage left the fluid)
        EXPECT_LE(batched.stats.scalar_handoffs, batched.stats.body_steps / 1000) << name;
        EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u) << name;
        EXPECT_GT(batched.stats.body_steps, 100u * s.bodies[0].count) << name;
        // and it is the scheme asked for: splitting ends elsewhere
        Scene split = s;
        split.integrator = Integrator::Splitting;
        const batch_test::Outcome o = run(split, field, true, Precision::Double);
        const double apart = farthest_apart(o, batched);
        EXPECT_GT(apart, 1e-6) << name;
        std::printf("%s %s%s: scalar vs batched |dx| %.2e |v| %.2e |w| %.2e, vs splitting %.2e m, "
                    "%llu of %llu steps handed to the scalar step\n",
                    name, shape.type == ShapeType::Box ? "leaves" : "pods",
                    extra ? " with Basset and Magnus" : "", d.x, d.v, d.w, apart,
                    static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                    static_cast<unsigned long long>(batched.stats.body_steps));
      }
    }
  }
}

TEST(RigidBatch, Rk4InAGustingSeriesMatchesTheScalarStep) {
  // rk4's stages sample a time-dependent field at their own times (t + h/2, t + h), as the
  // scalar step does; euler samples at the start only
  for (const Integrator scheme : {Integrator::Euler, Integrator::RK4}) {
    Scene s = rigid_scene(Shape::box(0.06, 0.04, 4e-4), 600, 32);
    s.integrator = scheme;
    s.dt = 1e-3;
    s.duration = 0.5;
    const FluidField field = batch_test::gusty_wind_grid(1.5e-5);
    ASSERT_EQ(field.frame_count(), 4u);
    expect_eligible(s, field);
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
    expect_close(d, 1e-9);
    EXPECT_LE(batched.stats.scalar_handoffs, batched.stats.body_steps / 1000);
  }
}

// An artist's leaf from a mesh (batch_test::bent_leaf, curled and turned; 464 panels here, the
// mesh's own triangles): its generalized mass M is a full symmetric 6 x 6, and the loops run the
// free Kirchhoff flow, the implicit force step and the Strang force steps on the full-mass kernels
// of model/kirchhoff.h, as the scalar step does.
Scene mesh_leaf_scene(int n) {
  Scene s = rigid_scene(batch_test::bent_leaf(13, 9), 600, n);
  s.bodies[0].panels = 400;  // never coarsened: the mesh's 464 triangles
  return s;
}

TEST(RigidBatch, MeshLeavesWithAFullMassMatchTheScalarStep) {
  const FluidField field = wind_grid(1.5e-5);
  {
    const Model m = test::compile(mesh_leaf_scene(1), field);
    const BodyType& t = m.types[0];
    ASSERT_FALSE(t.M_diagonal);
    ASSERT_TRUE(t.flat);
    // a full M: products of inertia and an off-diagonal linear block (the turn: the in-plane
    // added masses are small, so the latter is too) and linear-angular coupling (the curl:
    // the added mass of the curled plate), relative to the diagonal (measured 0.07, 5.5e-4 and
    // 0.0099 at 464 panels)
    auto rel = [&](int r, int c) { return std::abs(t.M(r, c)) / std::sqrt(t.M(r, r) * t.M(c, c)); };
    EXPECT_GT(rel(3, 4), 0.02);
    EXPECT_GT(rel(0, 1), 2e-4);
    double coupling = 0;
    for (int r = 0; r < 3; ++r)
      for (int c = 3; c < 6; ++c) coupling = std::max(coupling, rel(r, c));
    EXPECT_GT(coupling, 0.004);
    std::printf("mesh leaf: M(3,4) %.3g, M(0,1) %.3g, largest coupling %.3g (relative)\n",
                rel(3, 4), rel(0, 1), coupling);
  }
  struct Case {
    Integrator scheme;
    bool extra;  // the Basset history and the Magnus force too
  };
  for (const Case c : {Case{Integrator::Splitting, false}, Case{Integrator::Strang, false},
                       Case{Integrator::Splitting, true}}) {
    Scene s = mesh_leaf_scene(100);
    s.integrator = c.scheme;
    if (c.extra) {
      s.effects.add(Effect::Basset);
      s.effects.add(Effect::Magnus);
      s.bodies[0].angular_velocity = Vec3(5, 20, -10);
    }
    expect_eligible(s, field);
    const auto [scalar, batched, d] = scalar_and_batched(s, field);
    EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
    expect_close(d, 1e-8);
    EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / 100);
    EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u);
    EXPECT_GT(count(batched.state, BodyStatus::Landed) + count(batched.state, BodyStatus::Exited),
              0u);
    double turned = 0;
    for (size_t i = 0; i < batched.state.size(); ++i)
      turned = std::max(turned, batched.state.w[i].norm());
    EXPECT_GT(turned, 1.0);  // rad/s
    std::printf("mesh leaves, %s%s: scalar vs batched |dx| %.2e, %llu Newton steps, %llu of %llu "
                "steps handed to the scalar step\n",
                c.scheme == Integrator::Strang ? "strang" : "splitting",
                c.extra ? " with Basset and Magnus" : "", d.x,
                static_cast<unsigned long long>(batched.stats.newton_steps),
                static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                static_cast<unsigned long long>(batched.stats.body_steps));
  }
}

TEST(RigidBatch, MeshLeavesEulerAndRk4MatchTheScalarStep) {
  // the explicit schemes on the full-mass kernels (rigid_batch_explicit.h compiled for FullMass):
  // the impulse conversions with a full M and K's six rows (euler), M^-1 of the rates and M_body's
  // gyroscopic terms (rk4), the added-mass wrench of a full K (both), then with the Basset
  // history (euler: the implicit solve of a full M + b P; rk4: the correction through
  // (M + b P)^-1's first three columns, which turns the spin too) and Magnus, on the batched
  // step, not handed to the scalar one.
  const FluidField field = wind_grid(1.5e-5);
  for (const Integrator scheme : {Integrator::Euler, Integrator::RK4}) {
    for (const bool extra : {false, true}) {
      Scene s = mesh_leaf_scene(64);
      s.integrator = scheme;
      s.dt = 5e-4;
      s.duration = 0.3;
      if (extra) {
        s.effects.add(Effect::Basset);
        s.effects.add(Effect::Magnus);
        s.bodies[0].angular_velocity = Vec3(5, 20, -10);
      }
      {
        const Model m = test::compile(s, field);
        ASSERT_FALSE(m.types[0].M_diagonal);
      }
      expect_eligible(s, field);
      const auto [scalar, batched, d] = scalar_and_batched(s, field);
      const char* name = scheme == Integrator::Euler ? "euler" : "rk4";
      EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << name;
      expect_close(d, 1e-8);
      // the loops take the steps themselves (rk4 hands over a lane whose stage left the fluid)
      EXPECT_LE(batched.stats.scalar_handoffs, batched.stats.body_steps / 1000) << name;
      EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u) << name;
      EXPECT_GT(batched.stats.body_steps, 100u * s.bodies[0].count) << name;
      double turned = 0;
      for (size_t i = 0; i < batched.state.size(); ++i)
        turned = std::max(turned, batched.state.w[i].norm());
      EXPECT_GT(turned, 1.0) << name;  // rad/s
      // and it is the scheme asked for: splitting ends elsewhere
      Scene split = s;
      split.integrator = Integrator::Splitting;
      const batch_test::Outcome o = run(split, field, true, Precision::Double);
      const double apart = farthest_apart(o, batched);
      EXPECT_GT(apart, 1e-6) << name;
      std::printf("mesh leaves, %s%s: scalar vs batched |dx| %.2e |v| %.2e |w| %.2e, vs "
                  "splitting %.2e m, %llu of %llu steps handed to the scalar step\n",
                  name, extra ? " with Basset and Magnus" : "", d.x, d.v, d.w, apart,
                  static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                  static_cast<unsigned long long>(batched.stats.body_steps));
    }
  }
}

TEST(RigidBatch, MeshLeavesInFloatStayCloseToDouble) {
  // single precision on the full-mass loops (M and M^-1 rounded to float in the products): over
  // 0.3 s of tumbling in the wind grid the mesh leaves end close to double (measured 1.3e-5 m;
  // a leaf falls about 0.3 m in that time)
  Scene s = mesh_leaf_scene(64);
  s.duration = 0.3;
  const FluidField field = wind_grid(1.5e-5);
  const batch_test::Outcome dbl = run(s, field, true, Precision::Double);
  const batch_test::Outcome flt = run(s, field, true, Precision::Float);
  EXPECT_EQ(flt.stats.scalar_handoffs, 0u);
  const auto [same, dx] = batch_test::float_vs_double(dbl, flt, false);
  EXPECT_GE(same, dbl.state.size() - 2);
  EXPECT_LT(dx, 1e-3);
  EXPECT_GT(dx, 0.0);  // single precision really ran
}

TEST(RigidBatch, FreeFlowOfAFullMassKeepsItsInvariants) {
  // the mesh leaves with added mass alone, in fluid at rest: each batched step is the free
  // Kirchhoff flow of a full M (the force steps add nothing), which conserves the energy
  // 1/2 Y.M^-1 Y of Y = M xi, |P|, P.L and the world-frame impulse R P (Lamb section 124) to the
  // iteration's tolerance; 1000 steps of fast tumbling
  for (const Integrator scheme : {Integrator::Splitting, Integrator::Strang}) {
    Scene s = mesh_leaf_scene(64);
    s.effects = test::effects({Effect::AddedMass});
    s.integrator = scheme;
    s.uniform_field = true;
    s.has_ground = false;
    s.duration = 2.0;
    s.bodies[0].velocity = Vec3(0.4, -0.2, 0.3);
    s.bodies[0].angular_velocity = Vec3(8, -15, 25);
    const FluidField field =
        FluidField::uniform(Vec3::Zero(), 0, 0, s.kinematic_viscosity, s.drift);
    const Model m = test::compile(s, field);
    const BodyType& t = m.types[0];
    ASSERT_FALSE(t.M_diagonal);
    std::string why;
    ASSERT_EQ(step_kind(m, t, &why), StepKind::Batched) << why;
    State st = initial_state(m, s);
    auto impulse = [&](const State& x, size_t i) {
      Vec6 xi;
      xi << x.v[i], x.w[i];
      return Vec6(t.M * xi);
    };
    std::vector<Vec6> Y0;
    std::vector<Vec3> P0w;
    for (size_t i = 0; i < st.size(); ++i) {
      Y0.push_back(impulse(st, i));
      P0w.push_back(st.q[i] * Vec3(Y0[i].head<3>()));
    }
    RunOptions opt;
    opt.every = 1e9;
    const RunStats stats = simulate(m, &st, opt);
    EXPECT_EQ(stats.body_steps, 1000u * st.size());
    EXPECT_EQ(stats.scalar_handoffs, 0u);  // the loops took every step
    double worst_e = 0, worst_p = 0, worst_pl = 0, worst_pw = 0, turned = 0;
    for (size_t i = 0; i < st.size(); ++i) {
      const Vec6 Y = impulse(st, i), y0 = Y0[i];
      const double e = Y.dot(t.M_inv * Y), e0 = y0.dot(t.M_inv * y0);
      worst_e = std::max(worst_e, std::abs(e / e0 - 1));
      worst_p = std::max(worst_p, std::abs(Y.head<3>().norm() / y0.head<3>().norm() - 1));
      worst_pl = std::max(worst_pl, std::abs(Y.head<3>().dot(Y.tail<3>()) -
                                             y0.head<3>().dot(y0.tail<3>())) /
                                        (y0.head<3>().norm() * y0.tail<3>().norm()));
      worst_pw = std::max(worst_pw,
                          (st.q[i] * Vec3(Y.head<3>()) - P0w[i]).norm() / P0w[i].norm());
      // the motion was not trivial: the body-frame impulse changed direction
      turned = std::max(turned, (Y.head<3>() - y0.head<3>()).norm() / y0.head<3>().norm());
    }
    EXPECT_LT(worst_e, 1e-9);
    EXPECT_LT(worst_p, 1e-9);
    EXPECT_LT(worst_pl, 1e-9);
    EXPECT_LT(worst_pw, 1e-9);
    EXPECT_GT(turned, 0.1);
    std::printf("free flow of a full M (%s): energy %.1e, |P| %.1e, P.L %.1e, R P %.1e; %llu "
                "Newton steps of %llu\n",
                scheme == Integrator::Strang ? "strang" : "splitting", worst_e, worst_p, worst_pl,
                worst_pw, static_cast<unsigned long long>(stats.newton_steps),
                static_cast<unsigned long long>(stats.body_steps));
  }
}

TEST(RigidBatch, StiffDragTakesTheNewtonPathLikeTheScalarStep) {
  // light cards and paper disks at a coarse step (20 ms): the drag is stiff, and the loops
  // iterate Newton themselves (with the Basset history's implicit mass in the second run). Over
  // the first 0.5 s: with the aspect-ratio plate drag (its lower broadside C_D) the cards
  // later spin up into free flows that Newton is slow on (handed to the scalar step, 24 % of the
  // steps over 1 s) and their chaotic motion amplifies rounding past 1e-9.
  for (const Shape& shape : {Shape::box(0.06, 0.04, 4e-4), Shape::ellipsoid(0.03, 0.02, 6e-4)}) {
    for (const bool basset : {false, true}) {
      Scene s = rigid_scene(shape, 500, 64);
      s.dt = 0.02;
      s.duration = 0.5;
      if (basset) s.effects.add(Effect::Basset);
      const FluidField field = wind_grid(1.5e-5);
      expect_eligible(s, field);
      const auto [scalar, batched, d] = scalar_and_batched(s, field);
      EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
      expect_close(d, 1e-9);
      // the loops solve the stiff steps by Newton themselves (not handing them all to the
      // scalar step); the hardest free flows still go there (Newton slow to converge)
      EXPECT_GT(batched.stats.newton_steps, batched.stats.body_steps / 2);
      EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / 5);
      std::printf("stiff %s%s: %llu Newton steps, %llu of %llu steps handed to the scalar step\n",
                  shape.type == ShapeType::Box ? "cards" : "disks", basset ? " with Basset" : "",
                  static_cast<unsigned long long>(batched.stats.newton_steps),
                  static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                  static_cast<unsigned long long>(batched.stats.body_steps));
    }
  }
}

TEST(RigidBatch, HardLanesGoToTheScalarStepAndStillMatch) {
  // tissue-paper squares spinning fast at a coarse step: the drag is stiff and the free
  // Kirchhoff flow needs substeps (its Newton iteration alone does not converge), which only the
  // scalar step takes. Over 0.1 s: the tissue's motion is chaotic at this step, rounding
  // differences grow about 100 times every 0.1 s
  Scene s = rigid_scene(Shape::box(0.03, 0.03, 5e-5), 200, 64);
  s.dt = 0.02;
  s.duration = 0.1;
  s.bodies[0].angular_velocity = Vec3(40, -25, 10);
  const FluidField field = wind_grid(1.5e-5);
  expect_eligible(s, field);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  EXPECT_GT(batched.stats.scalar_handoffs, batched.stats.body_steps / 10);
  EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps);
  expect_close(d, 1e-9);
  std::printf("tissue: %llu of %llu steps handed to the scalar step\n",
              static_cast<unsigned long long>(batched.stats.scalar_handoffs),
              static_cast<unsigned long long>(batched.stats.body_steps));
}

TEST(RigidBatch, PlatesInFluidAtRestMatchTheScalarStep) {
  // nothing samples the field: falling cards with drag and lift in still air
  Scene s = rigid_scene(Shape::box(0.05, 0.03, 5e-4), 700, 40);
  s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::Lift, Effect::AddedMass});
  s.uniform_field = true;
  s.has_ground = false;
  const FluidField field = FluidField::uniform(Vec3::Zero(), 0, 0, s.kinematic_viscosity, s.drift);
  expect_eligible(s, field);
  const auto [scalar, batched, d] = scalar_and_batched(s, field);
  expect_close(d, 1e-9);
  for (size_t i = 0; i < batched.state.size(); ++i)
    EXPECT_LT(batched.state.x[i].z(), s.bodies[0].box_hi.z()) << "body " << i;  // they fell
}

TEST(RigidBatch, IdenticalForAnyThreadCount) {
  const Scene s = rigid_scene(Shape::box(0.06, 0.04, 4e-4), 600, 200);
  const FluidField field = wind_grid(1.5e-5);
  const batch_test::Outcome one = run(s, field, true, Precision::Double, 1);
  const batch_test::Outcome two = run(s, field, true, Precision::Double, 2);
  const Diff d = batch_test::compare(one, two);
  EXPECT_EQ(d.x, 0.0);
  EXPECT_EQ(d.t, 0.0);
  EXPECT_EQ(d.v, 0.0);
  EXPECT_EQ(d.q, 0.0);
  EXPECT_EQ(d.u, 0.0);
}

// A block steps only the lanes up to its last live one, rounded up to whole vectors
// (Samples::width): bodies 5-13 or 5-10 alone end bitwise where they end in a full block of
// 32, on both precisions and both implicit schemes, with bodies landing on the way
// (batch_test::expect_lanes_ignore_width).
TEST(RigidBatch, ALaneEndsTheSameWhateverHowManyLanesItsBlockSteps) {
  const FluidField field = wind_grid(1.5e-5);
  for (const Integrator scheme : {Integrator::Splitting, Integrator::Strang}) {
    for (const Precision p : {Precision::Double, Precision::Float}) {
      Scene s = rigid_scene(Shape::box(0.06, 0.04, 4e-4), 600, 32);
      s.integrator = scheme;
      s.duration = 1.5;
      batch_test::expect_lanes_ignore_width(s, field, p);
    }
  }
}

TEST(RigidBatch, FloatStaysCloseToDouble) {
  // spinning seed pods (the free Kirchhoff flow of an anisotropic inertia; not chaotic like
  // tumbling plates): float follows double closely over 1 s
  Scene s = rigid_scene(Shape::ellipsoid(0.004, 0.002, 0.002), 400, 200);
  s.effects.remove(Effect::AddedMass);
  s.bodies[0].angular_velocity = Vec3(5, 20, -10);
  const FluidField field = wind_grid(1.5e-5);
  const batch_test::Outcome dbl = run(s, field, true, Precision::Double);
  const batch_test::Outcome flt = run(s, field, true, Precision::Float);
  const auto [same, dx] = batch_test::float_vs_double(dbl, flt, false);  // where they stopped
  EXPECT_GE(same, dbl.state.size() - 3);
  EXPECT_LT(dx, 1e-3);
  EXPECT_GT(dx, 0.0);  // single precision really ran
}

TEST(RigidBatch, BodiesWithTheirCentreOfMassOffTheCentroidMatchTheScalarStep) {
  // a centre of mass off the volume centroid (mass_offset: a keel, a weighted leaf stem): the
  // fluid's forces and the buoyancy act at the centroid, which moves at v + w x r_cob, and turn
  // the body about its centre of mass. Every scheme, on leaves (plate drag, torque and lift; with
  // added mass M is full), seed pods (ellipsoid drag), a leaf without added mass (a diagonal M)
  // and a sphere (not on the isotropic M's loops, which take only uniform spheres), spinning,
  // with Magnus, in the wind grid with seen turbulence, 0.2 s
  struct Case {
    const char* name;
    Shape shape;
    double density;
    Vec3 offset;
    bool added_mass;
  };
  const Case cases[] = {
      {"leaf", Shape::box(0.06, 0.04, 4e-4), 600, Vec3(0.004, -0.002, -1e-4), true},
      {"pod", Shape::ellipsoid(0.004, 0.002, 0.002), 600, Vec3(0.001, 0, -0.0005), true},
      {"leaf, no added mass", Shape::box(0.06, 0.04, 4e-4), 600, Vec3(0.004, 0, 0), false},
      {"bead", Shape::sphere(0.003), 1500, Vec3(0, 0.0005, -0.001), true},
  };
  const FluidField field = wind_grid(1.5e-5);
  for (const Case& c : cases) {
    for (const Integrator scheme :
         {Integrator::Splitting, Integrator::Strang, Integrator::Euler, Integrator::RK4}) {
      Scene s = rigid_scene(c.shape, c.density, 32);
      s.bodies[0].mass_offset = c.offset;
      if (!c.added_mass) s.effects.remove(Effect::AddedMass);
      s.effects.add(Effect::Magnus);
      s.bodies[0].angular_velocity = Vec3(5, 20, -10);
      s.integrator = scheme;
      s.dt = 1e-3;
      s.duration = 0.2;
      const std::string name = std::string(c.name) + ", " + integrator_name(scheme);
      {
        const Model m = test::compile(s, field);
        std::string why;
        EXPECT_TRUE(rigid_batch_eligible(m, m.types[0], &why)) << name << ": " << why;
        EXPECT_EQ(step_kind(m, m.types[0], nullptr), StepKind::Batched) << name;
      }
      const auto [scalar, batched, d] = scalar_and_batched(s, field);
      EXPECT_EQ(scalar.stats.body_steps, batched.stats.body_steps) << name;
      expect_close(d, 1e-9);
      EXPECT_LT(batched.stats.scalar_handoffs, batched.stats.body_steps / 100) << name;
      EXPECT_GT(count(batched.state, BodyStatus::Moving), 0u) << name;
      // and the offset's terms ran: the same bodies with a uniform mass end elsewhere
      Scene uniform = s;
      uniform.bodies[0].mass_offset = Vec3::Zero();
      const batch_test::Outcome o = run(uniform, field, true, Precision::Double);
      const double apart = farthest_apart(o, batched);
      EXPECT_GT(apart, 1e-5) << name;
      std::printf("%s: scalar vs batched |dx| %.2e |v| %.2e |w| %.2e, vs a uniform mass %.2e m, "
                  "%llu of %llu steps handed to the scalar step\n",
                  name.c_str(), d.x, d.v, d.w, apart,
                  static_cast<unsigned long long>(batched.stats.scalar_handoffs),
                  static_cast<unsigned long long>(batched.stats.body_steps));
    }
  }
}

TEST(RigidBatch, EligibilitySaysWhatExcludesABodyType) {
  const Scene s = rigid_scene(Shape::box(0.06, 0.04, 4e-4), 600, 1);
  const FluidField field = wind_grid(1.5e-5);
  batch_test::expect_exclusions(
      s, field, rigid_batch_eligible,
      {
          {[](Scene& e) { e.turbulence_model = TurbulenceModel::Body; },
           "the body turbulence model"},
          {[](Scene& e) { e.batched = false; }, "the scene turns the batched step off"},
      });
}

}  // namespace
}  // namespace lrigid
