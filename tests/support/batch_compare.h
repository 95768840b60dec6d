// What the batched-step tests share: a sheared wind grid with an obstacle, and a scene run on
// the scalar and on the batched step with the largest differences of the final states (the
// statuses, stop times and reasons must be equal).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compile/compile_model.h"
#include "effects/plan.h"
#include "effects/registry.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace batch_test {

// A 12 x 8 x 6 m box of air with a sheared, accelerating wind, k rising with height, a solid
// block in the middle (invalid points) and the ground at z = 0.
inline FluidField wind_grid(double nu) {
  const GridGeometry g = test::grid_geometry(25, 17, 13, Vec3(-6, -4, -0.5), Vec3(0.5, 0.5, 0.5));
  const RawGridFrame f = test::grid_frame(g, [](const Vec3& x, Vec3* U, double* k, double* eps) {
    const double z = std::max(x.z(), 0.0);
    *U = Vec3(1.5 * std::sqrt(z) * (1 + 0.05 * x.x()), 0.3 * std::sin(0.5 * x.x()), -0.05 * x.y());
    *k = 0.05 + 0.2 * z / 5.5;
    *eps = 0.4 * *k;
    return !(std::abs(x.x()) <= 1.0 && std::abs(x.y()) <= 1.0 && x.z() <= 2.0);
  });
  return FluidField::grid(g, {f}, nu, Drift::Stationary, TimeMode::Clamp);
}

// The same box with a gusting wind: frames at 0, 0.3, 0.55 and 0.9 s (uneven: the steps' blend
// weights and dU/dt change from bracket to bracket) whose wind speed and k swing by up to 40 %,
// clamped after the last frame (the 1 s runs pass it). A time-dependent field: samples blend two
// frames and carry dU/dt.
inline FluidField gusty_wind_grid(double nu) {
  const GridGeometry g = test::grid_geometry(25, 17, 13, Vec3(-6, -4, -0.5), Vec3(0.5, 0.5, 0.5));
  std::vector<RawGridFrame> frames;
  for (double t : {0.0, 0.3, 0.55, 0.9}) {
    const double gust = 1 + 0.4 * std::sin(7.0 * t);
    RawGridFrame f = test::grid_frame(g, [gust](const Vec3& x, Vec3* U, double* k, double* eps) {
      const double z = std::max(x.z(), 0.0);
      *U = Vec3(1.5 * gust * std::sqrt(z) * (1 + 0.05 * x.x()), 0.3 * std::sin(0.5 * x.x() + gust),
                -0.05 * gust * x.y());
      *k = (0.05 + 0.2 * z / 5.5) * gust;
      *eps = 0.4 * *k;
      return !(std::abs(x.x()) <= 1.0 && std::abs(x.y()) <= 1.0 && x.z() <= 2.0);
    });
    f.time = t;
    frames.push_back(std::move(f));
  }
  return FluidField::grid(g, frames, nu, Drift::Stationary, TimeMode::Clamp);
}

// Splitting at 2 ms for 1 s (seed `seed`), the first body entry spawned with random orientations
// west of the grid's block, and the ground at z = 0 where bodies land (ground.contact "stop").
inline void release_in_wind_grid(Scene* s, uint64_t seed) {
  s->uniform_field = false;
  s->integrator = Integrator::Splitting;
  s->dt = 2e-3;
  s->duration = 1.0;
  s->seed = seed;
  s->has_ground = true;
  s->ground_z = 0;
  // the seed's landing: these scenes compare the batched and the scalar flight to round-off,
  // and contacts (bodies resting and sliding on the ground, contact/pass.h) amplify it;
  // contact/contacts_test.cpp compares the two steps with contacts on
  s->ground_contact = ContactMode::Stop;
  s->bodies[0].spawn_in_box = true;
  s->bodies[0].box_lo = Vec3(-5, -3, 0.3);
  s->bodies[0].box_hi = Vec3(-1.5, 3, 3);
  s->bodies[0].random_orientation = true;
}

struct Outcome {
  State state;
  RunStats stats;
};

inline Outcome run(const Scene& s, const FluidField& field, bool batched, Precision p,
                   int threads = 1) {
  Model m = test::compile(s, field);
  m.batched = batched;
  m.precision = p;
  Outcome r{initial_state(m, s), {}};
  RunOptions opt;
  opt.threads = threads;
  r.stats = simulate(m, &r.state, opt);
  return r;
}

