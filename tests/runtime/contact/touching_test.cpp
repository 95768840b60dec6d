// The touching points of a body (contact/touching.h, touching.cpp) against the geometry written
// here: a box tilted into the ground touches at the two corners of its lowest edge, at the depth
// and with the normal the tilt gives, and its gap to the ground is that of its lowest corner; a
// box just above the ground has its points found by the slack, by looking ahead and as
// speculative points; a sphere pressed into an inclined wall of a grid touches at its support
// point, along the wall's normal.
#include "contact/touching.h"

#include <gtest/gtest.h>

#include <cmath>

#include "integrate/simulation.h"
#include "support/contact_scenes.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// A box 10 x 8 x 4 cm over the ground z = 0, tilted by 10 degrees about y: in the body frame its
// lowest edge joins the corners (0.05, +-0.04, -0.02), at height z_c - 0.05 sin th - 0.02 cos th
// for a centre at height z_c; the next corners lie 0.1 sin th (17 mm) higher.
struct TiltedBox {
  double th = 10 * M_PI / 180;
  Model m;
  BodyState b;
  Mat3 R;
  State st;
  TiltedBox() : m(test::compile(scene())), st(initial_state(m, scene())) {
    b = load_body(st, 0);
    b.q = Quat(Eigen::AngleAxisd(th, Vec3::UnitY()));
    b.v = Vec3::Zero();
    b.w = Vec3::Zero();
    R = b.q.toRotationMatrix();
  }
  static Scene scene() {
    Scene s = test::sphere_scene(0.05, 600, 1.2, 1.5e-5);
    s.bodies[0].shape = Shape::box(0.1, 0.08, 0.04);
    s.effects = test::effects({Effect::Gravity});
    s.has_ground = true;
    s.ground_z = 0;
    return s;
  }
  // the centre's height at which the lowest edge is `gap` above the ground (m)
  double centre_height(double gap) const { return gap + 0.05 * std::sin(th) + 0.02 * std::cos(th); }
};

TEST(Touching, ABoxTiltedIntoTheGroundTouchesAtItsLowestEdge) {
  TiltedBox box;
  ASSERT_TRUE(box.m.ground_collides());
  const BodyType& type = box.m.types[0];
  box.b.x = Vec3(0.3, -0.1, box.centre_height(-0.001));  // the edge 1 mm into the ground
  Touching t;
  gather(box.m, type, box.b, box.R, 0, 0, &t);
  // the two corners; the edge's inner points between them are implied by them
  ASSERT_EQ(t.count, 2);
  EXPECT_EQ(t.touching, 2);
  EXPECT_TRUE(t.ground);
  const Vec3 n_body(-std::sin(box.th), 0, std::cos(box.th));  // R^T e_z
  for (int p = 0; p < 2; ++p) {
    const Vec3 r(t.r[3 * p], t.r[3 * p + 1], t.r[3 * p + 2]);
    const Vec3 n(t.n[3 * p], t.n[3 * p + 1], t.n[3 * p + 2]);
    EXPECT_NEAR(r.x(), 0.05, 1e-12) << p;
    EXPECT_NEAR(std::abs(r.y()), 0.04, 1e-12) << p;
    EXPECT_NEAR(r.z(), -0.02, 1e-12) << p;
    EXPECT_TRUE(test::near(n, n_body, 1e-15)) << p;
    EXPECT_NEAR(t.depth[p], 0.001, 1e-12) << p;
  }
  EXPECT_NE(t.r[1], t.r[4]);  // both ends of the edge
  EXPECT_NEAR(surface_gap(box.m, type, box.b.x, box.R, 0), -0.001, 1e-12);
  // 5 mm deeper than the next corners reach: four corners
  box.b.x.z() = box.centre_height(-0.1 * std::sin(box.th) - 0.005);
  Touching deep;
  gather(box.m, type, box.b, box.R, 0, 0, &deep);
  EXPECT_EQ(deep.touching, 4);
}

