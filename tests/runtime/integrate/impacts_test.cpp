// Impacts located inside a step (integrate/impacts.h): a bounce on the ground or on a grid's
// wall taken where it happens, not at the step's end, leaves the trajectory at its closed form
// (a parabola reflected with e; a straight throw reflected about the wall's normal), even at a
// coarse step and through the grid's floor; with drag the bounces keep the scheme second order.
#include "integrate/impacts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "integrate/simulation.h"
#include "support/contact_scenes.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::bounce_scene;
using test::inclined_wall_grid;
using test::kG;
using test::wall_throw_scene;

class SphereBounce : public ::testing::TestWithParam<bool> {};

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
  // (integrate/impacts.h impact_inside_step) with gravity alone the step (strang) and the
  // touchdown's Hermite root are exact for a parabola, so a bounce taken where it happens leaves
  // the trajectory exact even at a coarse step; the impulse at the step's end and a position
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

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, SphereBounce, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

TEST(Walls, AnImpactOnAWallIsTakenWhereItHappensInsideTheStep) {
  // the sphere of wall_throw_scene at a coarse step (10 ms, the wall met 4.5 ms into a step): its
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
  const GridGeometry g = test::grid_geometry(5, 5, 101, Vec3(-0.2, -0.2, 0), Vec3(0.1, 0.1, 0.02));
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

}  // namespace
}  // namespace lrigid
