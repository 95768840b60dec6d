// The scalar step (integrate/integrators.h): each scheme's recipe over the stages, against
// closed forms. A sphere spinning down in a viscous fluid (the Stokes torque 8 pi mu r^3 w is
// exactly linear in w) converges at each scheme's order (euler 1, splitting 1, strang 2, rk4 4);
// under a constant force (weight, buoyancy and the added mass) strang, splitting and rk4 follow
// the parabola exactly and euler's position lags it by a T h / 2, also in a step split at an
// impact inside it; a step that fails or leaves the fluid leaves the body as it was; the
// orientation stays a unit quaternion; noise substeps sum the finer steps' increments.
#include "integrate/integrators.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr Integrator kSchemes[] = {Integrator::Euler, Integrator::RK4, Integrator::Splitting,
                                   Integrator::Strang};

// Takes n steps of body 0 with step_body from b at t = 0.
void steps(const Model& m, int n, BodyState* b) {
  for (int k = 0; k < n; ++k) {
    std::string reason;
    ASSERT_EQ(step_body(m, m.types[0], 0, k, k * m.dt, b, &reason), StepOutcome::Ok) << reason;
  }
}

// A sphere of radius r (density rho_s) in a fluid at rest of viscosity mu, spinning about a
// fixed axis: its only wrench is the Stokes torque -8 pi mu r^3 w (no added mass of rotation), so
// w' = -lambda w with lambda = 8 pi mu r^3 / J = 15 mu / (rho_s r^2), and
// w(t) = w0 exp(-lambda t), the angle turned theta(t) = w0 (1 - exp(-lambda t)) / lambda.
// The errors at T with n and 2n steps: their ratio is 2^p for a scheme of order p.
TEST(Integrators, EachSchemeConvergesAtItsOrderOnASphereSpinningDown) {
  const double r = 0.01, rho_s = 1000, rho_f = 1000, lambda = 10, T = 0.4;
  const double mu = lambda * rho_s * r * r / 15;
  const Vec3 axis = Vec3(1, 2, 2) / 3.0;
  const double w0 = 10;
  const double w_exact = w0 * std::exp(-lambda * T);
  const double theta_exact = w0 * (1 - std::exp(-lambda * T)) / lambda;
  const struct {
    Integrator scheme;
    double order;
  } cases[] = {{Integrator::Euler, 1}, {Integrator::Splitting, 1}, {Integrator::Strang, 2},
               {Integrator::RK4, 4}};
  for (const auto& c : cases) {
    double err_w[2], err_theta[2];
    for (int i = 0; i < 2; ++i) {
      const int n = 80 << i;
      Scene s = test::sphere_scene(r, rho_s, rho_f, mu / rho_f);
      s.effects = test::effects({Effect::Drag});
      s.integrator = c.scheme;
      s.dt = T / n;
      const Model m = test::compile(s);
      BodyState b{Vec3::Zero(), Quat::Identity(), Vec3::Zero(), w0 * axis, Vec3::Zero()};
      steps(m, n, &b);
      EXPECT_EQ(b.v, Vec3::Zero()) << "no force on a sphere spinning in fluid at rest";
      EXPECT_LT((b.w - b.w.dot(axis) * axis).norm(), 1e-12) << "it spins about its axis";
      // the turn about the axis (q and the axis: body and world frames agree on it)
      const double theta = 2 * std::atan2(b.q.vec().dot(axis), b.q.w());
      err_w[i] = std::abs(b.w.dot(axis) - w_exact);
      err_theta[i] = std::abs(theta - theta_exact);
    }
    const double p_w = std::log2(err_w[0] / err_w[1]);
    const double p_theta = std::log2(err_theta[0] / err_theta[1]);
    std::printf("%s: spin error %.3g rad/s (order %.3f), angle error %.3g rad (order %.3f)\n",
                integrator_name(c.scheme), err_w[1], p_w, err_theta[1], p_theta);
    EXPECT_NEAR(p_w, c.order, 0.1) << integrator_name(c.scheme);
    EXPECT_NEAR(p_theta, c.order, 0.1) << integrator_name(c.scheme);
  }
}