TEST(Touching, ABoxJustAboveTheGroundIsFoundBySlackLookAheadAndAsSpeculativePoints) {
  TiltedBox box;
  const BodyType& type = box.m.types[0];
  box.b.x = Vec3(0, 0, box.centre_height(0.001));  // the edge 1 mm above the ground
  EXPECT_NEAR(surface_gap(box.m, type, box.b.x, box.R, 0), 0.001, 1e-12);
  Touching none;
  gather(box.m, type, box.b, box.R, 0, 0, &none);
  EXPECT_EQ(none.count, 0);
  // within a slack of 2 mm: the two corners, at depth 0
  Touching slack;
  gather(box.m, type, box.b, box.R, 0, 0, &slack, nullptr, 0.002);
  ASSERT_EQ(slack.count, 2);
  EXPECT_EQ(slack.depth[0], 0.0);
  EXPECT_EQ(slack.depth[1], 0.0);
  // falling at 20 mm/s (world), looked at 0.1 s ahead: 2 mm lower, 1 mm into the ground
  const double fall = 0.02;
  ASSERT_LT(fall, box.m.rest_speed);
  box.b.v = box.R.transpose() * Vec3(0, 0, -fall);
  Touching ahead;
  gather(box.m, type, box.b, box.R, 0, 0.1, &ahead);
  ASSERT_EQ(ahead.count, 2);
  EXPECT_NEAR(ahead.depth[0], 0.001, 1e-12);
  EXPECT_NEAR(ahead.depth[1], 0.001, 1e-12);
  // speculative points: approaching slower than rest_speed and reaching the ground within
  // 0.1 s, at minus their gap; the next corners (17 mm up) are not reached in that time
  Touching spec;
  gather(box.m, type, box.b, box.R, 0, 0, &spec, nullptr, 0, 0.1);
  ASSERT_EQ(spec.count, 2);
  EXPECT_EQ(spec.touching, 0);
  EXPECT_NEAR(spec.depth[0], -0.001, 1e-12);
  EXPECT_NEAR(spec.depth[1], -0.001, 1e-12);
  // approaching faster than rest_speed: an impact, no speculative point
  box.b.v = box.R.transpose() * Vec3(0, 0, -2 * box.m.rest_speed);
  Touching fast;
  gather(box.m, type, box.b, box.R, 0, 0, &fast, nullptr, 0, 0.1);
  EXPECT_EQ(fast.count, 0);
}

TEST(Touching, ASphereInAnInclinedWallTouchesAtItsSupportPointAlongTheNormal) {
  const double th = 30 * M_PI / 180, r = 0.05;
  const Vec3 n(-std::sin(th), 0, std::cos(th));  // from the wall into the fluid
  Scene s = test::sphere_scene(r, 1000, 1.2, 1.5e-5);
  s.uniform_field = false;
  s.effects = test::effects({Effect::Gravity});
  const Model m = test::compile(s, test::inclined_wall_grid(n, Vec3::Zero()));
  ASSERT_TRUE(m.walls_collide());
  ASSERT_FALSE(m.ground_collides());
  State st = initial_state(m, s);
  BodyState b = load_body(st, 0);
  b.q = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
  const Mat3 R = b.q.toRotationMatrix();
  // a point of the wall's plane, then 4 cm out along its normal: the sphere 1 cm into the wall
  b.x = Vec3(0.1, 0, 0.1 * std::tan(th)) + 0.04 * n;
  ASSERT_NEAR(n.dot(b.x), 0.04, 1e-15);
  Touching t;
  gather(m, m.types[0], b, R, 0, 0, &t);
  ASSERT_EQ(t.count, 1);
  EXPECT_FALSE(t.ground);
  const Vec3 rb(t.r[0], t.r[1], t.r[2]), nb(t.n[0], t.n[1], t.n[2]);
  // (the grid stores the wall distance in single precision)
  EXPECT_TRUE(test::near(Vec3(R * nb), n, 1e-6));
  EXPECT_TRUE(test::near(Vec3(R * rb), Vec3(-r * n), 1e-6));
  EXPECT_NEAR(t.depth[0], r - n.dot(b.x), 1e-6);
  EXPECT_NEAR(surface_gap(m, m.types[0], b.x, R, 0), n.dot(b.x) - r, 1e-6);
}

}  // namespace
}  // namespace lrigid
