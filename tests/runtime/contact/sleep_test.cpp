// Resting, sleeping and waking (contact/sleep.h, sleep.cpp): a ball at rest sleeps after
// Model::sleep_time and wakes when its flow changes; the friction speed of a sheet in the wind
// (below it the sheet sleeps, above it slides); the wake gust is where the flow starts to move a
// body; a gust watch wakes a sleeper at the OU process's mean first-passage time (closed form),
// and wakes it at the same step on the scalar and the batched step, whatever the stretches.
#include "contact/sleep.h"
#include "effects/turbulence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// A ball at rest on the ground falls asleep after Model::sleep_time; in a time-dependent field
// it wakes at the next frame time (the flow around it changed) and, still at rest, sleeps again.
TEST(Sleeping, RestingBallSleepsAndWakesWhenTheFlowChanges) {
  const GridGeometry g = test::grid_geometry(3, 3, 3, Vec3(-1, -1, 0), Vec3(1, 1, 1));
  RawGridFrame a = test::grid_frame(g, [](const Vec3&, Vec3*, double*, double*) { return true; });
  RawGridFrame b = a;
  a.time = 0;
  b.time = 1.5;
  for (const bool transient : {false, true}) {
    Scene s = test::sphere_scene(0.05, 1000, 1.2, 1.5e-5);
    s.uniform_field = false;
    s.effects = test::effects({Effect::Gravity, Effect::MeanFlow, Effect::Drag});
    s.bodies[0].position = Vec3(0, 0, 0.05);
    s.has_ground = true;
    s.dt = 1e-3;
    s.duration = 2.0;
    std::vector<RawGridFrame> frames{a};
    if (transient) frames.push_back(b);
    const Model m =
        test::compile(s, FluidField::grid(g, frames, 1.5e-5, Drift::Stationary, TimeMode::Clamp));
    State st = initial_state(m, s);
    std::vector<std::pair<double, BodyStatus>> seen;
    RunOptions o;
    o.every = 0.1;
    o.on_output = [&](const State& x) { seen.emplace_back(x.t, x.status[0]); };
    const RunStats stats = simulate(m, &st, o);
    // asleep from about sleep_time on
    for (const auto& [t, status] : seen) {
      if (t > m.sleep_time + 0.05 && t < 1.45) {
        EXPECT_EQ(status, BodyStatus::Sleeping) << "t = " << t;
      }
      if (t < m.sleep_time - 0.05) {
        EXPECT_EQ(status, BodyStatus::Moving) << "t = " << t;
      }
    }
    // the steps it took: about sleep_time of them, plus sleep_time again after the wake
    const double steps = double(stats.body_steps) * s.dt;
    EXPECT_NEAR(steps, transient ? 2 * m.sleep_time : m.sleep_time, 0.15)
        << (transient ? "transient" : "steady");
    EXPECT_NEAR(st.x[0].z(), 0.05, 1e-6);
  }
}

TEST(Sleeping, BodiesWithTheBassetHistoryFallAsleepToo) {
  // the sleep test evaluates the flow's forces on the body held still, which reads its Basset
  // history (the scene of tests/integration/resume_test.sh); spheres and chips, on the scalar and
  // the batched step
  for (const bool batched : {false, true}) {
    for (const bool chip : {false, true}) {
      Scene s = test::sphere_scene(0.002, 1100, 1000, 1e-6);
      if (chip) s.bodies[0].shape = Shape::box(0.01, 0.006, 0.001);
      s.effects = test::effects(
          {Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::AddedMass, Effect::Basset});
      s.bodies[0].position = Vec3(0, 0, 0.01);
      s.has_ground = true;
      s.batched = batched;
      s.dt = 2e-3;
      s.duration = 3.0;
      const Model m = test::compile(s);
      State st = initial_state(m, s);
      simulate(m, &st, RunOptions{});
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping)
          << (chip ? "chip" : "sphere") << (batched ? " batched" : " scalar");
    }
  }
}