// A sphere denser than the fluid, with its weight, its buoyancy and its added mass
// m_a = rho V / 2: a = (m - rho V) g / (m + m_a), x(t) = x0 + v0 t + a t^2 / 2. Strang,
// splitting and rk4 take it exactly (trapezoidal positions, forces constant); euler's positions
// use the velocity at the start of each step, x_n = x(t_n) - a t_n h / 2. Split at tau inside a
// step (step_body_split, what an impact inside the step takes), the state handed to the split
// is the scheme's at t + tau, and the step goes on from what the split made of it (here a kick
// dv).
TEST(Integrators, UnderAConstantForceEachSchemeFollowsItsClosedFormAlsoSplitInsideAStep) {
  const double r = 0.01, rho_s = 2500, rho_f = 1000, h = 0.01;
  const int n = 50;
  Scene s = test::sphere_scene(r, rho_s, rho_f, 1e-6);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass});
  s.dt = h;
  const double V = 4.0 / 3.0 * M_PI * r * r * r, mass = rho_s * V;
  const Vec3 a = (mass - rho_f * V) / (mass + 0.5 * rho_f * V) * s.gravity;
  const Vec3 x0(0.1, -0.2, 0.3), v0(0.3, -0.2, 0.5);
  const Quat q0(Eigen::AngleAxisd(0.8, Vec3(-1, 2, 1).normalized()));
  const double tol = 1e-12;
  for (const Integrator scheme : kSchemes) {
    SCOPED_TRACE(integrator_name(scheme));
    s.integrator = scheme;
    const Model m = test::compile(s);
    const bool euler = scheme == Integrator::Euler;
    BodyState b{x0, q0, q0.inverse() * v0, Vec3::Zero(), Vec3::Zero()};
    steps(m, n, &b);
    const double T = n * h;
    const Vec3 x = x0 + v0 * T + 0.5 * a * T * T - (euler ? 0.5 * T * h : 0.0) * a;
    EXPECT_TRUE(test::near(b.x, x, tol));
    EXPECT_TRUE(test::near(Vec3(b.q * b.v), Vec3(v0 + a * T), tol));
    EXPECT_TRUE(test::near(b.w, Vec3::Zero(), tol));
    EXPECT_NEAR(std::abs(b.q.dot(q0)), 1.0, tol) << "no torque: the orientation is kept";

    // one step split at tau = 0.3 h, with a kick dv there
    const double tau = 0.3 * h;
    const Vec3 dv(0, 0.2, 1.0);
    BodyState c{x0, q0, q0.inverse() * v0, Vec3::Zero(), Vec3::Zero()};
    double t_split = -1;
    Vec3 x_split = Vec3::Constant(std::numeric_limits<double>::quiet_NaN()), v_split = x_split;
    const SplitAt kick = [&](double t, BodyState* at) {
      t_split = t;
      x_split = at->x;
      v_split = at->q * at->v;
      at->v += at->q.inverse() * dv;
    };
    std::string reason;
    ASSERT_EQ(step_body_split(m, m.types[0], 0, 0, 0.0, tau, kick, &c, &reason), StepOutcome::Ok)
        << reason;
    EXPECT_DOUBLE_EQ(t_split, tau);
    EXPECT_TRUE(test::near(x_split, Vec3(x0 + v0 * tau + (euler ? 0.0 : 0.5 * tau * tau) * a), tol));
    EXPECT_TRUE(test::near(v_split, Vec3(v0 + a * tau), tol));
    const double rest = h - tau;
    const Vec3 v1 = v_split + dv;
    const Vec3 x_end = x_split + v1 * rest + (euler ? 0.0 : 0.5 * rest * rest) * a;
    EXPECT_TRUE(test::near(c.x, x_end, tol));
    EXPECT_TRUE(test::near(Vec3(c.q * c.v), Vec3(v1 + a * rest), tol));
  }
}