// A batched block steps only its lanes up to the last live one, rounded up to whole vectors
// (integrate/batch_lanes.h Samples::width). Scene s has 32 bodies of one batched type: bodies 5-13
// and 5-10 run alone (lanes 0-8 of a block stepped 16 wide, lanes 0-5 of one stepped 8 wide in
// double) must end bitwise where they end as lanes 5-13 and 5-10 of the full block, some of them
// landed on the way (their lanes left the step) and some not.
inline void expect_lanes_ignore_width(const Scene& s, const FluidField& field, Precision p) {
  Model m = test::compile(s, field);
  m.batched = true;
  m.precision = p;
  State full = initial_state(m, s);
  const State start = full;
  simulate(m, &full, RunOptions{});
  for (const size_t end : {size_t(14), size_t(11)}) {
    State part = start;
    RunOptions few;
    few.body_begin = 5;
    few.body_end = end;
    simulate(m, &part, few);
    int landed = 0;
    for (size_t i = 5; i < end; ++i) {
      const std::string at = "body " + std::to_string(i) + " of 5-" + std::to_string(end - 1) +
                             (p == Precision::Float ? " float" : " double") + " scheme " +
                             std::to_string(int(s.integrator));
      EXPECT_EQ(full.status[i], part.status[i]) << at;
      EXPECT_EQ(full.x[i], part.x[i]) << at;
      EXPECT_EQ(full.v[i], part.v[i]) << at;
      EXPECT_EQ(full.w[i], part.w[i]) << at;
      EXPECT_EQ(full.q[i].coeffs(), part.q[i].coeffs()) << at;
      EXPECT_EQ(full.u_seen[i], part.u_seen[i]) << at;
      landed += full.status[i] == BodyStatus::Landed;
    }
    if (end == 14) {
      EXPECT_GT(landed, 0) << "no lane left the step";
      EXPECT_LT(landed, 9) << "every lane left the step";
    }
  }
}

// largest differences between two runs' states, per part
struct Diff {
  double x = 0, v = 0, w = 0, q = 0, u = 0;
  double t = 0;  // stop times (a landing is located inside its step, so it carries the round-off)
};

inline Diff compare(const Outcome& a, const Outcome& b) {
  Diff d;
  EXPECT_EQ(a.state.size(), b.state.size());
  for (size_t i = 0; i < a.state.size(); ++i) {
    EXPECT_EQ(a.state.status[i], b.state.status[i]) << "body " << i;
    const double ta = a.state.t_stop[i], tb = b.state.t_stop[i];
    if (std::isnan(ta) != std::isnan(tb))
      d.t = std::numeric_limits<double>::infinity();
    else if (!std::isnan(ta))
      d.t = std::max(d.t, std::abs(ta - tb));
    EXPECT_EQ(a.state.reason[i], b.state.reason[i]) << "body " << i;
    d.x = std::max(d.x, (a.state.x[i] - b.state.x[i]).norm());
    d.v = std::max(d.v, (a.state.v[i] - b.state.v[i]).norm());
    d.w = std::max(d.w, (a.state.w[i] - b.state.w[i]).norm());
    d.q = std::max(d.q, (a.state.q[i].coeffs() - b.state.q[i].coeffs()).norm());
    d.u = std::max(d.u, (a.state.u_seen[i] - b.state.u_seen[i]).norm());
  }
  return d;
}

// The scene run on the scalar step and on the batched step (double), and how far apart they end.
struct Both {
  Outcome scalar, batched;
  Diff d;
};

inline Both scalar_and_batched(const Scene& s, const FluidField& field) {
  Both b{run(s, field, false, Precision::Double), run(s, field, true, Precision::Double), {}};
  b.d = compare(b.scalar, b.batched);
  // the two steps stop the same bodies at the same times: a landing located inside its step
  // within 1 us (its position agrees to round-off; dt is 1e-3 s and more)
  EXPECT_LT(b.d.t, 1e-6);
  return b;
}

// The largest distance between where the bodies of two runs of one scene end or stopped, m.
inline double farthest_apart(const Outcome& a, const Outcome& b) {
  double d = 0;
  for (size_t i = 0; i < a.state.size(); ++i)
    d = std::max(d, (a.state.x[i] - b.state.x[i]).norm());
  return d;
}

