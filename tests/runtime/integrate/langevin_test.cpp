// Langevin statistics in a uniform field against Ornstein-Uhlenbeck theory (physics-notes §2):
// stationary variance beta^2/(2 alpha), autocorrelation exp(-alpha tau), the Euler-Maruyama
// variance bias 2/(2 - alpha h), and the well-mixed condition in a k gradient.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compile/compile_model.h"
#include "effects/turbulence.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr double kNu = 1e-6;

// nbody bodies of the given model at the origin in uniform turbulence (k, eps), turbulence only
Scene ou_scene(TurbulenceModel model, Drift drift, Integrator scheme, double dt, int nbody) {
  Scene s = test::sphere_scene(0.001, 1000, 1000, kNu, nbody);
  s.uniform_k = 0.06;
  s.uniform_epsilon = 0.02;
  s.effects = test::effects({Effect::Turbulence});
  if (model == TurbulenceModel::Seen) s.effects.add(Effect::Drag);
  s.turbulence_model = model;
  s.drift = drift;
  s.integrator = scheme;
  s.dt = dt;
  return s;
}

struct Stats {
  double var = 0;   // per-component variance
  double corr = 0;  // correlation between two times
};

// variance of the turbulent velocity at the last output and its correlation with the output
// `lag` seconds earlier, over all bodies and components
Stats measure(const Scene& s, double burn_in, double lag, bool seen) {
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  RunOptions opt;
  opt.every = lag;
  std::vector<std::vector<Vec3>> frames;
  opt.on_output = [&](const State& x) {
    std::vector<Vec3> u(x.size());
    // body model: the body's velocity R v + u' (v stays 0 without other effects)
    for (size_t i = 0; i < x.size(); ++i)
      u[i] = seen ? x.u_seen[i] : Vec3(x.q[i] * x.v[i] + x.u_seen[i]);
    frames.push_back(u);
  };
  Model mm = m;
  // a whole number of output intervals, so the last two outputs are exactly `lag` apart
  const double stride = double(output_stride(m, lag)) * m.dt;
  mm.duration = (std::ceil(burn_in / stride) + 1) * stride;
  simulate(mm, &st, opt);
  const auto& a = frames[frames.size() - 2];
  const auto& b = frames.back();
  double saa = 0, sbb = 0, sab = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      saa += a[i][c] * a[i][c];
      sbb += b[i][c] * b[i][c];
      sab += a[i][c] * b[i][c];
    }
  return Stats{sbb / (3.0 * b.size()), sab / std::sqrt(saa * sbb)};
}

struct OUCase {
  TurbulenceModel model;
  Drift drift;
  double alpha_dt;
};

class OUStatistics : public ::testing::TestWithParam<OUCase> {};

