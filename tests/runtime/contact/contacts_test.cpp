// Bodies meeting the ground and the grid's solids in the steps (contact/pass.h, sleep.h,
// integrate/impacts.h), against closed forms: a sphere bouncing on the ground (apex ratio e^2), a
// box on an inclined plane (sliding with g (sin th - mu cos th), staying when mu > tan th), a
// sphere on an inclined wall of a grid (reflection about the wall's normal), and the grid's edge
// (remove / stop).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "compile/compile_model.h"
#include "contact/events.h"
#include "contact/pass.h"
#include "contact/sleep.h"
#include "contact/solver.h"
#include "integrate/impacts.h"
#include "integrate/simulation.h"
#include "support/batch_compare.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr double kG = 9.81;

// the apexes (local maxima of z) of a trajectory sampled every step
std::vector<double> apexes(const std::vector<double>& z) {
  std::vector<double> a;
  for (size_t k = 1; k + 1 < z.size(); ++k)
    if (z[k] > z[k - 1] && z[k] >= z[k + 1]) a.push_back(z[k]);
  return a;
}

Scene bounce_scene(double e, bool batched) {
  Scene s = test::sphere_scene(0.05, 1000, 1.2, 1.5e-5);
  s.effects = test::effects({Effect::Gravity});  // the fluid's forces off
  s.bodies[0].position = Vec3(0, 0, 1.0);
  s.bodies[0].contact.restitution = e;
  s.bodies[0].contact.friction = 0.3;
  s.has_ground = true;
  s.ground_z = 0;
  s.dt = 1e-4;
  s.duration = 2.5;
  s.batched = batched;
  return s;
}

class SphereBounce : public ::testing::TestWithParam<bool> {};