// How far the effects `drop` move the bodies: the largest distance between where the bodies of
// `with` (the scene `s` run batched, double) end or stopped and where they do without them, m.
inline double moved_by(const Scene& s, const FluidField& field, const Outcome& with,
                       std::initializer_list<Effect> drop) {
  Scene plain = s;
  for (Effect e : drop) plain.effects.remove(e);
  return farthest_apart(with, run(plain, field, true, Precision::Double));
}

// The largest differences between two runs' states, without asking for the same statuses (a
// run without an effect may land its bodies elsewhere or at other times).
inline Diff apart(const Outcome& a, const Outcome& b) {
  Diff d;
  for (size_t i = 0; i < a.state.size(); ++i) {
    d.x = std::max(d.x, (a.state.x[i] - b.state.x[i]).norm());
    d.v = std::max(d.v, (a.state.v[i] - b.state.v[i]).norm());
    d.w = std::max(d.w, (a.state.w[i] - b.state.w[i]).norm());
    d.q = std::max(d.q, (a.state.q[i].coeffs() - b.state.q[i].coeffs()).norm());
  }
  return d;
}

// Every effect of the registry (effects/registry.h) that its row says the batched loops
// implement, at once, on scene s (one body type, which must take the batched step: its own
// effects are replaced), in each of the four schemes: the batched step ends where the scalar
// step ends, within tol (m, m/s, rad/s), and taking any one of those effects away moves the
// scalar step's bodies by more than 100 tol. A batched step that left an effect out, took it
// in another frame or handed the body type to the scalar step fails here, whatever the effect:
// nothing in the test names one. An effect whose row picks no wrench term for the body type
// (lift on a body that is not flat) does not apply to it and is not asked to move it.
// eligible: the batched step's test (rigid_batch_eligible).
inline void expect_every_batched_effect_applied(
    Scene s, const FluidField& field, double tol,
    bool (*eligible)(const Model&, const BodyType&, std::string*)) {
  s.effects = EffectSet{};
  for (const EffectInfo& e : all_effects())
    if (e.batched) s.effects.add(e.effect);
  for (const Integrator scheme :
       {Integrator::Splitting, Integrator::Strang, Integrator::Euler, Integrator::RK4}) {
    s.integrator = scheme;
    SCOPED_TRACE(integrator_name(scheme));
    const Model m = test::compile(s, field);
    std::string why;
    ASSERT_TRUE(eligible(m, m.types[0], &why)) << why;
    const Both b = scalar_and_batched(s, field);
    EXPECT_EQ(b.scalar.stats.body_steps, b.batched.stats.body_steps);
    // the loops take the steps themselves
    EXPECT_GT(b.batched.stats.body_steps, 0u);
    EXPECT_LE(b.batched.stats.scalar_handoffs, b.batched.stats.body_steps / 100);
    EXPECT_LT(b.d.x, tol);
    EXPECT_LT(b.d.v, tol);
    EXPECT_LT(b.d.w, tol);
    EXPECT_LT(b.d.q, tol);
    const char* least = "";
    double least_moved = std::numeric_limits<double>::infinity();
    for (const EffectInfo& e : all_effects()) {
      if (!s.effects.has(e.effect)) continue;
      if (e.term && !wrench_term(m.types[0], e.effect)) continue;
      Scene less = s;
      less.effects.remove(e.effect);
      const Diff moved = apart(run(less, field, false, Precision::Double), b.scalar);
      const double most = std::max({moved.x, moved.v, moved.w});
      EXPECT_GT(most, 100 * tol) << e.name << " does not move the bodies";
      if (most < least_moved) least_moved = most, least = e.name;
    }
    std::printf("%s: batched - scalar %.2g m, %.2g m/s, %.2g rad/s; the effect that moves the "
                "bodies least: %s, by %.2g (largest of m, m/s, rad/s)\n",
                integrator_name(scheme), b.d.x, b.d.v, b.d.w, least, least_moved);
  }
}

inline size_t count(const State& s, BodyStatus status) {
  size_t n = 0;
  for (BodyStatus x : s.status) n += x == status;
  return n;
}