// On Exited and Failed the body is left as it was before the step, and the reason says why: a
// step that carries the body out of a grid, and one from a non-finite velocity (failed, though
// its position samples as outside); the same body left as it was by the deterministic part
// alone (deterministic_substep).
TEST(Integrators, AStepThatFailsOrLeavesTheFluidLeavesTheBodyAsItWas) {
  const GridGeometry g = test::grid_geometry(3, 3, 3, Vec3::Zero(), Vec3(1, 1, 1));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3&, Vec3* U, double* k, double* eps) {
    *U = Vec3(0.5, 0, 0);
    *k = 0.01, *eps = 0.01;
    return true;
  });
  auto same = [](const BodyState& a, const BodyState& b) {
    // bitwise, so that a NaN left in place compares equal
    return std::memcmp(a.x.data(), b.x.data(), sizeof(Vec3)) == 0 &&
           std::memcmp(a.q.coeffs().data(), b.q.coeffs().data(), 4 * sizeof(double)) == 0 &&
           std::memcmp(a.v.data(), b.v.data(), sizeof(Vec3)) == 0 &&
           std::memcmp(a.w.data(), b.w.data(), sizeof(Vec3)) == 0 &&
           std::memcmp(a.u_seen.data(), b.u_seen.data(), sizeof(Vec3)) == 0;
  };
  for (const Integrator scheme : kSchemes) {
    SCOPED_TRACE(integrator_name(scheme));
    Scene s = test::sphere_scene(0.01, 2500, 1.2, 1.5e-5);
    s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::MeanFlow,
                               Effect::Turbulence});
    s.uniform_field = false;
    s.integrator = scheme;
    s.dt = 0.01;
    const Model m = test::compile(s, FluidField::grid(g, {f}, 1.5e-5, s.drift, TimeMode::Clamp));
    const Quat q(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
    // 0.5 cm from the grid's +x face, 1 m/s towards it: out within the step
    const BodyState leaving{Vec3(1.995, 1, 1), q, q.inverse() * Vec3(1, 0, 0), Vec3(1, 2, 3),
                            Vec3(0.01, 0.02, 0.03)};
    BodyState b = leaving;
    std::string reason;
    EXPECT_EQ(step_body(m, m.types[0], 0, 0, 0.0, &b, &reason), StepOutcome::Exited);
    EXPECT_NE(reason.find("left the fluid"), std::string::npos) << reason;
    EXPECT_TRUE(same(b, leaving));
    b = leaving;
    EXPECT_EQ(deterministic_substep(m, m.types[0], 0.0, m.dt, &b), StepOutcome::Exited);
    EXPECT_TRUE(same(b, leaving));
    // the same body in the middle of the grid takes the step
    BodyState inside = leaving;
    inside.x = Vec3(1, 1, 1);
    b = inside;
    EXPECT_EQ(step_body(m, m.types[0], 0, 0, 0.0, &b, &reason), StepOutcome::Ok) << reason;
    EXPECT_FALSE(same(b, inside));
    // a non-finite velocity: failed, not exited, though its position samples as outside
    BodyState broken = inside;
    broken.v.x() = std::numeric_limits<double>::quiet_NaN();
    b = broken;
    reason.clear();
    EXPECT_EQ(step_body(m, m.types[0], 0, 0, 0.0, &b, &reason), StepOutcome::Failed);
    EXPECT_EQ(reason.rfind("non-finite ", 0), 0u) << reason;
    EXPECT_TRUE(same(b, broken));
    // (the deterministic part alone reports it as leaving the fluid: its end samples outside
    // before its state is checked; its one caller treats both alike)
    b = broken;
    EXPECT_NE(deterministic_substep(m, m.types[0], 0.0, m.dt, &b), StepOutcome::Ok);
    EXPECT_TRUE(same(b, broken));
  }
}

// Every orientation update multiplies by a unit quaternion and renormalizes (integrators.h):
// after a million steps of a tumbling body |q| - 1 and R^T R - I stay at round-off.
TEST(Kinematics, QuaternionStaysUnitOverAMillionSteps) {
  for (Integrator scheme : {Integrator::Euler, Integrator::RK4, Integrator::Splitting}) {
    Scene s = test::sphere_scene(1, 800, 1000, 1e-6);
    s.bodies[0].shape = Shape::ellipsoid(0.03, 0.02, 0.01);
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

// With noise_substeps = r, a step of r h sees the sum of the r increments a run with step h sees:
// the two runs follow the same Brownian path (what the strong-error study needs). For slow
// decay (alpha T << 1) the velocity is ~ beta W(T), so both runs must end close together,
// while a different seed ends far away.
TEST(BrownianPath, CoarseStepsSumTheFineIncrements) {
  for (Integrator scheme : {Integrator::Euler, Integrator::Splitting}) {
    auto final_velocity = [&](double dt, uint32_t r, uint64_t seed) {
      // 50 bodies of the "body" turbulence model at the origin, turbulence only
      Scene s = test::sphere_scene(0.001, 1000, 1000, 1e-6, 50);
      s.effects = test::effects({Effect::Turbulence});
      s.turbulence_model = TurbulenceModel::Body;
      s.drift = Drift::Stationary;
      s.integrator = scheme;
      s.dt = dt;
      s.uniform_k = 1.0;
      s.uniform_epsilon = 1e-3;  // alpha ~ 5e-3 1/s: over 1 s the path is ~ beta W
      s.seed = seed;
      s.duration = 1.0;
      Model m = test::compile(s);
      m.noise_substeps = r;
      State st = initial_state(m, s);
      simulate(m, &st, RunOptions{});
      return st;
    };
    const State coarse = final_velocity(0.04, 4, 9), fine = final_velocity(0.01, 1, 9),
                other = final_velocity(0.01, 1, 10);
    double same = 0, diff = 0;
    for (size_t i = 0; i < coarse.size(); ++i) {
      same = std::max(same, (coarse.u_seen[i] - fine.u_seen[i]).norm());
      diff = std::max(diff, (other.u_seen[i] - fine.u_seen[i]).norm());
    }
    EXPECT_LT(same, 0.02 * diff) << integrator_name(scheme);
  }
}

}  // namespace
}  // namespace lrigid
