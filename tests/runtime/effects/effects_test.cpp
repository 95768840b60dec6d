// Each effect alone, against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "effects/added_mass.h"
#include "effects/buoyancy.h"
#include "effects/drag.h"
#include "effects/gravity.h"
#include "effects/turbulence.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::compile;
using test::sphere_scene;

TEST(Drag, SchillerNaumannLimits) {
  EXPECT_NEAR(schiller_naumann(1e-4) * 1e-4, 24.0, 1e-2);          // Stokes: C_D Re -> 24
  EXPECT_NEAR(schiller_naumann(100), 24.0 / 100 * (1 + 0.15 * std::pow(100, 0.687)), 1e-12);
  EXPECT_EQ(schiller_naumann(5000), 0.44);
}

TEST(Drag, SphereAtLowReynoldsIsStokesDrag) {
  const double r = 1e-5, rho = 1000, nu = 1e-6, u = 1e-4;  // Re = 2e-3
  const Model m = compile(sphere_scene(r, 2500, rho, nu));
  const Wrench w = drag_wrench(m.types[0], Vec3(u, 0, 0), Vec3::Zero(), rho, nu);
  const double stokes = 6 * M_PI * rho * nu * r * u;
  // Stokes times Schiller-Naumann's finite-Re factor (1 + 0.15 Re^0.687), Re = 2e-3
  EXPECT_NEAR(-w[0] / stokes, 1.0 + 0.15 * std::pow(2e-3, 0.687), 1e-9);
  EXPECT_NEAR(-w[0] / stokes, 1.0, 3e-3);
  EXPECT_NEAR(w.tail<3>().norm(), 0.0, 1e-30);
}

TEST(Drag, SphereFollowsSchillerNaumannAtModerateRe) {
  const double r = 5e-4, rho = 998.2, nu = 1.0016e-3 / 998.2, u = 0.146;
  const Model m = compile(sphere_scene(r, 2500, rho, nu));
  const Wrench w = drag_wrench(m.types[0], Vec3(0, 0, -u), Vec3::Zero(), rho, nu);
  const double re = u * 2 * r / nu;
  const double expect = 0.5 * rho * schiller_naumann(re) * M_PI * r * r * u * u;
  EXPECT_NEAR(w[2] / expect, 1.0, 1e-9);
}

TEST(Drag, SphereRotationalDragIsStokesTorque) {
  // no out-of-roundness: only the viscous 8 pi mu r^3 w
  const double r = 0.01, rho = 1000, nu = 1e-6;
  const Model m = compile(sphere_scene(r, 2500, rho, nu));
  const Wrench w = drag_wrench(m.types[0], Vec3::Zero(), Vec3(0, 0, 3), rho, nu);
  EXPECT_NEAR(w[5], -8 * M_PI * rho * nu * r * r * r * 3, 1e-15);
}

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

TEST(AddedMass, SphereInUniformFlowFeelsNoForceWhenCoMoving) {
  Scene s = sphere_scene(0.01, 100, 1000, 1e-6);
  const Model m = compile(s);
  const Wrench w = added_mass_wrench(m.types[0], Vec3::Zero(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(w.norm(), 0.0);
  // fluid acceleration a drags the added mass: F = m_a a, m_a = rho V / 2
  const Vec3 a(0.3, -0.2, 0.1);
  const Wrench f = added_mass_wrench(m.types[0], Vec3::Zero(), Vec3::Zero(), a);
  EXPECT_LT((f.head<3>() - 0.5 * 1000 * m.types[0].volume * a).norm(), 1e-15);
}

TEST(Turbulence, ExactOUStepLimits) {
  const OUStep small = ou_exact(1e-15, 2.0, 0.01);
  EXPECT_NEAR(small.noise_std, 2.0 * std::sqrt(0.01), 1e-12);
  const OUStep big = ou_exact(1e3, 2.0, 1.0);  // alpha h = 1000: stationary in one step
  EXPECT_NEAR(big.decay, 0.0, 1e-300);
  EXPECT_NEAR(big.noise_std, std::sqrt(4.0 / 2e3), 1e-12);
}

TEST(Turbulence, WellMixedDriftVanishesInHomogeneousTurbulence) {
  FluidSample s;
  s.sigma2 = 0.2;
  EXPECT_EQ(well_mixed_drift(Vec3(0.1, 0.2, 0.3), Vec3(1, 2, 3), s).norm(), 0.0);
  s.grad_sigma2 = Vec3(0.1, 0, 0);
  // mean over u' ~ N(0, sigma2) for a tracer (path velocity U + u', U = 0): <a> = 1/2 grad
  // sigma2 + <u u^T> grad sigma2 / (2 sigma2) = grad sigma2
  EXPECT_NEAR(well_mixed_drift(Vec3::Zero(), Vec3::Zero(), s).x(), 0.05, 1e-15);
  const Vec3 u(0.3, -0.1, 0.2);
  EXPECT_NEAR(well_mixed_drift(u, u, s).x(), 0.05 + 0.3 * 0.3 * 0.1 / 0.4, 1e-15);
}

TEST(Turbulence, WellMixedDriftFollowsThePathNotTheFluctuation) {
  // a body at rest in a gradient: u' is rescaled only as fast as the body moves through sigma,
  // so the drift does not grow with u' (Thomson's u' + U would give u'^2 growth)
  FluidSample s;
  s.sigma2 = 0.2;
  s.grad_sigma2 = Vec3(0, 0, 0.4);
  const Vec3 big(0, 0, 10.0);
  EXPECT_NEAR(well_mixed_drift(big, Vec3::Zero(), s).z(), 0.2, 1e-15);
  const Vec3 v(0, 0, 0.5);
  EXPECT_NEAR(well_mixed_drift(big, v, s).z(), 0.2 + 10.0 * 0.5 * 0.4 / 0.4, 1e-13);
}

}  // namespace
}  // namespace lrigid