TEST_P(SphereBounce, ApexHeightRatioIsESquared) {
  const double e = 0.8, r = 0.05;
  Scene s = bounce_scene(e, GetParam());
  const Model m = test::compile(s);
  ASSERT_TRUE(m.ground_collides());
  State st = initial_state(m, s);
  std::vector<double> z;
  RunOptions o;
  o.every = s.dt;
  o.on_output = [&](const State& x) { z.push_back(x.x[0].z() - r); };
  simulate(m, &st, o);
  ASSERT_EQ(st.status[0], BodyStatus::Moving);
  std::vector<double> a = apexes(z);
  a.insert(a.begin(), z.front());  // the drop height is the first apex
  ASSERT_GE(a.size(), 4u);
  for (size_t n = 0; n + 1 < 4; ++n)
    EXPECT_NEAR(a[n + 1] / a[n] / (e * e), 1.0, 0.02)
        << "bounce " << n << ": apex " << a[n] << " -> " << a[n + 1] << " m";
  // never below the ground by more than one step's travel
  double lowest = 1;
  for (double h : z) lowest = std::min(lowest, h);
  EXPECT_GT(lowest, -std::sqrt(2 * kG * 1.0) * s.dt);
  EXPECT_GE(st.impacts[0], 4u);
  EXPECT_FALSE(std::isnan(st.t_touch[0]));
  EXPECT_NEAR(st.t_touch[0], std::sqrt(2 * 0.95 / kG), 2 * s.dt);
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, SphereBounce, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// The sphere of bounce_scene (gravity only, e) at time T, in closed form: its centre's height
// and vertical velocity after the bounces before T (each impact reverses e times the speed)
std::pair<double, double> bounce_exact(double z0, double r, double e, double T) {
  double t = 0, z = z0, v = 0;
  for (;;) {
    // the next impact: z + v s - g s^2 / 2 = r
    const double s_hit = (v + std::sqrt(v * v + 2 * kG * (z - r))) / kG;
    if (t + s_hit > T) break;
    t += s_hit;
    z = r;
    v = e * kG * s_hit - e * v;  // e times the impact speed g s - v, upward
  }
  const double s = T - t;
  return {z + v * s - 0.5 * kG * s * s, v - kG * s};
}

// s (in a uniform field) run to its end, its body still moving there
State run_to_end(const Scene& s) {
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  EXPECT_EQ(st.status[0], BodyStatus::Moving);
  return st;
}

TEST_P(SphereBounce, TheImpactIsTakenWhereItHappensInsideTheStep) {
  // (integrate/impacts.h impact_inside_step) with gravity alone the step (strang) and the touchdown's
  // Hermite root are exact for a parabola, so a bounce taken where it happens leaves the
  // trajectory exact even at a coarse step; the impulse at the step's end and a position
  // correction were off by about a step's travel (cm at dt = 10 ms)
  const double e = 0.8, r = 0.05, T = 1.3;
  for (const double dt : {1e-2, 7e-3}) {
    Scene s = bounce_scene(e, GetParam());
    s.dt = dt;
    s.duration = T;
    const State st = run_to_end(s);
    const auto [z, vz] = bounce_exact(1.0, r, e, st.t);
    EXPECT_EQ(st.impacts[0], 2u) << dt;  // at 0.44 s and 1.14 s
    EXPECT_NEAR(st.x[0].z(), z, 1e-9) << dt;
    EXPECT_NEAR((st.q[0] * st.v[0]).z(), vz, 1e-8) << dt;
    EXPECT_NEAR(st.t_touch[0], std::sqrt(2 * 0.95 / kG), 1e-9) << dt;
  }
}

TEST_P(SphereBounce, WithDragTheBouncesKeepTheSchemesSecondOrder) {
  // a heavy sphere in still air, drag on, bouncing twice in 1.3 s: the error at the end against
  // a run at a 16 times finer step falls as dt^2 (strang), not as dt (an impact at the step's
  // end)
  const double e = 0.8, T = 1.3;
  auto run = [&](double dt) {
    Scene s = bounce_scene(e, GetParam());
    s.effects = test::effects({Effect::Gravity, Effect::Drag});
    s.bodies[0].density = 50;  // light: the drag matters (terminal speed about 5 m/s)
    s.dt = dt;
    s.duration = T;
    const State st = run_to_end(s);
    EXPECT_GE(st.impacts[0], 2u);
    return Vec3(st.x[0].z(), (st.q[0] * st.v[0]).z(), 0);
  };
  const Vec3 ref = run(2.5e-4 / 16);
  const double e1 = (run(4e-3) - ref).norm(), e2 = (run(2e-3) - ref).norm();
  const double e3 = (run(1e-3) - ref).norm();
  std::printf("bounce with drag: errors %.3g %.3g %.3g m\n", e1, e2, e3);
  EXPECT_GT(e1 / e2, 3.0) << e1 << " " << e2 << " " << e3;
  EXPECT_GT(e2 / e3, 3.0) << e1 << " " << e2 << " " << e3;
}

TEST(SphereBounce, StopModeStillLandsTheBody) {
  Scene s = bounce_scene(0.8, false);
  s.ground_contact = ContactMode::Stop;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  EXPECT_EQ(st.status[0], BodyStatus::Landed);
  EXPECT_NEAR(st.t_stop[0], std::sqrt(2 * 0.95 / kG), 2 * s.dt);
}

// A box resting on the ground under gravity tilted by th about y: the same as a box on a plane
// inclined by th, with the slope along +x.
Scene incline_scene(double th, double mu, bool batched) {
  Scene s;
  s.file = "<test>";
  s.fluid_density = 1.2;
  s.kinematic_viscosity = 1.5e-5;
  BodySpec b;
  b.name = "box";
  b.shape = Shape::box(0.1, 0.08, 0.04);
  b.density = 600;
  b.position = Vec3(0, 0, 0.02);
  b.contact.restitution = 0;
  b.contact.friction = mu;
  s.bodies.push_back(b);
  s.effects = test::effects({Effect::Gravity});
  s.gravity = kG * Vec3(std::sin(th), 0, -std::cos(th));
  s.has_ground = true;
  s.ground_z = 0;
  s.dt = 1e-3;
  s.batched = batched;
  return s;
}

class Incline : public ::testing::TestWithParam<bool> {};

TEST_P(Incline, BoxSlidesWithGTimesSinMinusMuCos) {
  const double th = 20 * M_PI / 180, mu = 0.2;
  Scene s = incline_scene(th, mu, GetParam());
  s.duration = 2;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  const double a = kG * (std::sin(th) - mu * std::cos(th));
  const Vec3 V = st.q[0] * st.v[0];
  EXPECT_NEAR(V.x() / (a * s.duration), 1.0, 0.02) << "speed " << V.x() << " m/s";
  EXPECT_NEAR(st.x[0].x() / (0.5 * a * s.duration * s.duration), 1.0, 0.02);
  EXPECT_NEAR(st.x[0].z(), 0.02, 1e-4) << "it stays on the plane";
  EXPECT_EQ(st.contact[0], ContactState::Sliding);
  EXPECT_EQ(st.status[0], BodyStatus::Moving);
}

TEST_P(Incline, BoxStaysWhenMuAboveTanTheta) {
  const double th = 20 * M_PI / 180, mu = 0.5;
  ASSERT_GT(mu, std::tan(th));
  for (const bool sleep : {true, false}) {
    Scene s = incline_scene(th, mu, GetParam());
    s.duration = 10;
    Model m = test::compile(s);
    if (!sleep) m.sleep_time = 1e9;  // the contact alone must hold it
    State st = initial_state(m, s);
    const Vec3 x0 = st.x[0];
    simulate(m, &st, RunOptions{});
    EXPECT_LT((st.x[0] - x0).norm(), 1e-6) << (sleep ? "with" : "without") << " sleeping";
    if (sleep) {
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping);
    } else {
      EXPECT_EQ(st.contact[0], ContactState::Resting);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, Incline, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// A grid whose wall distance is the inclined plane n.(x - p0) (n unit, pointing into the fluid):
// fluid at rest, points below the plane invalid.
FluidField inclined_wall_grid(const Vec3& n, const Vec3& p0) {
  const GridGeometry g = test::grid_geometry(21, 5, 21, Vec3(-1, -0.2, -1), Vec3(0.1, 0.1, 0.1));
  RawGridFrame f = test::grid_frame(g, [&](const Vec3& x, Vec3*, double* k, double* eps) {
    *k = 1e-6;
    *eps = 1e-6;
    return n.dot(x - p0) >= 0;
  });
  f.wall_distance.resize(g.points());
  for (size_t p = 0; p < g.points(); ++p) {
    const size_t i = p % size_t(g.n[0]), j = (p / size_t(g.n[0])) % size_t(g.n[1]);
    const size_t l = p / (size_t(g.n[0]) * size_t(g.n[1]));
    const Vec3 x = g.origin + Vec3(double(i), double(j), double(l)).cwiseProduct(g.spacing);
    f.wall_distance[p] = float(n.dot(x - p0));
  }
  return FluidField::grid(g, {f}, 1.5e-5, Drift::Stationary, TimeMode::Clamp);
}

// A 5 cm sphere thrown at 2 m/s straight down from 0.3 m onto the inclined wall of
// inclined_wall_grid (normal n), gravity off, friction 0, restitution e, for 0.3 s at step dt.
Scene wall_throw_scene(double e, double dt, bool batched) {
  Scene s = test::sphere_scene(0.05, 1000, 1.2, 1.5e-5);
  s.uniform_field = false;
  s.effects = test::effects({Effect::Gravity});
  s.gravity = Vec3::Zero();
  s.bodies[0].position = Vec3(0, 0, 0.3);
  s.bodies[0].velocity = Vec3(0, 0, -2);
  s.bodies[0].contact.restitution = e;
  s.bodies[0].contact.friction = 0;
  s.dt = dt;
  s.duration = 0.3;
  s.batched = batched;
  return s;
}

TEST(Walls, SphereReflectsAboutTheInclinedWallsNormal) {
  const double th = 30 * M_PI / 180, e = 0.6, r = 0.05;
  const Vec3 n(-std::sin(th), 0, std::cos(th));  // the wall rises along +x
  for (const bool batched : {false, true}) {
    const Scene s = wall_throw_scene(e, 1e-4, batched);
    const Model m = test::compile(s, inclined_wall_grid(n, Vec3::Zero()));
    ASSERT_TRUE(m.walls_collide());
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    ASSERT_EQ(st.status[0], BodyStatus::Moving) << st.reason[0];
    const Vec3 V0(0, 0, -2), V = st.q[0] * st.v[0];
    const double vn0 = V0.dot(n);
    const Vec3 vt0 = V0 - vn0 * n;
    EXPECT_NEAR(V.dot(n), -e * vn0, 1e-6 * std::abs(vn0)) << (batched ? "batched" : "scalar");
    EXPECT_TRUE(test::near(Vec3(V - V.dot(n) * n), vt0, 1e-6));
    EXPECT_EQ(st.impacts[0], 1u);
    // the sphere never went into the wall by more than one step's travel
    EXPECT_GT(n.dot(st.x[0]) - r, -2.0 * s.dt);
  }
}

// Leaves (6 x 4 cm, 0.4 mm thick, 600 kg/m^3) dropped from 2-5 cm at random orientations in
// still air (gravity, added mass, drag) onto the ground, or onto a level wall of a grid (the
// ground off): each comes to rest and sleeps, none rocks on. Without the speculative points
// of the contact pass (docs/contacts.md "Speculative points") a leaf lying a few micrometres
// tilted landed on one edge every step, its impulse there tipped it onto the other, and 11 of
// 50 rocked at a few tenths of a radian per second for ever (4 "sliding" in place, 7 resting
// for less than the sleep time at a time).
Scene leaves_dropped_scene(bool on_wall, bool batched) {
  Scene s = test::sphere_scene(0.01, 600, 1.204, 1.5e-5, 50);
  s.bodies[0].name = "leaf";
  s.bodies[0].shape = Shape::box(0.06, 0.04, 0.0004);
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(-0.8, -0.1, 0.02);
  s.bodies[0].box_hi = Vec3(0.8, 0.1, 0.05);
  s.bodies[0].random_orientation = true;
  s.bodies[0].contact.restitution = 0.1;
  s.bodies[0].contact.friction = 0.6;
  s.effects = test::effects({Effect::Gravity, Effect::AddedMass, Effect::Drag});
  s.uniform_field = !on_wall;
  s.has_ground = !on_wall;
  s.ground_z = 0;
  s.dt = 2e-3;
  s.duration = 1.5;
  s.seed = 1;
  s.batched = batched;
  return s;
}

TEST(Walls, LeavesDroppedOnTheGroundOrALevelWallComeToRestAndSleep) {
  for (const bool on_wall : {false, true})
    for (const bool batched : {false, true}) {
      const Scene s = leaves_dropped_scene(on_wall, batched);
      const Model m = on_wall ? test::compile(s, inclined_wall_grid(Vec3::UnitZ(), Vec3::Zero()))
                              : test::compile(s);
      ASSERT_EQ(m.walls_collide(), on_wall);
      State st = initial_state(m, s);
      simulate(m, &st, RunOptions{});
      const char* where = on_wall ? "on the wall" : "on the ground";
      const size_t asleep = batch_test::count(st, BodyStatus::Sleeping);
      EXPECT_EQ(asleep, st.status.size()) << where << (batched ? ", batched" : ", scalar");
      for (size_t i = 0; i < st.status.size(); ++i)
        EXPECT_NEAR(st.x[i].z(), 0.0002, 1e-4) << "leaf " << i << " lies " << where;
    }
}

TEST(Walls, AnImpactOnAWallIsTakenWhereItHappensInsideTheStep) {
  // the sphere of the test above at a coarse step (10 ms, the wall met 4.5 ms into a step): its
  // position at the end is the closed form's (straight to the wall, reflected with e, straight on)
  const double th = 30 * M_PI / 180, e = 0.6, r = 0.05;
  const Vec3 n(-std::sin(th), 0, std::cos(th));
  for (const bool batched : {false, true}) {
    const Scene s = wall_throw_scene(e, 1e-2, batched);
    const Model m = test::compile(s, inclined_wall_grid(n, Vec3::Zero()));
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    ASSERT_EQ(st.status[0], BodyStatus::Moving) << st.reason[0];
    const Vec3 x0(0, 0, 0.3), V0(0, 0, -2);
    const double t_hit = (n.dot(x0) - r) / -V0.dot(n);  // n.x - r = 0
    const Vec3 V1 = V0 - (1 + e) * V0.dot(n) * n;
    const Vec3 x = x0 + t_hit * V0 + (st.t - t_hit) * V1;
    // (to the grid's float wall distance: 2e-9 m found; with the impulse at the step's end it was
    // 9 mm off)
    EXPECT_TRUE(test::near(st.x[0], x, 1e-7))
        << (batched ? "batched " : "scalar ") << st.x[0].transpose() << " against "
        << x.transpose();
    EXPECT_EQ(st.impacts[0], 1u);
  }
}

TEST(Walls, AnImpactThroughTheGridsFloorIsTakenWhereItHappens) {
  // the grid's floor is the ground (as in the wind scene): a step that ends more than a cell
  // below it has no sample there, and its impact is located by the deterministic part alone
  // (impact_through_floor). The bouncing sphere of SphereBounce at dt = 30 ms, its centre a step
  // below the floor at each impact: the closed form at the end, to 1e-9 m
  const double e = 0.8, r = 0.05;
  // (2 cm cells: a step that ends within a cell below the floor samples its bottom layer,
  // FluidField::set_floor_clamp, and is taken by impact_inside_step)
  const GridGeometry g =
      test::grid_geometry(5, 5, 101, Vec3(-0.2, -0.2, 0), Vec3(0.1, 0.1, 0.02));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3&, Vec3*, double* k, double* eps) {
    *k = 1e-6;
    *eps = 1e-6;
    return true;
  });
  for (const bool batched : {false, true}) {
    Scene s = bounce_scene(e, batched);
    s.uniform_field = false;
    // the mean flow (at rest: no force) makes the step sample the field, and a step ending
    // below the floor leave it
    s.effects = test::effects({Effect::Gravity, Effect::MeanFlow});
    s.bodies[0].position = Vec3(0, 0, 1.05);  // both steps that meet the ground end 8 and 5 cm
    s.dt = 0.03;                              // below the floor
    s.duration = 1.29;
    const Model m =
        test::compile(s, FluidField::grid(g, {f}, 1.5e-5, Drift::Stationary, TimeMode::Clamp));
    ASSERT_TRUE(m.ground_collides());
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    ASSERT_EQ(st.status[0], BodyStatus::Moving) << st.reason[0];
    const auto [z, vz] = bounce_exact(1.05, r, e, st.t);
    EXPECT_EQ(st.impacts[0], 2u);
    EXPECT_NEAR(st.x[0].z(), z, 1e-9) << (batched ? "batched" : "scalar");
    EXPECT_NEAR((st.q[0] * st.v[0]).z(), vz, 1e-8) << (batched ? "batched" : "scalar");
    EXPECT_NEAR(st.t_touch[0], std::sqrt(2 * 1.0 / kG), 1e-9);
  }
}

TEST(Outside, RemoveHidesABodyThatLeavesTheGridStopKeepsIt) {
  for (const OutsideMode mode : {OutsideMode::Remove, OutsideMode::Stop}) {
    Scene s = test::sphere_scene(0.02, 1000, 1.2, 1.5e-5);
    s.uniform_field = false;
    // the mean flow: the body samples the field (one that does not never learns it left)
    s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::MeanFlow});
    s.gravity = Vec3::Zero();
    s.bodies[0].position = Vec3(0.5, 0, 0.5);
    s.bodies[0].velocity = Vec3(5, 0, 0);
    s.outside = mode;
    s.dt = 1e-3;
    s.duration = 0.3;
    const Model m = test::compile(s, inclined_wall_grid(Vec3(0, 0, 1), Vec3(0, 0, -0.9)));
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    EXPECT_EQ(st.status[0], BodyStatus::Exited);
    EXPECT_EQ(st.reason[0], "left the grid");
    EXPECT_EQ(st.hidden[0], mode == OutsideMode::Remove ? 1 : 0);
    EXPECT_STREQ(st.state_name(0), "exited");
  }
}