// A sheet of paper lying flat on the ground in a uniform wind along x: the
// speed U* at which the wind's force on it held still (drag, and lift, from the model's own
// effects: flow_can_move) equals mu (weight - lift) is found by bisection; below it the sheet
// stays, above it slides.
Scene plate_in_wind_scene(double U, double k, bool batched, bool turbulent = false) {
  Scene s = test::sphere_scene(0.05, 600, 1.2, 1.5e-5);
  s.bodies[0].name = "paper";
  s.bodies[0].shape = Shape::box(0.15, 0.1, 0.002);
  s.bodies[0].position = Vec3(0, 0, 0.001);
  s.bodies[0].contact.restitution = 0;
  s.bodies[0].contact.friction = 0.4;
  s.effects = test::effects({Effect::Gravity, Effect::Drag, Effect::Lift, Effect::MeanFlow});
  if (turbulent) s.effects.add(Effect::Turbulence);
  s.uniform_U = Vec3(U, 0, 0);
  s.uniform_k = k;
  s.uniform_epsilon = k > 0 ? 0.1 : 0;
  s.has_ground = true;
  s.ground_z = 0;
  s.dt = 1e-3;
  s.duration = 2.0;
  s.batched = batched;
  return s;
}

// Does flow_can_move say the wind U (and turbulence k) moves the sheet at rest? One model,
// its uniform field replaced (compiling the model is the slow part).
bool wind_moves_plate(double U, double k, bool turbulent = false) {
  static Model m = test::compile(plate_in_wind_scene(1, 0, false, false));
  static Model mt = test::compile(plate_in_wind_scene(1, 0.01, false, true));
  Model& model = turbulent ? mt : m;
  model.field = FluidField::uniform(Vec3(U, 0, 0), k, k > 0 ? 0.1 : 0, 1.5e-5, Drift::Stationary);
  State st = initial_state(model, plate_in_wind_scene(U, k, false, turbulent));
  const double gust = turbulent ? kGustSigmas * std::sqrt(2.0 * k / 3.0) : 0.0;
  return flow_can_move(model, model.types[0], load_body(st, 0), Vec3::UnitZ(), 0, gust);
}

double threshold_speed() {
  double lo = 0, hi = 1;
  while (!wind_moves_plate(hi, 0)) hi *= 2;
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (lo + hi);
    (wind_moves_plate(mid, 0) ? hi : lo) = mid;
  }
  return hi;
}

class PlateInWind : public ::testing::TestWithParam<bool> {};

