// The run loop (integrate/simulation.h): which step a body type takes (docs/architecture.md,
// "Where a body is stepped"), the outputs at the start, every whole number of steps and at the
// end, the stretches of steps between rebuilds of the work list (at most 256 steps, ending at
// each output), the range of bodies a process advances, a resumed run ending where the whole run
// ends, and the same seed giving bitwise-identical trajectories for any thread count
// (counter-based noise keyed by seed, body and step) while a different seed gives others.
#include "integrate/rigid_batch.h"
#include "integrate/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "compile/compile_model.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

// n light beads in a uniform turbulent wind, spread in a box: every body moves differently
Scene wind_scene(int n) {
  Scene s = test::sphere_scene(0.002, 300, 1.2, 1.5e-5, n);
  s.uniform_U = Vec3(2, 0.5, 0);
  s.uniform_k = 0.5;
  s.uniform_epsilon = 0.3;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag,
                             Effect::MeanFlow, Effect::Turbulence});
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_hi = Vec3(1, 1, 1);
  s.dt = 1e-3;
  s.duration = 1.0;
  return s;
}

bool identical(const State& a, const State& b) {
  return a.size() == b.size() &&
         std::memcmp(a.x.data(), b.x.data(), a.x.size() * sizeof(Vec3)) == 0 &&
         std::memcmp(a.q.data(), b.q.data(), a.q.size() * sizeof(Quat)) == 0 &&
         std::memcmp(a.v.data(), b.v.data(), a.v.size() * sizeof(Vec3)) == 0 &&
         std::memcmp(a.w.data(), b.w.data(), a.w.size() * sizeof(Vec3)) == 0 &&
         std::memcmp(a.u_seen.data(), b.u_seen.data(), a.u_seen.size() * sizeof(Vec3)) == 0;
}

bool simulated_same_body(const State& a, const State& b, size_t i) {
  return a.x[i] == b.x[i] && a.q[i].coeffs() == b.q[i].coeffs() && a.v[i] == b.v[i] &&
         a.w[i] == b.w[i] && a.u_seen[i] == b.u_seen[i];
}

// A uniform sphere takes the batched step with the isotropic M; a body with its centre of mass
// off its centroid (a sphere too) with the full one, an ellipsoid and a box with the diagonal M; what rules the
// batched step out (the scene's "batched": false, the body turbulence model, noise substeps)
// leaves the scalar step, and says why.
TEST(Simulation, StepKindFollowsTheBodyTypeAndTheScene) {
  auto kind = [](const Scene& s, std::string* why = nullptr) {
    const Model m = test::compile(s);
    return step_kind(m, m.types[0], why);
  };
  auto mass = [](const Scene& s) {
    const Model m = test::compile(s);
    return batch_mass(m.types[0]);
  };
  const Scene beads = wind_scene(1);
  EXPECT_EQ(kind(beads), StepKind::Batched);
  EXPECT_EQ(mass(beads), BatchMass::Isotropic);
  Scene keel = beads;
  keel.bodies[0].mass_offset = Vec3(0, 0, -0.0005);
  EXPECT_EQ(kind(keel), StepKind::Batched);
  EXPECT_NE(mass(keel), BatchMass::Isotropic) << "about the centroid its M couples spin and drift";
  Scene seed = beads;
  seed.bodies[0].shape = Shape::ellipsoid(0.004, 0.002, 0.001);
  EXPECT_EQ(kind(seed), StepKind::Batched);
  EXPECT_EQ(mass(seed), BatchMass::Diagonal);
  Scene card = beads;
  card.effects.remove(Effect::AddedMass);  // (a box's comes from the panel method)
  card.bodies[0].shape = Shape::box(0.05, 0.03, 5e-4);
  EXPECT_EQ(kind(card), StepKind::Batched);
  EXPECT_EQ(mass(card), BatchMass::Diagonal);
  Scene single = beads;
  single.precision = Precision::Float;
  EXPECT_EQ(kind(single), StepKind::Batched) << "the precision does not change the step";
  EXPECT_EQ(mass(single), BatchMass::Isotropic);
  for (Scene scalar : {beads, seed}) {
    std::string why;
    Scene off = scalar;
    off.batched = false;
    EXPECT_EQ(kind(off, &why), StepKind::Scalar);
    EXPECT_FALSE(why.empty());
    Scene body_model = scalar;
    body_model.turbulence_model = TurbulenceModel::Body;
    why.clear();
    EXPECT_EQ(kind(body_model, &why), StepKind::Scalar);
    EXPECT_FALSE(why.empty());
    Model substeps = test::compile(scalar);
    substeps.noise_substeps = 4;
    why.clear();
    EXPECT_EQ(step_kind(substeps, substeps.types[0], &why), StepKind::Scalar);
    EXPECT_FALSE(why.empty());
  }
}