// A body that could not be sampled while on the fluid's side of every wall (wall distance > 0)
// left the grid, even when one more step with its velocity would keep it in the box (a batched
// step's turbulence can carry it past the edge): removed and hidden, not "hit a solid" (which
// left it visible at the grid's edge in the wind scene). Inside a solid it still hit one.
TEST(Outside, AStepPastTheEdgeFromTheFluidSideIsLeavingTheGrid) {
  Scene s = test::sphere_scene(0.02, 1000, 1.2, 1.5e-5);
  s.uniform_field = false;
  s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::MeanFlow});
  s.outside = OutsideMode::Remove;
  const Model m = test::compile(s, inclined_wall_grid(Vec3(0, 0, 1), Vec3(0, 0, -0.9)));
  ASSERT_TRUE(m.walls_collide());
  State st = initial_state(m, s);
  BodyState b = load_body(st, 0);
  b.x = Vec3(0.999, 0, 0.5);  // 1 mm from the edge x = 1, at rest
  stop_body(m, m.types[0], 0, 0.1, StepOutcome::Exited, "", &b, &st);
  EXPECT_EQ(st.reason[0], "left the grid");
  EXPECT_EQ(st.hidden[0], 1);
  b.x = Vec3(0.5, 0, -0.95);  // below the wall z = -0.9
  stop_body(m, m.types[0], 0, 0.1, StepOutcome::Exited, "", &b, &st);
  EXPECT_EQ(st.reason[0].rfind("hit a solid", 0), 0u) << st.reason[0];
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

