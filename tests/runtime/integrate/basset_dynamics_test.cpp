// Basset history force in the step, on the case with a closed form: a light sphere released
// from rest in fluid at rest, Stokes regime (Re ~ 4e-4). Maxey-Riley with the history term:
//   M_eff v' = (m - m_f) g - 6 pi mu a v - C int_0^t v'(s) / sqrt(t - s) ds,  M_eff = m + m_f/2
// Laplace transform: V(s) = gamma / (s (s + beta sqrt(pi s) + alpha)) with alpha = 6 pi mu a /
// M_eff, beta = C / M_eff, gamma = (m - m_f) g / M_eff. For rho_p / rho_f < 0.625 the roots r1,
// r2 of x^2 + beta sqrt(pi) x + alpha are real and negative, and with a_i = -r_i
//   v(t) = gamma / (r1 - r2) [(1 - erfcx(a1 sqrt t)) / a1 - (1 - erfcx(a2 sqrt t)) / a2]
// (erfcx(x) = exp(x^2) erfc(x)), from L^-1{1/(s (sqrt s + a))} = (1 - erfcx(a sqrt t)) / a.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "effects/basset.h"
#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

double erfcx(double x) {
  if (x < 20) return std::exp(x * x) * std::erfc(x);
  const double x2 = x * x;
  return 1.0 / (x * std::sqrt(M_PI)) * (1 - 0.5 / x2 + 0.75 / (x2 * x2));
}

struct BassetCase {
  double a = 5e-6, rho_p = 250, rho = 1000, nu = 1e-6, g = 9.81;
  double m() const { return rho_p * 4.0 / 3.0 * M_PI * a * a * a; }
  double mf() const { return rho * 4.0 / 3.0 * M_PI * a * a * a; }
  double M() const { return m() + 0.5 * mf(); }
  double alpha() const { return 6 * M_PI * rho * nu * a / M(); }
  double beta() const { return 6 * a * a * rho * std::sqrt(M_PI * nu) / M(); }
  double gamma() const { return (m() - mf()) * -g / M(); }  // along z (negative: rises)
  double exact(double t) const {
    const double b = beta() * std::sqrt(M_PI), disc = b * b - 4 * alpha();
    const double r1 = (-b + std::sqrt(disc)) / 2, r2 = (-b - std::sqrt(disc)) / 2;
    const double a1 = -r1, a2 = -r2, st = std::sqrt(t);
    return gamma() / (r1 - r2) * ((1 - erfcx(a1 * st)) / a1 - (1 - erfcx(a2 * st)) / a2);
  }
  double no_history(double t) const {  // same without the Basset term
    return gamma() / alpha() * (1 - std::exp(-alpha() * t));
  }
};

// v_z(t) of the sphere; window > 0 replaces the kernel by a direct full-history quadrature
std::vector<std::pair<double, double>> run(const BassetCase& c, double dt, double T, bool basset,
                                           int direct_window = 0,
                                           Integrator integ = Integrator::Splitting) {
  Scene s = test::sphere_scene(c.a, c.rho_p, c.rho, c.nu);
  s.integrator = integ;
  s.gravity = Vec3(0, 0, -c.g);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag});
  if (basset) s.effects.add(Effect::Basset);
  s.dt = dt;
  s.duration = T;
  Model m = test::compile(s);
  if (direct_window > 0) {
    BassetKernel& k = m.types[0].basset;
    const Mat6 inv = k.implicit_inv;
    k = make_basset_kernel(k.coef, dt, direct_window, T);
    k.decay.clear(), k.inject.clear(), k.lambda.clear(), k.weight.clear();
    k.implicit_inv = inv;
  }
  State st = initial_state(m, s);
  std::vector<std::pair<double, double>> out;
  RunOptions opt;
  opt.every = T / 40;
  opt.threads = 1;
  opt.on_output = [&](const State& x) {
    out.emplace_back(x.t, (x.q[0].toRotationMatrix() * x.v[0]).z());
  };
  simulate(m, &st, opt);
  return out;
}

TEST(BassetDynamics, SphereFromRestMatchesTheClosedForm) {
  const BassetCase c;
  const double tau = 1 / c.alpha();   // ~4 microseconds
  const double dt = tau / 400, T = 20 * tau;
  const double v_term = c.gamma() / c.alpha();
  const auto with = run(c, dt, T, true);
  const auto without = run(c, dt, T, false);
  double err = 0, gap = 0;
  for (size_t i = 1; i < with.size(); ++i) {
    const double t = with[i].first;
    err = std::max(err, std::abs(with[i].second - c.exact(t)));
    gap = std::max(gap, std::abs(c.exact(t) - c.no_history(t)));
    EXPECT_NEAR(without[i].second, c.no_history(t), 5e-3 * std::abs(v_term)) << t;
  }
  std::printf("Basset, sphere from rest: max |v - v_exact| = %.2e of v_terminal over 20 tau_p "
              "(history effect itself: %.2f of v_terminal)\n",
              err / std::abs(v_term), gap / std::abs(v_term));
  EXPECT_LT(err, 5e-3 * std::abs(v_term));
  EXPECT_GT(gap, 20 * err) << "the history force must matter in this case";
  RecordProperty("max_error_rel_terminal", std::to_string(err / std::abs(v_term)));
}

TEST(BassetDynamics, EulerAndRk4AlsoMatchTheClosedForm) {
  // the history force enters both step forms (impulse form: euler; velocity form: rk4)
  const BassetCase c;
  const double tau = 1 / c.alpha(), dt = tau / 400, T = 20 * tau;
  const double v_term = std::abs(c.gamma() / c.alpha());
  for (Integrator integ : {Integrator::Euler, Integrator::RK4}) {
    const auto v = run(c, dt, T, true, 0, integ);
    double err = 0;
    for (size_t i = 1; i < v.size(); ++i)
      err = std::max(err, std::abs(v[i].second - c.exact(v[i].first)));
    std::printf("Basset, %s: max |v - v_exact| = %.2e of v_terminal\n", integrator_name(integ),
                err / v_term);
    EXPECT_LT(err, 5e-3 * v_term) << integrator_name(integ);
  }
}

TEST(BassetDynamics, FastKernelMatchesFullHistoryQuadrature) {
  const BassetCase c;
  const double tau = 1 / c.alpha();
  const double dt = tau / 100, T = 20 * tau;
  const int steps = int(std::llround(T / dt));
  const auto fast = run(c, dt, T, true);
  const auto direct = run(c, dt, T, true, steps + 2);
  const double v_term = std::abs(c.gamma() / c.alpha());
  double err = 0;
  for (size_t i = 0; i < fast.size(); ++i)
    err = std::max(err, std::abs(fast[i].second - direct[i].second));
  std::printf("Basset: window %d + exponential tail vs full history: max diff %.2e of "
              "v_terminal\n", kBassetWindow, err / v_term);
  EXPECT_LT(err, 5e-4 * v_term);  // the history effect itself is 0.5 v_terminal
}

}  // namespace
}  // namespace lrigid