TEST_P(OUStatistics, ExactSchemeHasTheoreticalVarianceAndCorrelation) {
  const OUCase c = GetParam();
  const LangevinCoefficients lc = langevin_coefficients(0.06, 0.02, kNu, c.drift);
  const double dt = c.alpha_dt / lc.alpha;
  const int n = 20000;
  Scene s = ou_scene(c.model, c.drift, Integrator::Splitting, dt, n);
  const double lag = std::max(0.5 / lc.alpha, dt);
  const double lag_steps = std::round(lag / dt);
  const Stats st =
      measure(s, 8.0 / lc.alpha + dt, lag_steps * dt, c.model == TurbulenceModel::Seen);
  // Monte Carlo standard errors: var ~ sigma2 sqrt(2/(3n)); corr ~ (1 - rho^2)/sqrt(3n)
  const double se_var = lc.sigma2 * std::sqrt(2.0 / (3.0 * n));
  EXPECT_NEAR(st.var, lc.sigma2, 4 * se_var) << "alpha dt = " << c.alpha_dt;
  const double rho = std::exp(-lc.alpha * lag_steps * dt);
  EXPECT_NEAR(st.corr, rho, 4 * (1 - rho * rho) / std::sqrt(3.0 * n) + 1e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Models, OUStatistics,
    ::testing::Values(OUCase{TurbulenceModel::Body, Drift::Stationary, 0.1},
                      OUCase{TurbulenceModel::Body, Drift::Stationary, 1.0},
                      OUCase{TurbulenceModel::Body, Drift::Stationary, 5.0},
                      OUCase{TurbulenceModel::Body, Drift::Original, 0.5},
                      OUCase{TurbulenceModel::Seen, Drift::Stationary, 0.1},
                      OUCase{TurbulenceModel::Seen, Drift::Stationary, 5.0},
                      OUCase{TurbulenceModel::Seen, Drift::Original, 1.0}));

TEST(OUStatistics, StationaryDriftReproducesTheFieldsK) {
  // <u_i^2> = 2k/3 with the stationary drift (what a frozen RANS field should give)
  const int n = 20000;
  const Scene s =
      ou_scene(TurbulenceModel::Body, Drift::Stationary, Integrator::Splitting, 0.01, n);
  const Stats st = measure(s, 3.0, 0.1, false);
  EXPECT_NEAR(st.var, 2.0 / 3.0 * 0.06, 4 * 0.04 * std::sqrt(2.0 / (3.0 * n)));
}

TEST(OUStatistics, EulerMaruyamaVarianceIsBiasedAsTheoryPredicts) {
  // explicit update: stationary variance sigma2 * 2 / (2 - alpha h)
  const LangevinCoefficients lc = langevin_coefficients(0.06, 0.02, kNu, Drift::Stationary);
  const double ah = 0.5;
  const int n = 20000;
  const Scene s = ou_scene(TurbulenceModel::Body, Drift::Stationary, Integrator::Euler,
                           ah / lc.alpha, n);
  const Stats st = measure(s, 10.0 / lc.alpha, ah / lc.alpha, false);
  const double expect = lc.sigma2 * 2.0 / (2.0 - ah);
  EXPECT_NEAR(st.var, expect, 4 * expect * std::sqrt(2.0 / (3.0 * n)));
  EXPECT_GT(st.var, 1.15 * lc.sigma2);  // clearly not the exact value
}

// Tracers in a field whose k grows along x stay uniformly spread (Thomson's well-mixed
// condition); without the drift correction they drain towards low k.
// Returns the counts in 8 bins across [-2, 2] m after 8 s.
std::vector<int> tracer_bins(bool correction, int n,
                             TurbulenceModel model = TurbulenceModel::Seen) {
  const GridGeometry g = test::grid_geometry(81, 2, 2, Vec3(-20, -50, -50), Vec3(0.5, 100, 100));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3& x, Vec3*, double* k, double* eps) {
    // k from 0.02 to 0.32 m^2/s^2 across |x| < 1.5 m; eps/k = 0.5 1/s, T_L ~ 0.44 s
    *k = 0.17 + 0.15 * std::tanh(x.x() / 1.0);
    *eps = 0.5 * *k;
    return true;
  });
  Scene s = test::sphere_scene(1e-4, 1000, 1000, kNu, n);
  s.effects = test::effects({Effect::Drag, Effect::Turbulence});
  s.turbulence_model = model;
  s.drift = Drift::Stationary;
  s.integrator = Integrator::Splitting;
  s.dt = 0.02;
  s.duration = 8;  // ~ 18 Lagrangian times
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(-8, -1, -1);
  s.bodies[0].box_hi = Vec3(8, 1, 1);
  const FluidField field =
      FluidField::grid(g, {f}, kNu, s.drift, TimeMode::Clamp);
  Model m = test::compile(s, field);
  m.well_mixed_correction = correction;
  State st = initial_state(m, s);
  simulate(m, &st, RunOptions{});
  std::vector<int> bins(8, 0);
  for (size_t i = 0; i < st.size(); ++i) {
    EXPECT_EQ(st.status[i], BodyStatus::Moving);
    const double x = st.x[i].x();
    if (x >= -2 && x < 2) ++bins[int((x + 2) / 0.5)];
  }
  return bins;
}