// The batched steps hand the lanes near the ground to the same contact pass as the scalar step:
// with contacts on, the wind scene of the batched-step tests ends in the same states.
TEST(ContactsBatched, LeavesAndBeadsOnTheGroundMatchTheScalarStep) {
  for (const bool plates : {false, true}) {
    Scene s = plates ? test::sphere_scene(0.01, 400, 1.2, 1.5e-5, 96)
                     : test::sphere_scene(2.5e-4, 2500, 1.2, 1.5e-5, 96);
    if (plates) s.bodies[0].shape = Shape::box(0.04, 0.03, 0.0005);
    s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag,
                               Effect::AddedMass, Effect::MeanFlow, Effect::Turbulence});
    if (plates) s.effects.add(Effect::Lift);
    batch_test::release_in_wind_grid(&s, 7);
    s.ground_contact = ContactMode::Collide;
    s.duration = 2.0;
    const FluidField field = batch_test::wind_grid(1.5e-5);
    const auto [scalar, batched, d] = batch_test::scalar_and_batched(s, field);
    size_t touched = 0, states_differ = 0;
    for (size_t i = 0; i < batched.state.size(); ++i) {
      touched += !std::isnan(batched.state.t_touch[i]);
      states_differ += scalar.state.state_code(i) != batched.state.state_code(i);
    }
    EXPECT_GT(touched, 10u) << "the scene puts bodies on the ground";
    EXPECT_EQ(states_differ, 0u);
    EXPECT_EQ(batch_test::count(batched.state, BodyStatus::Landed), 0u);
    EXPECT_LT(d.x, plates ? 1e-6 : 1e-9) << (plates ? "plates" : "beads");
    EXPECT_LT(d.v, plates ? 1e-4 : 1e-9) << (plates ? "plates" : "beads");
  }
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

// A ball at rest on the ground falls asleep after Model::sleep_time; in a time-dependent field
// it wakes at the next frame time (the flow around it changed) and, still at rest, sleeps again.
TEST(Sleeping, RestingBallSleepsAndWakesWhenTheFlowChanges) {
  const GridGeometry g = test::grid_geometry(3, 3, 3, Vec3(-1, -1, 0), Vec3(1, 1, 1));
  RawGridFrame a = test::grid_frame(g, [](const Vec3&, Vec3*, double*, double*) { return true; });
  RawGridFrame b = a;
  a.time = 0;
  b.time = 1.5;
  for (const bool transient : {false, true}) {
    Scene s = test::sphere_scene(0.05, 1000, 1.2, 1.5e-5);
    s.uniform_field = false;
    s.effects = test::effects({Effect::Gravity, Effect::MeanFlow, Effect::Drag});
    s.bodies[0].position = Vec3(0, 0, 0.05);
    s.has_ground = true;
    s.dt = 1e-3;
    s.duration = 2.0;
    std::vector<RawGridFrame> frames{a};
    if (transient) frames.push_back(b);
    const Model m = test::compile(
        s, FluidField::grid(g, frames, 1.5e-5, Drift::Stationary, TimeMode::Clamp));
    State st = initial_state(m, s);
    std::vector<std::pair<double, BodyStatus>> seen;
    RunOptions o;
    o.every = 0.1;
    o.on_output = [&](const State& x) { seen.emplace_back(x.t, x.status[0]); };
    const RunStats stats = simulate(m, &st, o);
    // asleep from about sleep_time on
    for (const auto& [t, status] : seen) {
      if (t > m.sleep_time + 0.05 && t < 1.45) {
        EXPECT_EQ(status, BodyStatus::Sleeping) << "t = " << t;
      }
      if (t < m.sleep_time - 0.05) {
        EXPECT_EQ(status, BodyStatus::Moving) << "t = " << t;
      }
    }
    // the steps it took: about sleep_time of them, plus sleep_time again after the wake
    const double steps = double(stats.body_steps) * s.dt;
    EXPECT_NEAR(steps, transient ? 2 * m.sleep_time : m.sleep_time, 0.15)
        << (transient ? "transient" : "steady");
    EXPECT_NEAR(st.x[0].z(), 0.05, 1e-6);
  }
}