TEST_P(PlateInWind, StaysBelowTheFrictionSpeedSlidesAbove) {
  const double Us = threshold_speed();
  ASSERT_GT(Us, 0.5);
  ASSERT_LT(Us, 100);
  for (const double f : {0.9, 1.1}) {
    const Scene s = plate_in_wind_scene(f * Us, 0, GetParam());
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    simulate(m, &st, RunOptions{});
    if (f < 1) {
      // at rest: it fell asleep where the flow cannot move it, and did not creep
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping) << f << " U* = " << f * Us << " m/s";
      EXPECT_LT(std::abs(st.x[0].x()), 1e-4) << "it crept";
    } else {
      EXPECT_EQ(st.status[0], BodyStatus::Moving);
      EXPECT_EQ(st.contact[0], ContactState::Sliding);
      EXPECT_GT(st.x[0].x(), 0.05) << "it should slide downwind";
      EXPECT_NEAR(st.x[0].z(), 0.001, 1e-3) << "along the ground";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, PlateInWind, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// The gust at which the flow moves the sheet at rest (wake_gust) is where flow_can_move turns:
// the force on the sheet follows the wind it sees, mean and gust, so a mean wind of 0.9 U*
// needs a gust of 0.1 U*.
TEST(Sleeping, TheWakeGustIsWhereTheFlowStartsToMoveTheBody) {
  const double Us = threshold_speed();
  const double sigma = 0.1 * Us, k = 1.5 * sigma * sigma;
  Scene s = plate_in_wind_scene(0.9 * Us, k, false, true);
  const Model m = test::compile(s);
  const State st = initial_state(m, s);
  State copy = st;
  const BodyState b = load_body(copy, 0);
  const double g = wake_gust(m, m.types[0], b, Vec3::UnitZ(), 0, sigma);
  EXPECT_NEAR(g, 0.1 * Us, 1e-3 * Us);
  EXPECT_FALSE(flow_can_move(m, m.types[0], b, Vec3::UnitZ(), 0, 0.999 * g));
  EXPECT_TRUE(flow_can_move(m, m.types[0], b, Vec3::UnitZ(), 0, 1.001 * g));
  // none within kMaxGustSigmas standard deviations of a weak turbulence
  EXPECT_EQ(wake_gust(m, m.types[0], b, Vec3::UnitZ(), 0, 1e-3 * sigma), HUGE_VAL);
}

// A sleeping body's gust watch wakes it when the seen turbulence reaches its gust: for the OU
// process of a body at rest (stationary, per component variance sigma^2, rate alpha) started
// at u' = 0, the mean first-passage time to a level a sigma is, in units of 1/alpha,
//   T(a) = integral_0^a sqrt(2 pi) Phi(x) exp(x^2/2) dx
// (the backward equation -x T' + T'' = -1 with T(a) = 0). Checked over 4000 watches with
// a = 1.5; the watch looks at whole steps, which delays the passage as a barrier raised by
// 0.5826 sigma sqrt(2 alpha dt) would (Broadie, Glasserman & Kou 1997's correction). The
// components of u' across the mean flow, drawn at the wake, are those of the process at that
// time: mean 0, variance sigma^2 (1 - exp(-2 alpha t)). A watch asked again and again, a few
// steps further each time, wakes at the same step with the same u' as one asked once. With the
// crossing trajectories the rate is alpha b', Csanady's factor across the body's drift (the mean
// flow along x is across a drift along gravity): checked on a light hollow ball settling at about
// 1.6 u' (b' = 2.8); without them, on a heavy ball, alpha.
void expect_first_passage(double density, double k, double eps, bool crossing) {
  const int n = 4000;
  Scene s = test::sphere_scene(0.01, density, 1.2, 1.5e-5, n);
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::Drag, Effect::Turbulence});
  s.uniform_U = Vec3(1, 0, 0);
  s.uniform_k = k;
  s.uniform_epsilon = eps;
  s.has_ground = true;
  s.dt = 1e-4;
  s.duration = 10;
  s.crossing_trajectories = crossing;
  const Model m = test::compile(s);
  ASSERT_TRUE(keeps_gust_watch(m, m.types[0]));
  FluidSample fs;
  ASSERT_TRUE(m.field.sample(Vec3::Zero(), 0, false, &fs));
  const double vd = m.types[0].drift_speed;
  double b_along, b_across;
  crossing_factors(vd * vd, fs.sigma2, &b_along, &b_across);
  if (crossing) {
    EXPECT_GT(b_across, 2.0) << "the test tells the rates apart";
  } else {
    EXPECT_EQ(b_across, 1.0);
  }
  const double sigma = std::sqrt(fs.sigma2), alpha = fs.alpha * b_across, a = 1.5;
  ASSERT_GT(alpha * s.dt, 1e-4);
  ASSERT_LT(alpha * s.dt, 1e-2);
  State st = initial_state(m, s);
  double sum = 0, sum2 = 0, across = 0, across2 = 0, across_sq = 0, across_sq2 = 0;
  for (int i = 0; i < n; ++i) {
    st.status[i] = BodyStatus::Sleeping;
    GustWatch& w = st.watch[i];
    w = GustWatch{};
    w.gust = a * sigma;
    w.valid = 1;
    const GustWatch fresh = w;
    const uint64_t wake = watch_sleeper(m, &st, size_t(i), 100000000);
    ASSERT_NE(wake, GustWatch::kNever);
    EXPECT_GE(w.u.x(), a * sigma);
    const double T = double(wake) * s.dt * alpha;
    sum += T;
    sum2 += T * T;
    // across the mean flow (x): y and z, each N(0, sigma^2 (1 - exp(-2 alpha t)))
    const double sd = sigma * std::sqrt(-std::expm1(-2 * T));
    for (const double c : {w.u.y() / sd, w.u.z() / sd}) {
      across += c, across2 += c * c;
      across_sq += c * c, across_sq2 += c * c * c * c;
    }
    if (i < 100) {
      const GustWatch once = w;
      w = fresh;
      uint64_t upto = 1, again = GustWatch::kNever;
      while (again == GustWatch::kNever) again = watch_sleeper(m, &st, size_t(i), upto += 7);
      EXPECT_EQ(again, once.wake) << i;
      EXPECT_EQ(w.u, once.u) << i;
    }
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  const double am = across / (2 * n), ase = std::sqrt((across2 / (2 * n) - am * am) / (2 * n));
  const double vm = across_sq / (2 * n),
               vse = std::sqrt((across_sq2 / (2 * n) - vm * vm) / (2 * n));
  EXPECT_NEAR(am, 0, 4 * ase) << "mean across the flow, in its standard deviations";
  EXPECT_NEAR(vm, 1, 4 * vse) << "variance across the flow / sigma^2 (1 - exp(-2 alpha t))";
  auto mfpt = [](double level) {  // Simpson's rule on 2000 intervals
    auto f = [](double x) {
      return std::sqrt(2 * M_PI) * 0.5 * std::erfc(-x / std::sqrt(2.0)) * std::exp(0.5 * x * x);
    };
    const int k = 2000;
    double r = f(0) + f(level);
    for (int j = 1; j < k; ++j) r += (j % 2 ? 4 : 2) * f(level * j / k);
    return r * level / (3 * k);
  };
  const double expected = mfpt(a + 0.5826 * std::sqrt(2 * alpha * s.dt));
  EXPECT_NEAR(mean, expected, 4 * se) << "mean first passage, 1/alpha; without the step's "
                                      << "correction " << mfpt(a);
  // the watch follows the process it sees: twice the rate would halve the time
  EXPECT_GT(mean, 0.75 * expected);
}

TEST(Sleeping, AGustWatchWakesAtTheOuProcesssFirstPassage) {
  {
    SCOPED_TRACE("heavy ball, no crossing trajectories");
    expect_first_passage(1000, 0.01, 0.1, false);
  }
  {
    SCOPED_TRACE("hollow ball, crossing trajectories");
    expect_first_passage(5, 1.0, 1.0, true);
  }
}

// A sheet held by friction in a mean wind of 0.9 U* with a turbulence whose gusts can move it
// falls asleep and its watch wakes it when a gust comes: it slides downwind and rests again. The
// batched step wakes it at the same step as the scalar one. Without the gusts (a turbulence far
// too weak) it sleeps and never wakes.
class GustWatchOnSteps : public ::testing::TestWithParam<bool> {};

TEST_P(GustWatchOnSteps, ASheetInGustsSleepsAndWakesWhenAGustComes) {
  const double Us = threshold_speed();
  const double sigma = 0.07 * Us, k = 1.5 * sigma * sigma;
  EXPECT_TRUE(wind_moves_plate(0.9 * Us, k, true));  // a 3 sigma gust moves it
  for (const double scale : {1.0, 1e-6}) {
    Scene s = plate_in_wind_scene(0.9 * Us, scale * k, GetParam(), true);
    s.duration = 10;
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    int slept = 0, woke = 0;
    BodyStatus before = BodyStatus::Moving;
    double x_asleep = 0, moved = 0;
    RunOptions o;
    o.every = s.dt;
    o.on_output = [&](const State& now) {
      if (now.status[0] == BodyStatus::Sleeping && before != BodyStatus::Sleeping) {
        ++slept;
        x_asleep = now.x[0].x();
      }
      if (now.status[0] == BodyStatus::Moving && before == BodyStatus::Sleeping) ++woke;
      if (before == BodyStatus::Moving && slept > 0)
        moved = std::max(moved, now.x[0].x() - x_asleep);
      before = now.status[0];
    };
    simulate(m, &st, o);
    if (scale == 1.0) {
      EXPECT_GE(slept, 2) << "it should fall asleep again after a gust moved it";
      EXPECT_GE(woke, 1);
      EXPECT_GT(moved, 1e-4) << "woken by a gust, it should slide downwind";
    } else {
      EXPECT_EQ(slept, 1);
      EXPECT_EQ(woke, 0);
      EXPECT_EQ(st.status[0], BodyStatus::Sleeping);
      EXPECT_EQ(st.watch[0].wake, GustWatch::kNever);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ScalarAndBatched, GustWatchOnSteps, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "batched" : "scalar"; });

// Where the stretches of steps end (outputs, and at most kStretchSteps apart) does not change
// what the bodies do: 32 sheets dropped in a gusty wind onto the ground, where they land, slide,
// fall asleep and are woken by their gust watches (some inside a stretch, as dormant lanes, some
// at a stretch's start), end bitwise where the same run with an output every step leaves them.
TEST(Sleeping, StretchesDoNotChangeTheRun) {
  const double Us = threshold_speed();
  const double sigma = 0.07 * Us, k = 1.5 * sigma * sigma;
  for (const bool batched : {false, true}) {
    Scene s = plate_in_wind_scene(0.9 * Us, k, batched, true);
    s.bodies[0].count = 32;
    s.bodies[0].spawn_in_box = true;
    s.bodies[0].box_lo = Vec3(-1, -1, 0.002);
    s.bodies[0].box_hi = Vec3(1, 1, 0.05);
    s.bodies[0].random_orientation = true;
    s.duration = 2;
    const Model m = test::compile(s);
    State a = initial_state(m, s), b = a;
    RunOptions every_step;
    every_step.every = s.dt;
    int sleeping = 0, woken = 0;
    std::vector<uint8_t> was(32, 0);
    every_step.on_output = [&](const State& now) {
      for (size_t i = 0; i < 32; ++i) {
        const bool asleep = now.status[i] == BodyStatus::Sleeping;
        sleeping += asleep && !was[i];
        woken += !asleep && was[i];
        was[i] = asleep;
      }
    };
    simulate(m, &a, every_step);
    RunOptions at_end;
    at_end.every = s.duration;
    simulate(m, &b, at_end);
    EXPECT_GT(sleeping, 5) << (batched ? "batched" : "scalar");
    EXPECT_GT(woken, 2) << (batched ? "batched" : "scalar");
    for (size_t i = 0; i < 32; ++i) {
      EXPECT_EQ(a.x[i], b.x[i]) << i << (batched ? " batched" : " scalar");
      EXPECT_EQ(a.status[i], b.status[i]) << i;
    }
  }
}

// Scalar and batched steps wake the sheet at the same step and leave it at the same place.
TEST(Sleeping, GustWatchesWakeTheSameOnBothSteps) {
  const double Us = threshold_speed();
  const double sigma = 0.1 * Us, k = 1.5 * sigma * sigma;
  std::vector<double> x[2];
  std::vector<int> status[2];
  for (const bool batched : {false, true}) {
    Scene s = plate_in_wind_scene(0.9 * Us, k, batched, true);
    s.duration = 4;
    const Model m = test::compile(s);
    State st = initial_state(m, s);
    RunOptions o;
    o.every = 0.05;
    o.on_output = [&](const State& now) {
      x[batched].push_back(now.x[0].x());
      status[batched].push_back(int(now.status[0]));
    };
    simulate(m, &st, o);
  }
  ASSERT_EQ(x[0].size(), x[1].size());
  for (size_t j = 0; j < x[0].size(); ++j) {
    EXPECT_EQ(status[0][j], status[1][j]) << "output " << j;
    EXPECT_NEAR(x[0][j], x[1][j], 1e-6) << "output " << j;
  }
}

}  // namespace
}  // namespace lrigid