TEST(WellMixed, TracersStayUniformInAKGradient) {
  const int n = 30000;
  const std::vector<int> bins = tracer_bins(true, n);
  // uniform: n * 0.5/16 per bin
  const double expect = n * 0.5 / 16.0;
  const double se = std::sqrt(expect);
  // low-k side vs high-k side: the classic failure is a pile-up on the low-k side
  const double low = bins[0] + bins[1] + bins[2] + bins[3];
  const double high = bins[4] + bins[5] + bins[6] + bins[7];
  std::printf("well-mixed, corrected: low/high = %.4f (MC std err %.4f)\n", low / high,
              std::sqrt(2.0 / (4 * expect)));
  EXPECT_NEAR(low / high, 1.0, 4 * std::sqrt(2.0 / (4 * expect)));
  for (int b = 0; b < 8; ++b) EXPECT_NEAR(bins[b], expect, 4.5 * se) << "bin " << b;
}

TEST(WellMixed, WithoutTheDriftCorrectionTracersGatherAtLowK) {
  // the test above can fail: the uncorrected model visibly violates the condition
  const int n = 30000;
  const std::vector<int> bins = tracer_bins(false, n);
  const double low = bins[0] + bins[1] + bins[2] + bins[3];
  const double high = bins[4] + bins[5] + bins[6] + bins[7];
  const double expect = n * 0.5 / 16.0;
  std::printf("well-mixed, uncorrected: low/high = %.4f\n", low / high);
  EXPECT_GT(low / high - 1.0, 5 * std::sqrt(2.0 / (4 * expect)));
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

// The "body" model with drag on: drag acts on the body's own (non-turbulent) motion, the
// turbulent velocity u' moves the body directly, so the body's velocity variance is the field's
// 2k/3 for any dt (before, drag relaxed the fluctuation away within the step: ~beta^2 h / 2).
TEST(OUStatistics, BodyModelWithDragKeepsTheFieldsKForAnyDt) {
  for (double dt : {1e-3, 1e-2}) {
    const int n = 10000;  // 4 standard errors are 3 % of 2k/3
    Scene s = ou_scene(TurbulenceModel::Body, Drift::Stationary, Integrator::Splitting, dt, n);
    s.effects.add(Effect::Drag);
    const Stats st = measure(s, 3.0, 0.1, false);
    EXPECT_NEAR(st.var, 2.0 / 3.0 * 0.06, 4 * 0.04 * std::sqrt(2.0 / (3.0 * n))) << "dt " << dt;
  }
}

}  // namespace
}  // namespace lrigid