TEST(Sleeping, BodiesWithTheBassetHistoryFallAsleepToo) {
  // the sleep test evaluates the flow's forces on the body held still, through its Basset history
  // (a crash on a null history once: tests/integration/resume_test.sh's scene); spheres and
  // chips, on the scalar and the batched step
  for (const bool batched : {false, true}) {
    for (const bool chip : {false, true}) {
      Scene s = test::sphere_scene(0.002, 1100, 1000, 1e-6);
      if (chip) s.bodies[0].shape = Shape::box(0.01, 0.006, 0.001);
      s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag,
                                 Effect::AddedMass, Effect::Basset});
      s.bodies[0].position = Vec3(0, 0, 0.01);
      s.has_ground = true;
      s.batched = batched;
      s.dt = 2e-3;
      s.duration = 3.0;
      const Model m = test::compile(s);
      State st = initial_state(m, s);
      simulate(m, &st, RunOptions{});
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping) << (chip ? "chip" : "sphere")
                                                     << (batched ? " batched" : " scalar");
    }
  }
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

// ground.contact "stop" with colliding walls: the ground still lands the bodies, on the scalar
// and on the batched step.
TEST(GroundStopWallsCollide, TheGroundStillLandsTheBody) {
  for (const bool batched : {false, true}) {
    Scene s = test::sphere_scene(0.05, 1000, 1.2, 1.5e-5);
    s.uniform_field = false;
    s.effects = test::effects({Effect::Gravity, Effect::MeanFlow, Effect::Drag});
    s.bodies[0].position = Vec3(0, 0, 0.5);
    s.has_ground = true;
    s.ground_z = 0;
    s.ground_contact = ContactMode::Stop;
    s.dt = 1e-3;
    s.duration = 1.0;
    s.batched = batched;
    const Model m = test::compile(s, inclined_wall_grid(Vec3(1, 0, 0), Vec3(-0.9, 0, 0)));
    ASSERT_TRUE(m.walls_collide());
    ASSERT_FALSE(m.ground_collides());
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    EXPECT_EQ(st.status[0], BodyStatus::Landed) << (batched ? "batched" : "scalar");
  }
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

// A sheet of paper lying flat on the ground in a uniform wind along x (issue 23, item 6): the
// speed U* at which the wind's force on it held still (drag, and lift, from the model's own
// effects: flow_can_move) equals mu (weight - lift) is found by bisection; below it the sheet
// stays, above it slides.
Scene plate_in_wind_scene(double U, double k, bool batched, bool turbulent = false) {
  Scene s = test::sphere_scene(0.05, 600, 1.2, 1.5e-5);
  s.bodies[0].name = "paper";
  s.bodies[0].shape = Shape::box(0.15, 0.1, 0.002);
  s.bodies[0].position = Vec3(0, 0, 0.001);
  s.bodies[0].contact.restitution = 0;
  s.bodies[0].contact.friction = 0.4;
  s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::Lift, Effect::MeanFlow});
  if (turbulent) s.effects.add(Effect::Turbulence);
  s.uniform_U = Vec3(U, 0, 0);
  s.uniform_k = k;
  s.uniform_epsilon = k > 0 ? 0.1 : 0;
  s.has_ground = true;
  s.ground_z = 0;
  s.dt = 1e-3;
  s.duration = 2.0;
  s.batched = batched;
  return s;
}

// Does flow_can_move say the wind U (and turbulence k) moves the sheet at rest? One model,
// its uniform field replaced (compiling the model is the slow part).
bool wind_moves_plate(double U, double k, bool turbulent = false) {
  static Model m = test::compile(plate_in_wind_scene(1, 0, false, false));
  static Model mt = test::compile(plate_in_wind_scene(1, 0.01, false, true));
  Model& model = turbulent ? mt : m;
  model.field = FluidField::uniform(Vec3(U, 0, 0), k, k > 0 ? 0.1 : 0, 1.5e-5, Drift::Stationary);
  State st = initial_state(model, plate_in_wind_scene(U, k, false, turbulent));
  const double gust = turbulent ? kGustSigmas * std::sqrt(2.0 * k / 3.0) : 0.0;
  return flow_can_move(model, model.types[0], load_body(st, 0), Vec3::UnitZ(), 0, gust);
}

double threshold_speed() {
  double lo = 0, hi = 1;
  while (!wind_moves_plate(hi, 0)) hi *= 2;
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (lo + hi);
    (wind_moves_plate(mid, 0) ? hi : lo) = mid;
  }
  return hi;
}

class PlateInWind : public ::testing::TestWithParam<bool> {};