// The output interval in whole steps: every / dt rounded, at least one step.
TEST(Simulation, OutputStrideIsTheIntervalInWholeSteps) {
  const Model m = test::compile(wind_scene(1));  // dt = 1 ms
  EXPECT_EQ(output_stride(m, 0.1), 100u);
  EXPECT_EQ(output_stride(m, 1.0), 1000u);
  EXPECT_EQ(output_stride(m, 0.0996), 100u);
  EXPECT_EQ(output_stride(m, 0.00149), 1u);
  EXPECT_EQ(output_stride(m, 0.0016), 2u);
  EXPECT_EQ(output_stride(m, 0.0004), 1u);
  EXPECT_EQ(output_stride(m, 0.0), 1u);
}

// Outputs at step 0, at every stride steps and at the end (1 s at 1 ms, every 0.3 s: steps 0,
// 300, 600, 900, 1000), the state's time its step times dt; a resumed run (output_at_start
// false) skips the first. Stretches of steps (one on_progress call each) end at each output and
// after at most 256 steps, the first one that comes: 256, 300, 556, 600, 856, 900, 1000.
TEST(Simulation, OutputsAndStretchesEndAtWholeStrides) {
  const Scene s = wind_scene(3);
  const Model m = test::compile(s);
  const uint64_t total = 1000, stride = 300, longest = 256;
  std::vector<uint64_t> outputs_expected = {0}, stretches_expected;
  for (uint64_t k = stride; k < total; k += stride) outputs_expected.push_back(k);
  outputs_expected.push_back(total);
  for (uint64_t first = 0; first < total;) {
    first = std::min({total, (first / stride + 1) * stride, first + longest});
    stretches_expected.push_back(first);
  }
  for (const bool at_start : {true, false}) {
    State st = initial_state(m, s);
    std::vector<uint64_t> outputs, stretches;
    std::vector<double> fractions;
    RunOptions opt;
    opt.every = 0.3;
    opt.output_at_start = at_start;
    opt.on_output = [&](const State& now) {
      outputs.push_back(now.step);
      EXPECT_EQ(now.t, double(now.step) * m.dt);
    };
    opt.on_progress = [&](const State& now, double fraction) {
      stretches.push_back(now.step);
      fractions.push_back(fraction);
    };
    const RunStats stats = simulate(m, &st, opt);
    std::vector<uint64_t> expect = outputs_expected;
    if (!at_start) expect.erase(expect.begin());
    EXPECT_EQ(outputs, expect);
    EXPECT_EQ(stretches, stretches_expected);
    ASSERT_EQ(fractions.size(), stretches.size());
    for (size_t i = 0; i < stretches.size(); ++i)
      EXPECT_DOUBLE_EQ(fractions[i], double(stretches[i]) / double(total));
    EXPECT_EQ(stats.steps, total);
    EXPECT_EQ(stats.body_steps, 3 * total);
  }
}

