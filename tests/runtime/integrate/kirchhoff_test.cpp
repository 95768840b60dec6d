// Rigid-body invariants of the generalized Kirchhoff equations (Lamb §124): force-free motion in
// fluid at rest conserves the energy 1/2 xi.M xi, the impulse R P (world frame), |P| and P.L; the
// Munk moment turns a prolate body broadside; orientation stays a unit quaternion.
#include <gtest/gtest.h>

#include <cmath>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

Scene ellipsoid_scene(double a, double b, double c, double density) {
  Scene s = test::sphere_scene(1, density, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(a, b, c);
  return s;
}

Vec6 momentum(const Model& m, const State& st) {
  Vec6 xi;
  xi << st.v[0], st.w[0];
  return m.types[0].M * xi;
}

TEST(Kirchhoff, ForceFreeMotionConservesEnergyAndMomenta) {
  Scene s = ellipsoid_scene(0.03, 0.02, 0.01, 500);  // light: added mass comparable to mass
  s.effects = test::effects({Effect::AddedMass});
  s.integrator = Integrator::RK4;
  s.dt = 1e-3;
  s.duration = 10;  // 1e4 steps
  s.bodies[0].velocity = Vec3(0.3, 0.1, -0.2);
  s.bodies[0].angular_velocity = Vec3(2, -1, 3);
  s.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
  const Model m = test::compile(s);
  // the coupled tensor: translation and rotation parts of M must both be non-trivial
  ASSERT_GT(m.types[0].K_fluid(0, 0), 0.1 * m.types[0].mass);
  State st = initial_state(m, s);
  auto energy = [&](const State& x) {
    Vec6 xi;
    xi << x.v[0], x.w[0];
    return 0.5 * xi.dot(m.types[0].M * xi);
  };
  const double e0 = energy(st);
  const Vec6 p0 = momentum(m, st);
  const Vec3 P0w = st.q[0] * Vec3(p0.head<3>());
  double worst_e = 0, worst_p = 0, worst_pl = 0, worst_pw = 0;
  RunOptions opt;
  opt.every = 0.5;
  opt.on_output = [&](const State& x) {
    const Vec6 p = momentum(m, x);
    worst_e = std::max(worst_e, std::abs(energy(x) / e0 - 1));
    worst_p = std::max(worst_p, std::abs(p.head<3>().norm() / p0.head<3>().norm() - 1));
    worst_pl = std::max(worst_pl, std::abs(p.head<3>().dot(p.tail<3>()) -
                                           p0.head<3>().dot(p0.tail<3>())) /
                                      (p0.head<3>().norm() * p0.tail<3>().norm()));
    worst_pw = std::max(worst_pw, (x.q[0] * Vec3(p.head<3>()) - P0w).norm() / P0w.norm());
  };
  simulate(m, &st, opt);
  EXPECT_LT(worst_e, 1e-6);
  EXPECT_LT(worst_p, 1e-6);
  EXPECT_LT(worst_pl, 1e-6);
  EXPECT_LT(worst_pw, 1e-6);
  // the motion really was non-trivial: the body turned far from its start
  EXPECT_LT(std::abs(st.q[0].dot(Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized())))), 0.99);
}