namespace lrigid {
namespace {

TEST(WellMixed, BodyModelTracersStayUniformToo) {
  const int n = 30000;
  const std::vector<int> bins = tracer_bins(true, n, TurbulenceModel::Body);
  const double low = bins[0] + bins[1] + bins[2] + bins[3];
  const double high = bins[4] + bins[5] + bins[6] + bins[7];
  const double expect = n * 0.5 / 16.0;
  std::printf("well-mixed, body model: low/high = %.4f\n", low / high);
  EXPECT_NEAR(low / high, 1.0, 4 * std::sqrt(2.0 / (4 * expect)));
}

// Heavy beads in a steep k gradient (k x 8000 over 3 m, eps/k = 0.2 1/s): the seen fluctuation must
// stay of the order of the local sigma. Thomson's drift with the tracer's transport velocity
// u' + U fed u' back into itself (du'/dt ~ u'^2 d ln sigma^2/dz), which blew beads that lag the
// fluid up to 150 m/s in the courtyard wind; along the body's own path the term is bounded.
TEST(WellMixed, SeenFluctuationOfHeavyBodiesStaysBoundedInASteepGradient) {
  const GridGeometry g = test::grid_geometry(2, 2, 61, Vec3(-50, -50, -0.5), Vec3(100, 100, 0.05));
  double k_max = 0;
  const RawGridFrame f = test::grid_frame(g, [&](const Vec3& x, Vec3*, double* k, double* eps) {
    *k = 1e-4 * std::exp(3.0 * (x.z() + 0.5));  // 1e-4 .. 0.8 m^2/s^2
    *eps = 0.2 * *k;
    k_max = std::max(k_max, *k);
    return true;
  });
  for (Integrator scheme : {Integrator::Splitting, Integrator::Euler}) {
    // 500 um glass beads in air, no gravity: they lag the fluid (response time ~1 s)
    Scene s = test::sphere_scene(2.5e-4, 2500, 1.2, 1.5e-5, 400);
    s.effects = test::effects({Effect::Drag, Effect::MeanFlow, Effect::Turbulence});
    s.integrator = scheme;
    s.dt = 2e-3;
    s.duration = 10;
    s.uniform_field = false;
    s.bodies[0].spawn_in_box = true;
    s.bodies[0].box_lo = Vec3(-1, -1, -0.4);
    s.bodies[0].box_hi = Vec3(1, 1, 2.4);
    Model m = test::compile(s, FluidField::grid(g, {f}, 1.5e-5, s.drift, TimeMode::Clamp));
    State st = initial_state(m, s);
    double worst = 0;
    RunOptions opt;
    opt.every = 0.05;
    opt.on_output = [&](const State& now) {
      for (size_t i = 0; i < now.size(); ++i)
        if (now.status[i] == BodyStatus::Moving) worst = std::max(worst, now.u_seen[i].norm());
    };
    simulate(m, &st, opt);
    const double sigma_max = std::sqrt(2.0 * k_max / 3.0);
    std::printf("%s: largest |u'| %.3g m/s, largest sigma %.3g m/s\n", integrator_name(scheme),
                worst, sigma_max);
    // 3 components, 400 bodies, 200 outputs: |u'| beyond 6 sigma is not a Gaussian sample
    EXPECT_LT(worst, 6 * sigma_max) << integrator_name(scheme);
    EXPECT_GT(worst, 0.5 * sigma_max) << integrator_name(scheme);  // the turbulence acted
  }
}

// Crossing trajectories (effects/turbulence.h, docs/physics/langevin.md): glass spheres of
// r = 20 um settling through uniform isotropic turbulence in air (u' = 0.1 m/s, no mean flow) at
// about 1.1 u'. With a linear response the body's velocity is the seen velocity filtered by a
// first-order lag of tau_p, which leaves the integral of its autocorrelation unchanged, so the
// long-time diffusivity along each axis is the seen process's own, sigma2 T_L / b: b along the
// drift, b' across it (the model's closed form). The displacement over a window dt of a
// stationary run has Var = 2 sigma2 T / (T^2 - tau^2) [T (T dt - T^2 (1 - e^{-dt/T})) -
// tau (tau dt - tau^2 (1 - e^{-dt/tau}))], T = T_L / b: checked within 3 Monte Carlo standard
// errors across (x, y) and along (z), for every scheme and both steps; and with the correction
// off, the tracer's time scale on both axes.
struct Diffusion {
  double var_across = 0, var_along = 0;  // of the displacement over the window, m^2
  double se_across = 0, se_along = 0;
  double expect_across = 0, expect_along = 0;
};

Diffusion settling_diffusion(Integrator scheme, bool batched, bool crossing) {
  const int n = 2500;
  Scene s = test::sphere_scene(20e-6, 2500, 1.2, 1.5e-5, n);
  s.uniform_k = 0.015;  // sigma2 = 2k/3 = 0.01 m^2/s^2
  s.uniform_epsilon = 0.005;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Turbulence});
  s.turbulence_model = TurbulenceModel::Seen;
  s.drift = Drift::Stationary;
  s.crossing_trajectories = crossing;
  s.integrator = scheme;
  s.batched = batched;
  s.dt = 2e-3;
  const double window = 4.0;  // after a burn-in of the same length (> 5 T_L)
  s.duration = 2 * window;
  const Model m = test::compile(s);
  const BodyType& t = m.types[0];
  EXPECT_EQ(step_kind(m, t, nullptr) == StepKind::Batched, batched);
  const LangevinCoefficients lc = langevin_coefficients(0.015, 0.005, 1.5e-5, Drift::Stationary);
  State st = initial_state(m, s);
  RunOptions opt;
  opt.every = window;
  std::vector<std::vector<Vec3>> x;
  opt.on_output = [&](const State& y) { x.push_back(y.x); };
  simulate(m, &st, opt);
  EXPECT_EQ(x.size(), 3u);
  Diffusion r;
  if (x.size() != 3) return r;
  // the sample variance of each component of the displacement
  double var[3];
  for (int c = 0; c < 3; ++c) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      const double d = x[2][i][c] - x[1][i][c];
      sum += d;
      sum2 += d * d;
    }
    var[c] = (sum2 - sum * sum / n) / (n - 1);
  }
  r.var_across = 0.5 * (var[0] + var[1]);
  r.var_along = var[2];
  r.se_across = r.var_across * std::sqrt(1.0 / n);  // two independent components
  r.se_along = r.var_along * std::sqrt(2.0 / n);
  // the drift the model gives the type, and its response time (its weight less buoyancy over
  // the drift speed: the drag per speed at the drift)
  Scene on = s;
  on.crossing_trajectories = true;
  const double vd = test::compile(on).types[0].drift_speed;
  EXPECT_GT(vd, 0.05);
  EXPECT_LT(vd, 0.2);
  EXPECT_EQ(t.drift_speed, crossing ? vd : 0.0);
  EXPECT_NEAR(t.drift_dir.z(), crossing ? -1.0 : 0.0, 1e-12);
  const double F = (t.mass - 1.2 * t.volume) * 9.81;
  const double tau = (t.mass + 0.5 * 1.2 * t.volume) * vd / F;
  double along = 1, across = 1;
  auto expect = [&](double b) {
    const double T = 1.0 / (lc.alpha * b), w = window;
    const double a = T * (T * w - T * T * -std::expm1(-w / T));
    const double c = tau * (tau * w - tau * tau * -std::expm1(-w / tau));
    return 2 * lc.sigma2 * T / (T * T - tau * tau) * (a - c);
  };
  if (crossing) crossing_factors(vd * vd, lc.sigma2, &along, &across);
  r.expect_across = expect(across);
  r.expect_along = expect(along);
  return r;
}

