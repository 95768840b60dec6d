// The events at the end of a step (contact/events.h, events.cpp): how far a shape reaches below
// its centre of mass (ground_reach) against a search over the shape and against closed forms,
// the touchdown located inside a step against a free fall's root, a body that lands on a "stop"
// ground, and a body that leaves the grid (stop_body: removed or kept, left the grid or hit a
// solid).
#include "contact/events.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "integrate/simulation.h"
#include "support/contact_scenes.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::bounce_scene;
using test::inclined_wall_grid;
using test::kG;

// The lowest point of a box and of an ellipsoid of half extents h whose centroid lies at c from
// the centre of mass, for random orientations, against a search over the shape written here: the
// box's 8 corners, and the ellipsoid's surface sampled on a grid of 600 x 1200 angles (its points
// lie on the surface, so the sampled lowest point is never below the true one and within
// h (pi / 600)^2 of it)
TEST(Events, GroundReachIsTheLowestPointOfTheShape) {
  const double h[3] = {0.03, 0.02, 0.005}, c[3] = {0.002, -0.001, 0.003};
  std::mt19937_64 g(11);
  std::normal_distribution<double> normal(0, 1);
  for (int trial = 0; trial < 12; ++trial) {
    const Quat q = Quat(normal(g), normal(g), normal(g), normal(g)).normalized();
    const Mat3 R = q.toRotationMatrix();
    const double r[3] = {R(2, 0), R(2, 1), R(2, 2)};
    const Vec3 rz(r[0], r[1], r[2]), cv(c[0], c[1], c[2]);
    double box_low = HUGE_VAL;
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner((k & 1) ? h[0] : -h[0], (k & 2) ? h[1] : -h[1], (k & 4) ? h[2] : -h[2]);
      box_low = std::min(box_low, rz.dot(cv + corner));
    }
    EXPECT_NEAR(ground_reach(false, r, h, c), -box_low, 1e-15) << trial;
    double ell_low = HUGE_VAL;
    const int nt = 600, np = 1200;
    for (int i = 0; i <= nt; ++i) {
      const double th = M_PI * i / nt;
      for (int j = 0; j < np; ++j) {
        const double ph = 2 * M_PI * j / np;
        const Vec3 p(h[0] * std::sin(th) * std::cos(ph), h[1] * std::sin(th) * std::sin(ph),
                     h[2] * std::cos(th));
        ell_low = std::min(ell_low, rz.dot(cv + p));
      }
    }
    const double reach = ground_reach(true, r, h, c);
    EXPECT_GE(reach, -ell_low - 1e-15) << trial;
    EXPECT_NEAR(reach, -ell_low, 1e-6) << trial;
  }
  // tilted by th about y (no offset): an ellipsoid of semi-axes (a, b, c) reaches
  // sqrt(a^2 sin^2 th + c^2 cos^2 th) below its centre, a box of half sides (a, b, c)
  // a sin th + c cos th
  const double zero[3] = {0, 0, 0};
  for (const double deg : {0.0, 10.0, 45.0, 80.0}) {
    const double th = deg * M_PI / 180, s = std::sin(th), co = std::cos(th);
    const double r[3] = {-s, 0, co};
    EXPECT_NEAR(ground_reach(true, r, h, zero),
                std::sqrt(h[0] * h[0] * s * s + h[2] * h[2] * co * co), 1e-15)
        << deg;
    EXPECT_NEAR(ground_reach(false, r, h, zero), h[0] * s + h[2] * co, 1e-15) << deg;
  }
}

TEST(Touchdown, FindsAFreeFallsRootInsideTheStep) {
  // a box tilted about x falls freely (no fluid forces): the motion through the step is a
  // parabola, which the cubic interpolant holds exactly, so the located time is the root of
  // z0 + vz t - g t^2/2 = reach to rounding
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5);
  s.bodies[0].shape = Shape::box(0.06, 0.04, 0.002);
  s.has_ground = true;
  s.ground_contact = ContactMode::Stop;
  s.dt = 0.01;
  const Model m = test::compile(s);
  const BodyType& type = m.types[0];
  const double g = 9.81, vz = -0.3;
  BodyState a;
  a.x = Vec3(0.1, 0.2, 0.05);
  a.q = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
  a.v = a.q.conjugate() * Vec3(0.2, 0, vz);
  a.w.setZero();
  a.u_seen.setZero();
  BodyState b = a;
  b.x = a.x + s.dt * Vec3(0.2, 0, vz) - 0.5 * g * s.dt * s.dt * Vec3::UnitZ();
  b.v = a.q.conjugate() * Vec3(0.2, 0, vz - g * s.dt);
  const double reach = std::sin(0.3) * 0.02 + std::cos(0.3) * 0.001;
  // the touchdown needs a step that reaches the ground: start just above it
  const double z0 = reach + 0.002;
  b.x.z() += z0 - a.x.z();
  a.x.z() = z0;
  ASSERT_TRUE(touches_ground(m, type, b));
  ASSERT_FALSE(touches_ground(m, type, a));
  BodyState at;
  const double tau = locate_touchdown(m, type, a, b, &at);
  // z0 + vz t - g t^2 / 2 = reach
  const double exact = (vz + std::sqrt(vz * vz + 2 * g * (z0 - reach))) / g;
  EXPECT_NEAR(tau, exact, 1e-12);
  EXPECT_NEAR(at.x.z(), reach, 1e-12);
  EXPECT_NEAR(at.x.x(), a.x.x() + 0.2 * exact, 1e-12);
  // a body that already touched at the start lands at the end of the step
  EXPECT_EQ(locate_touchdown(m, type, b, b, &at), s.dt);
}

TEST(Touchdown, ASpinningSphereTouchesAtItsRadius) {
  // a sphere's lowest point is one radius down whatever its orientation (the bounding box of a
  // sphere turned 45 degrees reaches 1.41 radii)
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5);
  s.has_ground = true;
  const Model m = test::compile(s);
  BodyState b;
  b.x = Vec3(0, 0, 0.0101);
  b.q = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3(1, 1, 0).normalized()));
  b.v.setZero(), b.w.setZero(), b.u_seen.setZero();
  EXPECT_FALSE(touches_ground(m, m.types[0], b));
  b.x.z() = 0.0099;
  EXPECT_TRUE(touches_ground(m, m.types[0], b));
}

TEST(Touchdown, ABodyWithAKeelTouchesWhereItsShapeDoes) {
  // a 2 cm cube whose centre of mass is 5 mm below its centroid (mass_offset, a keel): upright its
  // lowest point is 5 mm below the centre of mass, upside down 15 mm (the shape's half extents are
  // about the centroid, not the centre of mass: not 10 mm both ways)
  Scene s = test::sphere_scene(0.01, 1000, 1.2, 1.5e-5);
  s.bodies[0].shape = Shape::box(0.02, 0.02, 0.02);
  s.bodies[0].mass_offset = Vec3(0, 0, -0.005);
  s.has_ground = true;
  const Model m = test::compile(s);
  BodyState b;
  b.v.setZero(), b.w.setZero(), b.u_seen.setZero();
  for (const double turn : {0.0, M_PI}) {
    b.q = Quat(Eigen::AngleAxisd(turn, Vec3::UnitX()));
    const double reach = turn == 0.0 ? 0.005 : 0.015;
    b.x = Vec3(0, 0, reach + 1e-4);
    EXPECT_FALSE(touches_ground(m, m.types[0], b)) << turn;
    b.x.z() = reach - 1e-4;
    EXPECT_TRUE(touches_ground(m, m.types[0], b)) << turn;
  }
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