// The splitting scheme integrates the gyroscopic and Munk terms with the implicit midpoint rule
// and the Cayley rotation (integrate/dynamics.h, kirchhoff_flow), which keeps every quadratic
// invariant exactly: at a step 50 times coarser than above, on a light thin plate whose
// edgewise generalized mass is 1e-3 of its broadside one (the case most prone to blow up), in a
// uniform mean flow, the energy of the motion relative to the fluid, |P|, P.L and the world
// impulse R P stay constant to round-off and Newton tolerance.
TEST(Kirchhoff, SplittingKeepsTheInvariantsOfAThinLightPlateExactly) {
  Scene s = ellipsoid_scene(0.05, 0.05, 0.0005, 10);  // aspect 100, rho_b/rho_f = 0.01
  s.effects = test::effects({Effect::AddedMass, Effect::MeanFlow});
  s.uniform_U = Vec3(3, 0, 0);
  s.integrator = Integrator::Splitting;
  s.dt = 0.05;
  s.duration = 50;  // 1000 steps
  s.bodies[0].velocity = Vec3(2.5, 0.4, -0.3);
  s.bodies[0].angular_velocity = Vec3(2, -1, 3);
  s.bodies[0].orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
  const Model m = test::compile(s);
  const BodyType& t = m.types[0];
  ASSERT_LT(t.M(0, 0), 2e-3 * t.M(2, 2)) << "edgewise mass tiny against the broadside one";
  State st = initial_state(m, s);
  auto relative_impulse = [&](const State& x) {
    Vec6 xi_r;
    xi_r << x.v[0] - x.q[0].inverse() * s.uniform_U, x.w[0];
    return Vec6(t.M * xi_r);
  };
  auto energy = [&](const Vec6& Y) { return 0.5 * Y.dot(t.M_inv * Y); };
  const Vec6 Y0 = relative_impulse(st);
  const Vec3 P0w = st.q[0] * Vec3(Y0.head<3>());
  double worst_e = 0, worst_p = 0, worst_pl = 0, worst_pw = 0;
  RunOptions opt;
  opt.every = s.dt;
  opt.on_output = [&](const State& x) {
    const Vec6 Y = relative_impulse(x);
    worst_e = std::max(worst_e, std::abs(energy(Y) / energy(Y0) - 1));
    worst_p = std::max(worst_p, std::abs(Y.head<3>().norm() / Y0.head<3>().norm() - 1));
    worst_pl = std::max(worst_pl, std::abs(Y.head<3>().dot(Y.tail<3>()) -
                                           Y0.head<3>().dot(Y0.tail<3>())) /
                                      (Y0.head<3>().norm() * Y0.tail<3>().norm()));
    worst_pw = std::max(worst_pw, (x.q[0] * Vec3(Y.head<3>()) - P0w).norm() / P0w.norm());
  };
  const RunStats stats = simulate(m, &st, opt);
  EXPECT_EQ(stats.failed, 0u);
  EXPECT_LT(worst_e, 1e-9);
  EXPECT_LT(worst_p, 1e-9);
  EXPECT_LT(worst_pl, 1e-9);
  EXPECT_LT(worst_pw, 1e-9);
  EXPECT_LT(std::abs(st.q[0].dot(Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized())))), 0.99);
}

// angle between the body's long axis (body x) and its velocity, in degrees
double incidence(const State& st) {
  const Vec3 axis = st.q[0] * Vec3::UnitX();
  const Vec3 vel = st.q[0] * st.v[0];
  return std::acos(std::min(1.0, std::abs(axis.dot(vel)) / vel.norm())) * 180 / M_PI;
}

TEST(Kirchhoff, MunkMomentTurnsAProlateBodyBroadside) {
  double largest[2] = {0, 0};
  for (int with_am = 0; with_am < 2; ++with_am) {
    Scene s = ellipsoid_scene(0.06, 0.02, 0.02, 1000);
    s.effects = with_am ? test::effects({Effect::AddedMass}) : EffectSet{};
    s.integrator = Integrator::RK4;
    s.dt = 1e-3;
    s.duration = 3;
    // moving nearly along its axis: 5 degrees of incidence
    s.bodies[0].velocity = Vec3(std::cos(5 * M_PI / 180), std::sin(5 * M_PI / 180), 0);
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    RunOptions opt;
    opt.every = 0.01;
    opt.on_output = [&](const State& x) {
      largest[with_am] = std::max(largest[with_am], incidence(x));
    };
    simulate(m, &st, opt);
  }
  EXPECT_GT(largest[1], 80.0) << "with added mass the Munk moment turns it broadside";
  EXPECT_NEAR(largest[0], 5.0, 1e-6) << "without added mass nothing turns it";
}

TEST(Buoyancy, BottomHeavyBodyRightsItself) {
  Scene s = ellipsoid_scene(0.02, 0.02, 0.01, 1000);  // neutrally buoyant disk-like body
  s.bodies[0].mass_offset = Vec3(0, 0, -0.004);        // keel: centre of mass below the centroid
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

TEST(Kinematics, QuaternionStaysUnitOverAMillionSteps) {
  for (Integrator scheme : {Integrator::Euler, Integrator::RK4, Integrator::Splitting}) {
    Scene s = ellipsoid_scene(0.03, 0.02, 0.01, 800);
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

}  // namespace
}  // namespace lrigid
