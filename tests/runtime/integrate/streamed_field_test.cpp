// A streamed .pvd series (frames read on demand, only those around the current time resident)
// gives bitwise the same run as the series held in memory, with at most 3 frames resident
// (4 during the step that wraps a looping series).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "compile/compile_model.h"
#include "integrate/simulation.h"
#include "support/fixture.h"

namespace lrigid {
namespace {

constexpr int kFrames = 9;  // t = 0, 0.1, ..., 0.8 s

GridGeometry geometry() {
  GridGeometry g;
  g.n[0] = g.n[1] = g.n[2] = 5;
  g.origin = Vec3::Zero();
  g.spacing = Vec3(0.5, 0.5, 0.5);
  return g;
}

// a swirling, time-varying flow with k and epsilon varying in space and time
RawGridFrame frame(int i) {
  const GridGeometry g = geometry();
  RawGridFrame f;
  f.time = 0.1 * i;
  const size_t np = g.points();
  f.U.resize(3 * np);
  f.k.resize(np);
  f.epsilon.resize(np);
  f.valid.assign(np, 1);
  for (size_t p = 0; p < np; ++p) {
    const double x = 0.5 * double(p % 5), y = 0.5 * double((p / 5) % 5);
    const double z = 0.5 * double(p / 25);
    f.U[3 * p] = float(0.3 * std::sin(3 * f.time + y));
    f.U[3 * p + 1] = float(0.2 * std::cos(5 * f.time + z));
    f.U[3 * p + 2] = float(0.1 * std::sin(x - 4 * f.time));
    f.k[p] = float(0.02 + 0.01 * std::sin(x + y + 7 * f.time));
    f.epsilon[p] = float(0.01 + 0.004 * std::cos(z + 2 * f.time));
  }
  return f;
}

struct StreamOutcome {
  State state;
  StreamStats stats;
  size_t max_resident_seen = 0;  // at every output
};

StreamOutcome run(bool streamed, TimeMode mode, Integrator integrator, double duration) {
  Scene s = test::sphere_scene(0.002, 1000, 1.2, 1.5e-5, 64);
  s.effects = test::effects({Effect::AddedMass, Effect::Drag, Effect::MeanFlow,
                             Effect::Turbulence});
  s.bodies[0].spawn_in_box = true;
  s.bodies[0].box_lo = Vec3(0.8, 0.8, 0.8);
  s.bodies[0].box_hi = Vec3(1.2, 1.2, 1.2);
  s.integrator = integrator;
  s.dt = 0.01;  // frame times fall on steps
  s.duration = duration;
  std::vector<double> times;
  std::vector<RawGridFrame> frames;
  for (int i = 0; i < kFrames; ++i) {
    frames.push_back(frame(i));
    times.push_back(frames.back().time);
  }
  FluidField f = streamed ? FluidField::streamed(geometry(), times,
                                                 [](size_t i) { return frame(int(i)); },
                                                 1.5e-5, s.drift, mode)
                          : FluidField::grid(geometry(), frames, 1.5e-5, s.drift, mode);
  const Model m = test::compile(s, std::move(f));
  StreamOutcome r;
  r.state = initial_state(m, s);
  RunOptions opt;
  opt.every = 0.25;  // outputs between frame times
  opt.threads = 2;
  opt.on_output = [&](const State&) {
    r.max_resident_seen = std::max(r.max_resident_seen, m.field.resident_frames());
  };
  simulate(m, &r.state, opt);
  r.stats = m.field.stream_stats();
  return r;
}

void expect_same(const State& a, const State& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(a.x[i].data(), b.x[i].data(), sizeof(Vec3)), 0) << "body " << i;
    EXPECT_EQ(std::memcmp(a.v[i].data(), b.v[i].data(), sizeof(Vec3)), 0) << "body " << i;
    EXPECT_EQ(std::memcmp(a.q[i].coeffs().data(), b.q[i].coeffs().data(), sizeof(Quat)), 0);
    EXPECT_EQ(a.status[i], b.status[i]) << "body " << i;
  }
}

TEST(StreamedField, ClampSeriesGivesTheInMemoryRunWithAtMostThreeFramesResident) {
  for (const Integrator in : {Integrator::Splitting, Integrator::RK4}) {
    const StreamOutcome mem = run(false, TimeMode::Clamp, in, 0.8);
    const StreamOutcome str = run(true, TimeMode::Clamp, in, 0.8);
    expect_same(mem.state, str.state);
    // the bodies moved through the whole series
    size_t moving = 0;
    for (const BodyStatus st : str.state.status) moving += st == BodyStatus::Moving;
    EXPECT_GT(moving, 32u);
    EXPECT_LE(str.stats.max_resident, 3u);
    EXPECT_LE(str.max_resident_seen, 3u);
    EXPECT_GE(str.max_resident_seen, 2u);
    // time only advances: every frame read once
    EXPECT_EQ(str.stats.loads, size_t(kFrames));
    EXPECT_EQ(mem.stats.loads, 0u);
  }
}

TEST(StreamedField, LoopingSeriesRereadsFramesAndStillMatches) {
  // 1.7 s over a 0.8 s loop: the series wraps twice, frames are read again after each wrap
  const StreamOutcome mem = run(false, TimeMode::Loop, Integrator::Splitting, 1.7);
  const StreamOutcome str = run(true, TimeMode::Loop, Integrator::Splitting, 1.7);
  expect_same(mem.state, str.state);
  // the step that wraps needs the last two frames and the first two
  EXPECT_LE(str.stats.max_resident, 4u);
  EXPECT_GT(str.stats.loads, size_t(2 * kFrames - 2));
}

TEST(StreamedField, StretchesStopAtFrameTimes) {
  std::vector<double> times = {0, 0.1, 0.2};
  const FluidField f = FluidField::streamed(
      geometry(), times, [](size_t i) { return frame(int(i)); }, 1.5e-5, Drift::Stationary,
      TimeMode::Clamp);
  EXPECT_EQ(f.next_frame_time(0.0), 0.1);
  EXPECT_EQ(f.next_frame_time(0.1), 0.2);
  EXPECT_EQ(f.next_frame_time(0.25), HUGE_VAL);
  EXPECT_EQ(f.resident_frames(), 1u);  // the first, for the initial state
  f.prepare(0.12, 0.18);
  EXPECT_EQ(f.resident_frames(), 2u);
  f.prepare(0.05, 0.15);  // across t = 0.1: three frames
  EXPECT_EQ(f.resident_frames(), 3u);
  FluidSample out;
  EXPECT_TRUE(f.sample(Vec3(1, 1, 1), 0.07, false, &out));
}

}  // namespace
}  // namespace lrigid