TEST_P(PlateInWind, StaysBelowTheFrictionSpeedSlidesAbove) {
  const double Us = threshold_speed();
  ASSERT_GT(Us, 0.5);
  ASSERT_LT(Us, 100);
  for (const double f : {0.9, 1.1}) {
    const Scene s = plate_in_wind_scene(f * Us, 0, GetParam());
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    if (f < 1) {
      // at rest: it fell asleep where the flow cannot move it, and did not creep
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping) << f << " U* = " << f * Us << " m/s";
      EXPECT_LT(std::abs(st.x[0].x()), 1e-4) << "it crept";
    } else {
      EXPECT_EQ(st.status[0], BodyStatus::Moving);
      EXPECT_EQ(st.contact[0], ContactState::Sliding);
      EXPECT_GT(st.x[0].x(), 0.05) << "it should slide downwind";
      EXPECT_NEAR(st.x[0].z(), 0.001, 1e-3) << "along the ground";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, PlateInWind, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// The gust at which the flow moves the sheet at rest (wake_gust) is where flow_can_move turns:
// the force on the sheet follows the wind it sees, mean and gust, so a mean wind of 0.9 U*
// needs a gust of 0.1 U*.
TEST(Sleeping, TheWakeGustIsWhereTheFlowStartsToMoveTheBody) {
  const double Us = threshold_speed();
  const double sigma = 0.1 * Us, k = 1.5 * sigma * sigma;
  Scene s = plate_in_wind_scene(0.9 * Us, k, false, true);
  const Model m = test::compile(s);
  const State st = initial_state(m, s);
  State copy = st;
  const BodyState b = load_body(copy, 0);
  const double g = wake_gust(m, m.types[0], b, Vec3::UnitZ(), 0, sigma);
  EXPECT_NEAR(g, 0.1 * Us, 1e-3 * Us);
  EXPECT_FALSE(flow_can_move(m, m.types[0], b, Vec3::UnitZ(), 0, 0.999 * g));
  EXPECT_TRUE(flow_can_move(m, m.types[0], b, Vec3::UnitZ(), 0, 1.001 * g));
  // none within kMaxGustSigmas standard deviations of a weak turbulence
  EXPECT_EQ(wake_gust(m, m.types[0], b, Vec3::UnitZ(), 0, 1e-3 * sigma), HUGE_VAL);
}

// A sleeping body's gust watch wakes it when the seen turbulence reaches its gust: for the OU
// process of a body at rest (stationary, per component variance sigma^2, rate alpha) started
// at u' = 0, the mean first-passage time to a level a sigma is, in units of 1/alpha,
//   T(a) = integral_0^a sqrt(2 pi) Phi(x) exp(x^2/2) dx
// (the backward equation -x T' + T'' = -1 with T(a) = 0). Checked over 4000 watches with
// a = 1.5; the watch looks at whole steps, which delays the passage as a barrier raised by
// 0.5826 sigma sqrt(2 alpha dt) would (Broadie, Glasserman & Kou 1997's correction). The
// components of u' across the mean flow, drawn at the wake, are those of the process at that
// time: mean 0, variance sigma^2 (1 - exp(-2 alpha t)). A watch asked again and again, a few
// steps further each time, wakes at the same step with the same u' as one asked once.
TEST(Sleeping, AGustWatchWakesAtTheOuProcesssFirstPassage) {
  const int n = 4000;
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5, n);
  s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::Turbulence});
  s.uniform_U = Vec3(1, 0, 0);
  s.uniform_k = 0.01;
  s.uniform_epsilon = 0.1;
  s.has_ground = true;
  s.dt = 1e-4;
  s.duration = 10;
  const Model m = test::compile(s);
  ASSERT_TRUE(keeps_gust_watch(m, m.types[0]));
  FluidSample fs;
  ASSERT_TRUE(m.field.sample(Vec3::Zero(), 0, false, &fs));
  const double sigma = std::sqrt(fs.sigma2), alpha = fs.alpha, a = 1.5;
  ASSERT_GT(alpha * s.dt, 1e-4);
  ASSERT_LT(alpha * s.dt, 1e-2);
  State st = initial_state(m, s);
  double sum = 0, sum2 = 0, across = 0, across2 = 0, across_sq = 0, across_sq2 = 0;
  for (int i = 0; i < n; ++i) {
    st.status[i] = BodyStatus::Sleeping;
    GustWatch& w = st.watch[i];
    w = GustWatch{};
    w.gust = a * sigma;
    w.valid = 1;
    const GustWatch fresh = w;
    const uint64_t wake = watch_sleeper(m, &st, size_t(i), 100000000);
    ASSERT_NE(wake, GustWatch::kNever);
    EXPECT_GE(w.u.x(), a * sigma);
    const double T = double(wake) * s.dt * alpha;
    sum += T;
    sum2 += T * T;
    // across the mean flow (x): y and z, each N(0, sigma^2 (1 - exp(-2 alpha t)))
    const double sd = sigma * std::sqrt(-std::expm1(-2 * T));
    for (const double c : {w.u.y() / sd, w.u.z() / sd}) {
      across += c, across2 += c * c;
      across_sq += c * c, across_sq2 += c * c * c * c;
    }
    if (i < 100) {
      const GustWatch once = w;
      w = fresh;
      uint64_t upto = 1, again = GustWatch::kNever;
      while (again == GustWatch::kNever) again = watch_sleeper(m, &st, size_t(i), upto += 7);
      EXPECT_EQ(again, once.wake) << i;
      EXPECT_EQ(w.u, once.u) << i;
    }
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  const double am = across / (2 * n), ase = std::sqrt((across2 / (2 * n) - am * am) / (2 * n));
  const double vm = across_sq / (2 * n),
               vse = std::sqrt((across_sq2 / (2 * n) - vm * vm) / (2 * n));
  EXPECT_NEAR(am, 0, 4 * ase) << "mean across the flow, in its standard deviations";
  EXPECT_NEAR(vm, 1, 4 * vse) << "variance across the flow / sigma^2 (1 - exp(-2 alpha t))";
  auto mfpt = [](double level) {  // Simpson's rule on 2000 intervals
    auto f = [](double x) {
      return std::sqrt(2 * M_PI) * 0.5 * std::erfc(-x / std::sqrt(2.0)) * std::exp(0.5 * x * x);
    };
    const int k = 2000;
    double r = f(0) + f(level);
    for (int j = 1; j < k; ++j) r += (j % 2 ? 4 : 2) * f(level * j / k);
    return r * level / (3 * k);
  };
  const double expected = mfpt(a + 0.5826 * std::sqrt(2 * alpha * s.dt));
  EXPECT_NEAR(mean, expected, 4 * se) << "mean first passage, 1/alpha; without the step's "
                                      << "correction " << mfpt(a);
  // the watch follows the process it sees: twice the rate would halve the time
  EXPECT_GT(mean, 0.75 * expected);
}

// A sheet held by friction in a mean wind of 0.9 U* with a turbulence whose gusts can move it
// falls asleep and its watch wakes it when a gust comes: it slides downwind and rests again. The
// batched step wakes it at the same step as the scalar one. Without the gusts (a turbulence far
// too weak) it sleeps and never wakes.
class GustWatchOnSteps : public ::testing::TestWithParam<bool> {};