// A process advances only the bodies of its range [body_begin, body_end): the others stay as they
// were, and those of the range end where a run of all the bodies ends them (the bodies are
// independent).
TEST(Simulation, OnlyTheBodiesOfItsRangeAreAdvanced) {
  const Scene s = wind_scene(40);
  for (const bool batched : {true, false}) {
    Model m = test::compile(s);
    m.batched = batched;
    m.duration = 0.2;
    const State start = initial_state(m, s);
    State all = start, part = start;
    simulate(m, &all, RunOptions{});
    RunOptions range;
    range.body_begin = 7;
    range.body_end = 29;
    const RunStats stats = simulate(m, &part, range);
    EXPECT_EQ(stats.body_steps, 22u * 200u);
    for (size_t i = 0; i < start.size(); ++i) {
      const bool mine = i >= 7 && i < 29;
      EXPECT_TRUE(simulated_same_body(part, mine ? all : start, i)) << "body " << i << " batched " << batched;
      EXPECT_FALSE(simulated_same_body(all, start, i)) << "body " << i << " moved";
    }
  }
}

// A run stopped at 0.5 s and resumed from its state (no output at the start, the counts going
// on from the first part's) ends bitwise where the whole run ends, with the whole run's counts.
TEST(Simulation, AResumedRunEndsWhereTheWholeRunEnds) {
  const Scene s = wind_scene(40);
  for (const bool batched : {true, false}) {
    Model m = test::compile(s);
    m.batched = batched;
    State whole = initial_state(m, s), resumed = whole;
    const RunStats all = simulate(m, &whole, RunOptions{});
    Model half = m;
    half.duration = 0.5;
    RunStats live;
    RunOptions first;
    first.live_stats = &live;
    simulate(half, &resumed, first);
    EXPECT_EQ(resumed.step, 500u);
    EXPECT_EQ(live.steps, 500u);
    int outputs = 0;
    RunOptions second;
    second.output_at_start = false;
    second.live_stats = &live;
    second.on_output = [&](const State&) { ++outputs; };
    const RunStats rest = simulate(m, &resumed, second);
    EXPECT_EQ(outputs, 5);  // 0.6 ... 1.0 s
    EXPECT_TRUE(identical(whole, resumed)) << "batched " << batched;
    EXPECT_EQ(rest.body_steps, all.body_steps);
    EXPECT_EQ(rest.steps, all.steps);
  }
}

// wind_scene's beads released at 50 per second from 0.1 s (model/release.h): the last at 0.88 s
Scene release_scene(int n) {
  Scene s = wind_scene(n);
  s.bodies[0].release_rate = 50;
  s.bodies[0].release_start = 0.1;
  return s;
}

// Body k is unreleased (not stepped, hidden) until the first step at or after 0.1 + k / 50 s;
// the output there shows it where it starts, the next one has moved it. The run's body steps
// are those of the released bodies only.
TEST(Simulation, ARateReleasePutsBodyKInFlightFromStartPlusKOverRate) {
  const Scene s = release_scene(40);
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  const State start = st;
  std::vector<long> shown(st.size(), -1);  // the first output step each body is released at
  std::vector<Vec3> x_shown(st.size()), x_next(st.size());
  RunOptions opt;
  opt.every = m.dt;
  opt.on_output = [&](const State& now) {
    for (size_t i = 0; i < now.size(); ++i) {
      const bool waiting = now.status[i] == BodyStatus::Unreleased;
      EXPECT_EQ(now.hidden[i], waiting ? 1 : 0) << "body " << i << " at step " << now.step;
      if (waiting) {
        EXPECT_EQ(now.x[i], start.x[i]) << "an unreleased body is not stepped";
        continue;
      }
      if (shown[i] < 0) {
        shown[i] = long(now.step);
        x_shown[i] = now.x[i];
      } else if (long(now.step) == shown[i] + 1) {
        x_next[i] = now.x[i];
      }
    }
  };
  const RunStats stats = simulate(m, &st, opt);
  uint64_t expected_steps = 0;
  for (size_t k = 0; k < st.size(); ++k) {
    const double t_release = 0.1 + double(k) / 50;
    ASSERT_GE(shown[k], 0) << "body " << k << " released before the end";
    const double t = double(shown[k]) * m.dt;
    EXPECT_GE(t, t_release - 1e-9) << "body " << k << " not before its time";
    EXPECT_LT(t - m.dt, t_release) << "body " << k << " at the first step of its time";
    EXPECT_EQ(x_shown[k], start.x[k]) << "body " << k << " starts where initial_state put it";
    EXPECT_NE(x_next[k], start.x[k]) << "body " << k << " moves from its release on";
    expected_steps += 1000 - uint64_t(shown[k]);
  }
  EXPECT_EQ(stats.body_steps, expected_steps) << "unreleased bodies cost no steps";
}