// Float against double runs of one scene: the bodies with the same status, and the largest
// distance between their positions (of the moving ones only, or of all: where they stopped).
struct FloatCost {
  size_t same = 0;
  double dx = 0;  // m
};

inline FloatCost float_vs_double(const Outcome& dbl, const Outcome& flt, bool moving_only) {
  FloatCost c;
  for (size_t i = 0; i < dbl.state.size(); ++i) {
    if (dbl.state.status[i] != flt.state.status[i]) continue;
    ++c.same;
    if (!moving_only || dbl.state.status[i] == BodyStatus::Moving)
      c.dx = std::max(c.dx, (dbl.state.x[i] - flt.state.x[i]).norm());
  }
  std::printf("float vs double: %zu of %zu bodies with the same status, max |dx| = %.3g m\n",
              c.same, dbl.state.size(), c.dx);
  return c;
}

// An artist's leaf as a mesh (tests/data/meshes/make_meshes.py bent_leaf, which writes the
// 1696-triangle bent_leaf.obj): a length x width plate `thick` thick, its mid-surface curled to
// z = sag (2x/length)^2, turned by yaw (rad) about z; nx x ny vertices on each face. Its
// generalized mass is a full 6 x 6 (linear-angular coupling from the curl, products of inertia
// from the turn).
inline Shape bent_leaf(int nx, int ny, double length = 0.06, double width = 0.04,
                       double thick = 4e-4, double sag = 0.004, double yaw = 20 * M_PI / 180) {
  auto m = std::make_shared<TriangleMesh>();
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (const double side : {1.0, -1.0})
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        const double x = -length / 2 + length * i / (nx - 1), y = -width / 2 + width * j / (ny - 1);
        const double z = sag * (2 * x / length) * (2 * x / length);
        const double dz = 8 * sag * x / (length * length), n = std::sqrt(1 + dz * dz);
        const double px = x - side * 0.5 * thick * dz / n, pz = z + side * 0.5 * thick / n;
        m->vertices.emplace_back(c * px - s * y, s * px + c * y, pz);
      }
  auto top = [ny](int i, int j) { return i * ny + j; };
  auto bot = [nx, ny](int i, int j) { return nx * ny + i * ny + j; };
  for (int i = 0; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < ny; ++j) {
      m->faces.push_back({top(i, j), top(i + 1, j), top(i + 1, j + 1)});
      m->faces.push_back({top(i, j), top(i + 1, j + 1), top(i, j + 1)});
      m->faces.push_back({bot(i, j), bot(i + 1, j + 1), bot(i + 1, j)});
      m->faces.push_back({bot(i, j), bot(i, j + 1), bot(i + 1, j + 1)});
    }
  // the rim, counter-clockwise seen from +z, closed by side strips
  std::vector<std::pair<int, int>> rim;
  for (int i = 0; i < nx; ++i) rim.emplace_back(i, 0);
  for (int j = 1; j < ny; ++j) rim.emplace_back(nx - 1, j);
  for (int i = nx - 2; i >= 0; --i) rim.emplace_back(i, ny - 1);
  for (int j = ny - 2; j > 0; --j) rim.emplace_back(0, j);
  for (size_t k = 0; k < rim.size(); ++k) {
    const auto [pi, pj] = rim[k];
    const auto [qi, qj] = rim[(k + 1) % rim.size()];
    m->faces.push_back({bot(pi, pj), bot(qi, qj), top(qi, qj)});
    m->faces.push_back({bot(pi, pj), top(qi, qj), top(pi, pj)});
  }
  return Shape::from_mesh(std::move(m), "bent_leaf");
}

// Each change of the scene `s` excludes its first body type from a batched step (`eligible`),
// which names the reason given.
using Eligible = std::function<bool(const Model&, const BodyType&, std::string*)>;
using Exclusion = std::pair<std::function<void(Scene&)>, std::string>;

inline void expect_exclusions(const Scene& s, const FluidField& field, const Eligible& eligible,
                              const std::vector<Exclusion>& cases) {
  for (const auto& [change, reason] : cases) {
    Scene e = s;
    change(e);
    const Model m = test::compile(e, field);
    std::string why;
    EXPECT_FALSE(eligible(m, m.types[0], &why)) << reason;
    EXPECT_EQ(why, reason);
  }
}

}  // namespace batch_test
}  // namespace lrigid