TEST_P(GustWatchOnSteps, ASheetInGustsSleepsAndWakesWhenAGustComes) {
  const double Us = threshold_speed();
  const double sigma = 0.07 * Us, k = 1.5 * sigma * sigma;
  EXPECT_TRUE(wind_moves_plate(0.9 * Us, k, true));  // a 3 sigma gust moves it
  for (const double scale : {1.0, 1e-6}) {
    Scene s = plate_in_wind_scene(0.9 * Us, scale * k, GetParam(), true);
    s.duration = 10;
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    int slept = 0, woke = 0;
    BodyStatus before = BodyStatus::Moving;
    double x_asleep = 0, moved = 0;
    RunOptions o;
    o.every = s.dt;
    o.on_output = [&](const State& now) {
      if (now.status[0] == BodyStatus::Sleeping && before != BodyStatus::Sleeping) {
        ++slept;
        x_asleep = now.x[0].x();
      }
      if (now.status[0] == BodyStatus::Moving && before == BodyStatus::Sleeping) ++woke;
      if (before == BodyStatus::Moving && slept > 0)
        moved = std::max(moved, now.x[0].x() - x_asleep);
      before = now.status[0];
    };
    simulate(m, &st, o);
    if (scale == 1.0) {
      EXPECT_GE(slept, 2) << "it should fall asleep again after a gust moved it";
      EXPECT_GE(woke, 1);
      EXPECT_GT(moved, 1e-4) << "woken by a gust, it should slide downwind";
    } else {
      EXPECT_EQ(slept, 1);
      EXPECT_EQ(woke, 0);
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping);
      EXPECT_EQ(st.watch[0].wake, GustWatch::kNever);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, GustWatchOnSteps, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// Where the stretches of steps end (outputs, and at most kStretchSteps apart) does not change
// what the bodies do: 32 sheets dropped in a gusty wind onto the ground, where they land, slide,
// fall asleep and are woken by their gust watches (some inside a stretch, as dormant lanes, some
// at a stretch's start), end bitwise where the same run with an output every step leaves them.
TEST(Sleeping, StretchesDoNotChangeTheRun) {
  const double Us = threshold_speed();
  const double sigma = 0.07 * Us, k = 1.5 * sigma * sigma;
  for (const bool batched : {false, true}) {
    Scene s = plate_in_wind_scene(0.9 * Us, k, batched, true);
    s.bodies[0].count = 32;
    s.bodies[0].spawn_in_box = true;
    s.bodies[0].box_lo = Vec3(-1, -1, 0.002);
    s.bodies[0].box_hi = Vec3(1, 1, 0.05);
    s.bodies[0].random_orientation = true;
    s.duration = 2;
    const Model m = test::compile(s);
    State a = initial_state(m, s), b = a;
    RunOptions every_step;
    every_step.every = s.dt;
    int sleeping = 0, woken = 0;
    std::vector<uint8_t> was(32, 0);
    every_step.on_output = [&](const State& now) {
      for (size_t i = 0; i < 32; ++i) {
        const bool asleep = now.status[i] == BodyStatus::Sleeping;
        sleeping += asleep && !was[i];
        woken += !asleep && was[i];
        was[i] = asleep;
      }
    };
    simulate(m, &a, every_step);
    RunOptions at_end;
    at_end.every = s.duration;
    simulate(m, &b, at_end);
    EXPECT_GT(sleeping, 5) << (batched ? "batched" : "scalar");
    EXPECT_GT(woken, 2) << (batched ? "batched" : "scalar");
    for (size_t i = 0; i < 32; ++i) {
      EXPECT_EQ(a.x[i], b.x[i]) << i << (batched ? " batched" : " scalar");
      EXPECT_EQ(a.status[i], b.status[i]) << i;
    }
  }
}

// Scalar and batched steps wake the sheet at the same step and leave it at the same place.
TEST(Sleeping, GustWatchesWakeTheSameOnBothSteps) {
  const double Us = threshold_speed();
  const double sigma = 0.1 * Us, k = 1.5 * sigma * sigma;
  std::vector<double> x[2];
  std::vector<int> status[2];
  for (const bool batched : {false, true}) {
    Scene s = plate_in_wind_scene(0.9 * Us, k, batched, true);
    s.duration = 4;
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    RunOptions o;
    o.every = 0.05;
    o.on_output = [&](const State& now) {
      x[batched].push_back(now.x[0].x());
      status[batched].push_back(int(now.status[0]));
    };
    simulate(m, &st, o);
  }
  ASSERT_EQ(x[0].size(), x[1].size());
  for (size_t j = 0; j < x[0].size(); ++j) {
    EXPECT_EQ(status[0][j], status[1][j]) << "output " << j;
    EXPECT_NEAR(x[0][j], x[1][j], 1e-6) << "output " << j;
  }
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

// Rolling resistance (docs/contacts.md "Rolling resistance"): a sphere rolling without slipping
// on the ground, the fluid's forces off, under a torque mu_r R N against its rolling: with
// v = w R, m dv/dt = -F and I dw/dt = F R - mu_r R m g, I = 2/5 m R^2, so it decelerates at
// a = mu_r g / (1 + I / (m R^2)) = (5/7) mu_r g and stops after v0^2 / (2 a).
Scene rolling_scene(const Shape& shape, double density, double z0, const Vec3& v0,
                    const Vec3& w0, double mu_r, bool batched) {
  Scene s = test::sphere_scene(0.05, density, 1.2, 1.5e-5);
  s.bodies[0].shape = shape;
  s.effects = test::effects({Effect::Gravity});  // the fluid's forces off
  s.bodies[0].position = Vec3(0, 0, z0);
  s.bodies[0].velocity = v0;
  s.bodies[0].angular_velocity = w0;
  s.bodies[0].contact.restitution = 0.3;
  s.bodies[0].contact.friction = 0.5;
  s.bodies[0].contact.rolling_resistance = mu_r;
  s.has_ground = true;
  s.ground_z = 0;
  s.dt = 1e-3;
  s.duration = 4.0;
  s.batched = batched;
  return s;
}

// the centre's world positions at every output (every 10 ms) and the final state
struct Rolled {
  std::vector<double> t;
  std::vector<Vec3> x;
  State end;
};

Rolled roll(const Scene& s) {
  const Model m = test::compile(s);
  Rolled r{{}, {}, initial_state(m, s)};
  RunOptions o;
  o.every = 0.01;
  o.on_output = [&](const State& st) {
    r.t.push_back(st.t);
    r.x.push_back(st.x[0]);
  };
  simulate(m, &r.end, o);
  return r;
}

// the speed along the ground at output k (central difference: exact for a constant deceleration)
double speed_at(const Rolled& r, size_t k) {
  return (r.x[k + 1] - r.x[k - 1]).head<2>().norm() / (r.t[k + 1] - r.t[k - 1]);
}

size_t output_at(const Rolled& r, double t) {
  size_t k = 0;
  while (k + 1 < r.t.size() && r.t[k] < t - 1e-9) ++k;
  return k;
}

class RollingResistance : public ::testing::TestWithParam<bool> {};

TEST_P(RollingResistance, SphereDeceleratesAtFiveSeventhsMuRGAndStopsThere) {
  const double R = 0.05, v0 = 1.0, mu_r = 0.05;
  const double a = 5.0 / 7.0 * mu_r * kG;
  const Rolled r = roll(rolling_scene(Shape::sphere(R), 1000, R, Vec3(v0, 0, 0),
                                      Vec3(0, v0 / R, 0), mu_r, GetParam()));
  ASSERT_GT(r.t.size(), 300u);
  const size_t k1 = output_at(r, 0.5), k2 = output_at(r, 2.0);
  const double v1 = speed_at(r, k1), v2 = speed_at(r, k2);
  EXPECT_NEAR(v1, v0 - a * r.t[k1], 0.02 * v1);
  EXPECT_NEAR((v1 - v2) / (r.t[k2] - r.t[k1]), a, 0.02 * a);
  // stopped where v0^2 / (2 a) says, on the ground, and asleep (it stops at v0 / a = 2.85 s)
  const double rolled = (r.end.x[0] - Vec3(0, 0, R)).head<2>().norm();
  EXPECT_NEAR(rolled, v0 * v0 / (2 * a), 0.02 * v0 * v0 / (2 * a));
  EXPECT_NEAR(r.end.x[0].z(), R, 1e-5);  // on the ground (g dt^2 / 4 above it, as at rest)
  EXPECT_EQ(r.end.status[0], BodyStatus::Sleeping);
}

TEST_P(RollingResistance, WithoutItTheSphereKeepsRolling) {
  const double R = 0.05, v0 = 1.0;
  const Rolled r = roll(rolling_scene(Shape::sphere(R), 1000, R, Vec3(v0, 0, 0),
                                      Vec3(0, v0 / R, 0), 0.0, GetParam()));
  EXPECT_NEAR(r.end.x[0].x(), v0 * r.end.t, 1e-3 * v0 * r.end.t);
  EXPECT_NEAR(speed_at(r, r.t.size() - 2), v0, 1e-3 * v0);
  EXPECT_EQ(r.end.status[0], BodyStatus::Moving);
  EXPECT_EQ(r.end.contact[0], ContactState::Sliding);  // rolling: never at rest
}

// a seed pod (an ellipsoid 8 x 4 x 4 mm, 400 kg/m^3) lying on its side, rolling about its long
// axis: its cross-section is a circle of radius b = 2 mm and its inertia about that axis
// m (b^2 + c^2) / 5 = 2/5 m b^2, as a sphere's: it stops after v0^2 / (2 (5/7) mu_r g) too, and
// sleeps; dropped tumbling, it comes to rest and sleeps as well
TEST_P(RollingResistance, SeedPodComesToRestAndSleeps) {
  const double b = 0.002, v0 = 0.1, mu_r = 0.1;
  const double a = 5.0 / 7.0 * mu_r * kG;
  const Shape pod = Shape::ellipsoid(0.004, b, b);
  const Rolled r =
      roll(rolling_scene(pod, 400, b, Vec3(0, v0, 0), Vec3(-v0 / b, 0, 0), mu_r, GetParam()));
  const double rolled = (r.end.x[0] - Vec3(0, 0, b)).head<2>().norm();
  EXPECT_NEAR(rolled, v0 * v0 / (2 * a), 0.02 * v0 * v0 / (2 * a));
  EXPECT_EQ(r.end.status[0], BodyStatus::Sleeping);
  EXPECT_LT(r.end.t_stop[0], v0 / a + 0.5 + 0.05);  // stopped, then sleep_time of rest
  // dropped tilted about a horizontal axis, moving sideways: it lands, rocks and rolls, and
  // comes to rest (without resisting the twisting, the spin about the vertical, it ended lying
  // on its side spinning at 6 rad/s: docs/contacts.md)
  Scene drop = rolling_scene(pod, 400, 0.05, Vec3(0.3, 0.1, 0), Vec3::Zero(), mu_r, GetParam());
  drop.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 0).normalized()));
  const Rolled d = roll(drop);
  EXPECT_EQ(d.end.status[0], BodyStatus::Sleeping)
      << "w " << d.end.w[0].transpose() << " v " << d.end.v[0].transpose() << " contact "
      << int(d.end.contact[0]);
  EXPECT_LT(d.end.x[0].z(), 0.004);  // on the ground
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, RollingResistance, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// seed pods with rolling resistance blown over the ground of the wind grid: the batched step
// takes the same contacts (the same contact_after_step) as the scalar one
TEST(ContactsBatched, SeedPodsWithRollingResistanceMatchTheScalarStep) {
  Scene s = test::sphere_scene(0.002, 400, 1.2, 1.5e-5, 96);
  s.bodies[0].shape = Shape::ellipsoid(0.004, 0.002, 0.002);
  s.bodies[0].contact.rolling_resistance = 0.1;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag,
                             Effect::AddedMass, Effect::MeanFlow, Effect::Turbulence});
  batch_test::release_in_wind_grid(&s, 11);
  s.ground_contact = ContactMode::Collide;
  s.duration = 3.0;
  const FluidField field = batch_test::wind_grid(1.5e-5);
  const auto [scalar, batched, d] = batch_test::scalar_and_batched(s, field);
  size_t touched = 0, states_differ = 0;
  for (size_t i = 0; i < batched.state.size(); ++i) {
    touched += !std::isnan(batched.state.t_touch[i]);
    states_differ += scalar.state.state_code(i) != batched.state.state_code(i);
  }
  EXPECT_GT(touched, 10u) << "the scene puts bodies on the ground";
  EXPECT_GT(batch_test::count(batched.state, BodyStatus::Sleeping), 0u) << "some come to rest";
  EXPECT_EQ(states_differ, 0u);
  // ellipsoids take the rigid batched kernel, whose flight differs from the scalar step's at
  // round-off; the contacts amplify it (measured 2.2e-6 m, 4.5e-8 m/s; the plates above: 1e-6)
  EXPECT_LT(d.x, 1e-5);
  EXPECT_LT(d.v, 1e-4);
}

}  // namespace
}  // namespace lrigid