TEST(CrossingTrajectories, SettlingSpheresReachTheModelsDiffusivitiesInEveryScheme) {
  struct Case {
    Integrator scheme;
    bool batched;
  };
  Diffusion on;
  for (const Case c : {Case{Integrator::Strang, true}, Case{Integrator::Splitting, true},
                       Case{Integrator::Euler, true}, Case{Integrator::RK4, true},
                       Case{Integrator::Strang, false}}) {
    SCOPED_TRACE(std::string(integrator_name(c.scheme)) + (c.batched ? " batched" : " scalar"));
    const Diffusion d = settling_diffusion(c.scheme, c.batched, true);
    std::printf("%-9s %-7s: Var across %.5f (%.5f +- %.5f), along %.5f (%.5f +- %.5f) m^2\n",
                integrator_name(c.scheme), c.batched ? "batched" : "scalar", d.var_across,
                d.expect_across, d.se_across, d.var_along, d.expect_along, d.se_along);
    EXPECT_NEAR(d.var_across, d.expect_across, 3 * d.se_across);
    EXPECT_NEAR(d.var_along, d.expect_along, 3 * d.se_along);
    if (c.scheme == Integrator::Strang && c.batched) on = d;
  }
  // off: the tracer's time scale on both axes, twice the spread across
  const Diffusion off = settling_diffusion(Integrator::Strang, true, false);
  std::printf("off      : Var across %.5f (%.5f +- %.5f), along %.5f (%.5f +- %.5f) m^2\n",
              off.var_across, off.expect_across, off.se_across, off.var_along, off.expect_along,
              off.se_along);
  EXPECT_NEAR(off.var_across, off.expect_across, 3 * off.se_across);
  EXPECT_NEAR(off.var_along, off.expect_along, 3 * off.se_along);
  EXPECT_GT(off.var_across, 1.5 * on.var_across);
}

}  // namespace
}  // namespace lrigid
