// Reduced accuracy study (docs/accuracy.md): measured convergence orders of the
// integrators against the orders docs/physics/integrators.md states.
//   deterministic: euler 1, rk4 4, splitting 1 (its deterministic part is a linearly implicit
//   Euler step);
//   stochastic (additive noise): strong order 1 and weak order 1 for euler and splitting.
// Errors are measured against a run of the same scheme family at a much finer step; for the
// stochastic runs every step size sees the same Brownian path (Model::noise_substeps), so the
// strong error is pathwise and the weak error is a paired difference with a small Monte Carlo
// error. Slopes are least-squares fits of log(error) against log(dt).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "accuracy/cases.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

using test::compile;
using test::effects;
using accuracy::sinking_sphere;
using accuracy::tumbling_ellipsoid;

struct Run {
  std::vector<Vec3> x;       // final positions, m
  std::vector<Vec3> u_seen;  // final seen turbulent velocities, m/s
};

Run run(Scene s, Integrator integ, double dt, uint32_t substeps) {
  s.integrator = integ;
  s.dt = dt;
  Model m = compile(s);
  m.noise_substeps = substeps;
  State st = initial_state(m, s);
  RunOptions opt;
  opt.every = s.duration;
  opt.threads = 1;
  const RunStats stats = simulate(m, &st, opt);
  EXPECT_EQ(stats.failed, 0u);
  return {st.x, st.u_seen};
}

double rms_diff(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]).squaredNorm();
  return std::sqrt(s / double(a.size()));
}

// deterministic order: errors of the final positions against rk4 at dt_ref
// least-squares slope of log(err) against log(dt): the observed order
double log_log_slope(const std::vector<double>& dt, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(dt.size());
  for (size_t i = 0; i < dt.size(); ++i) {
    const double x = std::log(dt[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double deterministic_slope(const Scene& s, Integrator integ, const std::vector<double>& dts,
                           double dt_ref, const char* label) {
  const Run ref = run(s, Integrator::RK4, dt_ref, 1);
  std::vector<double> err;
  for (double dt : dts) {
    err.push_back(rms_diff(run(s, integ, dt, 1).x, ref.x));
    std::printf("%s %s dt %.3g s: error %.3e m\n", label, integrator_name(integ), dt, err.back());
  }
  const double p = log_log_slope(dts, err);
  std::printf("%s %s: slope %.2f\n", label, integrator_name(integ), p);
  return p;
}

TEST(Convergence, DeterministicOrdersOnASinkingSphere) {
  const Scene s = sinking_sphere();
  const std::vector<double> dts = {2e-3, 1e-3, 5e-4, 2.5e-4};
  // expected 1, 4, 1; tolerance +-0.25 on the first-order schemes, +-0.5 on rk4
  EXPECT_NEAR(deterministic_slope(s, Integrator::Euler, dts, 1e-5, "sphere"), 1.0, 0.25);
  EXPECT_NEAR(deterministic_slope(s, Integrator::Splitting, dts, 1e-5, "sphere"), 1.0, 0.25);
  EXPECT_NEAR(deterministic_slope(s, Integrator::RK4, dts, 1e-5, "sphere"), 4.0, 0.5);
}

TEST(Convergence, DeterministicOrdersOnATumblingEllipsoid) {
  const Scene s = tumbling_ellipsoid();
  const std::vector<double> dts = {4e-3, 2e-3, 1e-3, 5e-4};
  EXPECT_NEAR(deterministic_slope(s, Integrator::Euler, dts, 5e-5, "ellipsoid"), 1.0, 0.25);
  EXPECT_NEAR(deterministic_slope(s, Integrator::Splitting, dts, 5e-5, "ellipsoid"), 1.0, 0.25);
  EXPECT_NEAR(deterministic_slope(s, Integrator::RK4, dts, 5e-5, "ellipsoid"), 4.0, 0.5);
}

// small spheres in uniform turbulence (seen model): du' = -alpha u' dt + beta dW with drag
// coupling the body to u'
Scene ou_scene(int count) {
  Scene s = test::sphere_scene(2e-3, 1000, 998.2, 1e-6, count);
  s.uniform_k = 1e-3;     // m^2/s^2
  s.uniform_epsilon = 5e-4;  // m^3/s^3
  s.effects = effects({Effect::Buoyancy, Effect::Gravity, Effect::AddedMass, Effect::Drag,
                       Effect::MeanFlow, Effect::Turbulence});
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(-0.1, -0.1, -0.1);
  s.bodies[0].box_hi = Vec3(0.1, 0.1, 0.1);
  s.duration = 2.0;
  s.seed = 11;
  return s;
}

struct StochasticOrders {
  double strong, weak;
};

// strong: RMS over bodies of |x - x_ref| at T on the same Brownian path; weak: the paired
// difference of the position variance, |Var x - Var x_ref| (m^2)
StochasticOrders stochastic_slopes(Integrator integ) {
  const Scene s = ou_scene(1000);
  const double h = 1e-3;
  const Run ref = run(s, Integrator::Splitting, h, 1);
  auto variance = [](const std::vector<Vec3>& x) {
    Vec3 m = Vec3::Zero();
    for (const auto& p : x) m += p;
    m /= double(x.size());
    double v = 0;
    for (const auto& p : x) v += (p - m).squaredNorm();
    return v / double(x.size() - 1);
  };
  const double var_ref = variance(ref.x);
  std::vector<double> dts, strong, weak;
  for (int r : {10, 20, 40, 80}) {
    const Run a = run(s, integ, r * h, static_cast<uint32_t>(r));
    dts.push_back(r * h);
    strong.push_back(rms_diff(a.x, ref.x));
    weak.push_back(std::abs(variance(a.x) - var_ref));
    std::printf("ou %s dt %.3g s: strong %.3e m, weak (variance) %.3e m^2 of %.3e\n",
                integrator_name(integ), r * h, strong.back(), weak.back(), var_ref);
  }
  StochasticOrders o{log_log_slope(dts, strong), log_log_slope(dts, weak)};
  std::printf("ou %s: strong slope %.2f, weak slope %.2f\n", integrator_name(integ), o.strong,
              o.weak);
  return o;
}

TEST(Convergence, StochasticOrdersOfEulerMaruyama) {
  const StochasticOrders o = stochastic_slopes(Integrator::Euler);
  EXPECT_NEAR(o.strong, 1.0, 0.3);
  EXPECT_NEAR(o.weak, 1.0, 0.3);
}

TEST(Convergence, StochasticOrdersOfTheSplitting) {
  const StochasticOrders o = stochastic_slopes(Integrator::Splitting);
  EXPECT_NEAR(o.strong, 1.0, 0.3);
  EXPECT_NEAR(o.weak, 1.0, 0.3);
}

}  // namespace
}  // namespace lrigid
