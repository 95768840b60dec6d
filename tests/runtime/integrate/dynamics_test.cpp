// The generalized Kirchhoff equations of one body (integrate/dynamics.h): the acceleration and
// the impulse form's rates, each effect's exact share of them, the impulse and its inverse; the
// free Kirchhoff flow (kirchhoff_flow) against Euler's equations of a symmetric top and the
// invariants of Lamb §124 (force-free motion in fluid at rest conserves the energy
// 1/2 xi.M xi, the world impulse R P, |P| and P.L; the Munk moment turns a prolate body
// broadside); the structured mass paths (diagonal M, a sphere's closed-form flow) against the
// general one.
#include "integrate/dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compile/compile_model.h"
#include "effects/basset.h"
#include "effects/plan.h"
#include "effects/registry.h"
#include "integrate/integrators.h"
#include "integrate/simulation.h"
#include "model/state.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

Scene plate_scene(EffectSet e) {
  Scene s = test::sphere_scene(1, 1200, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(0.02, 0.05, 0.002);
  s.bodies[0].mass_offset = Vec3(0.001, 0, -0.0002);
  s.uniform_U = Vec3(0.3, -0.1, 0.05);
  s.effects = e;
  return s;
}

// Every effect of the registry, one at a time, on a flat body with an offset centre of mass in
// a mean flow, spinning: each effect that is a wrench term for it (all but the added mass, which
// is in M itself, and the effects that move the fluid) changes the acceleration by exactly
// M^-1 times its term.
TEST(EffectSwitch, EachEffectChangesTheAccelerationByExactlyItsTerm) {
  EffectSet all;
  for (const EffectInfo& info : all_effects())
    if (info.effect != Effect::Turbulence) all.add(info.effect);  // (no seen fluctuation here)
  const Model on = test::compile(plate_scene(all));
  ASSERT_TRUE(on.types[0].flat);
  // a Basset history with a non-zero cached integral
  std::vector<double> hist(on.types[0].basset.stride(), 0.0);
  hist[3] = 0.02, hist[4] = -0.01, hist[5] = 0.03;
  Kinematics k{Vec3(0, 0, 0), Quat(0.9, 0.1, -0.3, 0.2).normalized().toRotationMatrix(),
               Vec3(0.1, 0.2, -0.3), Vec3(1.5, -2.0, 0.7), Vec3::Zero(), hist.data()};
  int switched = 0;
  for (const EffectInfo& info : all_effects()) {
    const Effect e = info.effect;
    if (e == Effect::AddedMass || !wrench_term(on.types[0], e)) continue;
    ++switched;
    EffectSet less = all;
    less.remove(e);
    const Model off = test::compile(plate_scene(less));
    Vec6 a_on, a_off;
    FluidSample fs;
    ASSERT_EQ(velocity_derivative(on, on.types[0], k, 0, &a_on, &fs), EvalResult::Ok);
    ASSERT_EQ(velocity_derivative(off, off.types[0], k, 0, &a_off, &fs), EvalResult::Ok);
    // the effect's own term in the same context
    EffectContext c;
    Vec3 uf;
    ASSERT_TRUE(effect_context(on, on.types[0], k, 0, false, &fs, &c, &uf));
    Vec6 term = wrench_term(on.types[0], e)(c);
    EXPECT_GT(term.norm(), 0) << info.name;
    if (e == Effect::Drag) {
      // the plate's separated flow comes with its drag: the share of the Munk moment it takes
      // back (BodyType::munk_back, written in the added-mass terms) goes with the drag's term
      const Mat3& S = on.types[0].munk_back;
      ASSERT_GT(S.norm(), 0);
      EXPECT_TRUE(off.types[0].munk_back.isZero(0.0));
      term.tail<3>() += c.v_rel.cross(S * c.v_rel);
    }
    EXPECT_TRUE(test::near(Vec6(a_on - a_off), Vec6(on.types[0].M_inv * term),
                           1e-12 * (1 + a_on.norm())))
        << info.name;
    // impulse form: the rates differ by the same wrench
    ImpulseRates r_on, r_off;
    ASSERT_EQ(impulse_rates(on, on.types[0], k, 0, &r_on, nullptr), EvalResult::Ok);
    ASSERT_EQ(impulse_rates(off, off.types[0], k, 0, &r_off, nullptr), EvalResult::Ok);
    EXPECT_TRUE(test::near(Vec6(r_on.rate - r_off.rate), term, 1e-12 * (1 + r_on.rate.norm())));
  }
  EXPECT_GE(switched, 6);  // gravity, buoyancy, drag, lift, Magnus, Basset at least
}

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

// The mass paths: a diagonal M takes element-wise products and the diagonal kernels
// (model/kirchhoff.h DiagonalMass), an isotropic one (a sphere) the free flow in closed form;
// with those flags cleared the same body takes the general 6 x 6 path, which must give the same
// motion.

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

TEST(MassPaths, DiagonalShortcutMatchesTheGeneralPath) {
  for (Integrator integ : {Integrator::Splitting, Integrator::Euler, Integrator::RK4}) {
    SCOPED_TRACE(integrator_name(integ));
    const Model fast = test::compile(sheet_scene(integ));
    ASSERT_TRUE(fast.types[0].M_diagonal);
    Model general = fast;
    general.types[0].M_diagonal = false;
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

// A sphere's generalized mass: m + m_a on the translation (m_a = rho V / 2, Lamb §92), J on the
// rotation. Its acceleration from rest under weight and buoyancy is (m - rho V) g / (m + m_a) in
// any orientation, and in a uniform mean flow U its impulse is (m + m_a) v - m_a R^T U, which
// velocity_from_impulse turns back into its velocity.
TEST(Dynamics, ASpheresAccelerationAndImpulseAreItsClosedForms) {
  const double r = 0.01, rho_s = 2500, rho_f = 1000;
  Scene s = test::sphere_scene(r, rho_s, rho_f, 1e-6);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass,
                             Effect::MeanFlow});
  s.uniform_U = Vec3(0.4, -0.3, 0.1);
  const Model m = test::compile(s);
  const BodyType& t = m.types[0];
  const double V = 4.0 / 3.0 * M_PI * r * r * r, mass = rho_s * V, m_a = 0.5 * rho_f * V;
  const double J = 0.4 * mass * r * r;
  ASSERT_NEAR(t.mass, mass, 1e-12 * mass);
  const Mat3 R = Eigen::AngleAxisd(0.9, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  // moving with the fluid (no relative velocity, so no added-mass reaction), not spinning
  const Vec3 v_rest = R.transpose() * s.uniform_U;
  const Kinematics at_rest{Vec3::Zero(), R, v_rest, Vec3::Zero(), Vec3::Zero()};
  Vec6 xi_dot;
  FluidSample fs;
  ASSERT_EQ(velocity_derivative(m, t, at_rest, 0, &xi_dot, &fs), EvalResult::Ok);
  const Vec3 a = (mass - rho_f * V) / (mass + m_a) * (R.transpose() * s.gravity);
  EXPECT_TRUE(test::near(Vec3(xi_dot.head<3>()), a, 1e-9 * a.norm()));
  EXPECT_TRUE(test::near(Vec3(xi_dot.tail<3>()), Vec3::Zero(), 1e-12));
  // moving through the flow and spinning: the impulse, and back
  const Kinematics k{Vec3::Zero(), R, Vec3(0.2, 0.5, -0.7), Vec3(3, -1, 2), Vec3::Zero()};
  ImpulseRates rates;
  ASSERT_EQ(impulse_rates(m, t, k, 0, &rates, nullptr), EvalResult::Ok);
  EXPECT_TRUE(rates.fluid_inertia);
  const Vec3 P = (mass + m_a) * k.v - m_a * (R.transpose() * s.uniform_U);
  EXPECT_TRUE(test::near(Vec3(rates.impulse.head<3>()), P, 1e-9 * P.norm()));
  EXPECT_TRUE(test::near(Vec3(rates.impulse.tail<3>()), Vec3(J * k.w), 1e-9 * J * k.w.norm()));
  Vec6 xi;
  xi << k.v, k.w;
  EXPECT_TRUE(test::near(
      velocity_from_impulse(t, rates.impulse, R.transpose() * rates.u_fluid, true), xi,
      1e-12 * xi.norm()));
  // the impulse changes by the weight and buoyancy alone (world-frame rates: no gyroscopic term)
  const Vec3 F = (mass - rho_f * V) * (R.transpose() * s.gravity);
  EXPECT_TRUE(test::near(Vec3(rates.rate.head<3>()), F, 1e-9 * F.norm()));
}

// The free flow of a body without added mass in fluid at rest is Euler's torque-free rotation.
// For a symmetric top (I1 = I2) w3 stays constant and (w1, w2) turns at
// Omega = (I1 - I3) w3 / I1: w1(t) = w1 cos(Omega t) + w2 sin(Omega t),
// w2(t) = w2 cos(Omega t) - w1 sin(Omega t). The implicit midpoint rule is second order: halving
// h divides the error by 4.
TEST(Dynamics, TheFreeFlowOfASymmetricTopIsEulersRotationToSecondOrder) {
  Scene s = test::sphere_scene(1, 1000, 1000, 1e-6);
  s.bodies[0].shape = Shape::ellipsoid(0.03, 0.03, 0.01);
  const Model m = test::compile(s);
  const BodyType& t = m.types[0];
  const double I1 = t.M(3, 3), I3 = t.M(5, 5);
  ASSERT_NEAR(t.M(4, 4), I1, 1e-14 * I1);
  ASSERT_GT(std::abs(I1 - I3), 0.5 * I1);
  const Vec3 w0(1.0, 0.5, 5.0);
  const double T = 1.0, Omega = (I1 - I3) * w0.z() / I1;
  const Vec3 exact(w0.x() * std::cos(Omega * T) + w0.y() * std::sin(Omega * T),
                   w0.y() * std::cos(Omega * T) - w0.x() * std::sin(Omega * T), w0.z());
  double err[2];
  for (int i = 0; i < 2; ++i) {
    const int n = 50 << i;
    Quat q = Quat::Identity();
    Vec3 v = Vec3::Zero(), w = w0;
    for (int k = 0; k < n; ++k) kirchhoff_flow(t, Vec3::Zero(), T / n, &q, &v, &w);
    EXPECT_EQ(v, Vec3::Zero()) << "no force: the centre of mass stays at rest";
    err[i] = (w - exact).norm();
  }
  std::printf("symmetric top: error %.3g rad/s at h = %.3g s, %.3g at h/2\n", err[0], T / 50,
              err[1]);
  EXPECT_LT(err[1], 1e-3 * w0.norm());
  EXPECT_NEAR(std::log2(err[0] / err[1]), 2.0, 0.1);
}

}  // namespace
}  // namespace lrigid