// An entry released over time changes nothing of the other entries' bodies, to the bit (no
// draws of its own, no steps before its release).
TEST(Simulation, AReleasedEntryLeavesTheOthersBodiesAsTheyWere) {
  const Scene alone = wind_scene(20);
  Scene both = alone;
  both.bodies.push_back(release_scene(20).bodies[0]);
  both.bodies[1].name = "later";
  const Model ma = test::compile(alone), mb = test::compile(both);
  State a = initial_state(ma, alone), b = initial_state(mb, both);
  simulate(ma, &a, RunOptions{});
  simulate(mb, &b, RunOptions{});
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_TRUE(simulated_same_body(a, b, i)) << "body " << i;
  for (size_t i = a.size(); i < b.size(); ++i)
    EXPECT_EQ(b.status[i], BodyStatus::Moving) << "body " << i << " released by 1 s";
}

// With a release, a run resumed between two releases ends bitwise where the whole run ends, on
// one thread or two, batched or scalar.
TEST(Simulation, AResumedRunWithAReleaseEndsWhereTheWholeRunEnds) {
  const Scene s = release_scene(40);
  for (const bool batched : {true, false}) {
    Model m = test::compile(s);
    m.batched = batched;
    State whole = initial_state(m, s), resumed = whole, two = whole;
    const RunStats all = simulate(m, &whole, RunOptions{});
    RunOptions on_two;
    on_two.threads = 2;
    simulate(m, &two, on_two);
    EXPECT_TRUE(identical(whole, two)) << "1 and 2 threads, batched " << batched;
    Model half = m;
    half.duration = 0.5;
    RunStats live;
    RunOptions first;
    first.live_stats = &live;
    simulate(half, &resumed, first);
    size_t waiting = 0;
    for (BodyStatus b : resumed.status) waiting += b == BodyStatus::Unreleased;
    EXPECT_GT(waiting, 0u) << "some bodies still wait at 0.5 s";
    EXPECT_LT(waiting, resumed.size()) << "some are released by 0.5 s";
    RunOptions second;
    second.output_at_start = false;
    second.live_stats = &live;
    const RunStats rest = simulate(m, &resumed, second);
    EXPECT_TRUE(identical(whole, resumed)) << "batched " << batched;
    EXPECT_EQ(whole.status, resumed.status);
    EXPECT_EQ(rest.body_steps, all.body_steps);
  }
}

State run(int threads, uint64_t seed) {
  Scene s = test::sphere_scene(0.002, 300, 1.2, 1.5e-5, 301);
  s.uniform_U = Vec3(2, 0.5, 0);
  s.uniform_k = 0.5;
  s.uniform_epsilon = 0.3;
  s.effects = test::effects({Effect::Gravity, Effect::Buoyancy, Effect::AddedMass, Effect::Drag,
                             Effect::MeanFlow, Effect::Turbulence});
  s.seed = seed;
  s.bodies[0].shape = Shape::ellipsoid(0.004, 0.002, 0.001);
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_hi = Vec3(1, 1, 1);
  s.bodies[0].random_orientation = true;
  s.integrator = Integrator::Splitting;
  s.dt = 1e-3;
  s.duration = 0.5;
  const Model m = test::compile(s);
  State st = initial_state(m, s);
  RunOptions opt;
  opt.threads = threads;
  simulate(m, &st, opt);
  return st;
}

TEST(Determinism, IdenticalForAnyThreadCount) {
  const State one = run(1, 42);
  EXPECT_TRUE(identical(one, run(2, 42)));
  EXPECT_TRUE(identical(one, run(3, 42)));
  EXPECT_FALSE(identical(one, run(1, 43)));
  // the turbulence really moved the bodies apart from each other
  EXPECT_GT((one.u_seen[0] - one.u_seen[1]).norm(), 0.0);
}

}  // namespace
}  // namespace lrigid
