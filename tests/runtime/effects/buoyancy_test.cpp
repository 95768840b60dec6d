// Gravity and buoyancy (effects/gravity.h, buoyancy.h): a neutrally buoyant body feels no net
// force, and a body whose centre of mass lies below its centroid gets a righting torque, which
// rights it over a run.
#include "effects/buoyancy.h"

#include <gtest/gtest.h>

#include <cmath>

#include "effects/gravity.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::compile;
using test::sphere_scene;

TEST(Buoyancy, NeutralBodyFeelsNoNetForce) {
  const Model m = compile(sphere_scene(0.01, 1000, 1000, 1e-6));
  const Vec3 g(0, 0, -9.81);
  const Wrench total = gravity_wrench(m.types[0], g) + buoyancy_wrench(m.types[0], 1000, g);
  EXPECT_LT(total.norm(), 1e-15);
}

TEST(Buoyancy, BottomHeavyBodyGetsRightingTorque) {
  Scene s = sphere_scene(0.01, 500, 1000, 1e-6);
  s.bodies[0].mass_offset = Vec3(0, 0, -0.005);  // centre of mass below the centroid
  const Model m = compile(s);
  // tilt the body by +30 deg about x: gravity in the body frame
  const Mat3 R = Eigen::AngleAxisd(M_PI / 6, Vec3::UnitX()).toRotationMatrix();
  const Vec3 g_b = R.transpose() * Vec3(0, 0, -9.81);
  const Wrench b = buoyancy_wrench(m.types[0], 1000, g_b);
  EXPECT_LT(b[3], 0);  // torque about x opposes the tilt
  EXPECT_NEAR(b.head<3>().norm(), 1000 * m.types[0].volume * 9.81, 1e-12);
}

TEST(Buoyancy, BottomHeavyBodyRightsItself) {
  Scene s = sphere_scene(1, 1000, 1000, 1e-6);  // neutrally buoyant disk-like body
  s.bodies[0].shape = Shape::ellipsoid(0.02, 0.02, 0.01);
  s.bodies[0].mass_offset = Vec3(0, 0, -0.004);  // keel: centre of mass below the centroid
  s.bodies[0].orientation = Quat(Eigen::AngleAxisd(60 * M_PI / 180, Vec3::UnitX()));
  s.gravity = Vec3(0, 0, -9.81);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag});
  s.integrator = Integrator::Splitting;
  s.dt = 1e-3;
  s.duration = 20;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  const double tilt = std::acos((st.q[0] * Vec3::UnitZ()).z()) * 180 / M_PI;
  EXPECT_LT(tilt, 2.0);
  // neutrally buoyant: no net force, so it stays (nearly) where it was
  EXPECT_LT(st.x[0].norm(), 0.05);
}

}  // namespace
}  // namespace lrigid
